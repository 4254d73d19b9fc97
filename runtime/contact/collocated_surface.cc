#include "runtime/contact/collocated_surface.h"

#include <algorithm>
#include <cmath>

#include "common/base/error.h"

namespace ffriga {

namespace {

// Orientation check of the SID's outward_sign (sid.h): if the normal at every collocation
// point points toward the centre of mass, the convention was mixed up. Non-convex regions
// with mixed signs pass.
void checkOutwardNormal(const CollocatedSurface& side, const BodyModel& body,
                        const ContactSurface& cs) {
  const FlexibleBodySid& sid = body.sid();
  const Eigen::VectorXd c = (sid.first_moment / sid.mass).head(side.dim);
  const int nc = side.numPoints();
  int inward = 0;
  SurfacePoint sp;
  for (int i = 0; i < nc; ++i) {
    const Eigen::VectorXd s = cs.collocation_points.row(i).transpose();
    side.surface.evaluate(cs.collocation_element[i], s.data(), side.P0, 1, sp);
    if (side.surface.normal(sp.dx).dot(sp.x - c) < 0.0) ++inward;
  }
  if (inward == nc) {
    throw InputError(Str() << "body '" << body.name() << "', surface '" << cs.name
                           << "': the outward normal (outward_sign " << cs.outward_sign
                           << ") points toward the centre of mass at every collocation point; "
                           << "expected it to point out of the body (2D rule: n = sign (t_y, "
                           << "-t_x), 3D: n = sign x_s0 x x_s1)");
  }
}

}  // namespace

void CollocatedSurface::setup(const BodyModel& body, int index) {
  const FlexibleBodySid& sid = body.sid();
  FFRIGA_CHECK(index >= 0 && index < static_cast<int>(sid.surfaces.size()),
               "surface " << index << " of body '" << body.name() << "'");
  const ContactSurface& cs = sid.surfaces[index];
  dim = body.spaceDim();
  name = cs.name;
  surface = ExtractedSurface(cs, sid.weights);
  cps = surface.allFunctions();
  P0 = sid.control_points;
  const int d = dim, nq = body.nq(), nc = static_cast<int>(cs.collocation_points.rows());
  if (nc == 0 || cs.collocation_weights.size() != nc ||
      static_cast<int>(cs.collocation_element.size()) != nc) {
    throw InputError(Str() << "body '" << body.name() << "', surface '" << cs.name << "': " << nc
                           << " collocation points, " << cs.collocation_weights.size()
                           << " weights, " << cs.collocation_element.size() << " elements");
  }
  PhiSt.resize(nq, cps.size() * d);
  for (std::size_t i = 0; i < cps.size(); ++i)
    PhiSt.middleCols(i * d, d) = sid.Phi.middleRows(cps[i] * d, d).transpose();
  xc0.resize(nc, d);
  PhiCt = Eigen::MatrixXd::Zero(nq, nc * d);
  weight.resize(nc);
  combo_offset.assign(1, 0);
  combo_local.clear();
  combo_value.clear();
  local.assign(P0.rows(), -1);
  for (std::size_t k = 0; k < cps.size(); ++k) local[cps[k]] = static_cast<int>(k);
  Eigen::MatrixXd R;
  for (int i = 0; i < nc; ++i) {
    const int e = cs.collocation_element[i];
    FFRIGA_CHECK(e >= 0 && e < surface.numElements(), "collocation element " << e);
    const Eigen::VectorXd s = cs.collocation_points.row(i).transpose();
    surface.basis(e, s.data(), 0, R);
    xc0.row(i).setZero();
    for (int k = 0; k < surface.numFunctions(e); ++k) {
      const int f = surface.functions(e)[k];
      xc0.row(i) += R(0, k) * P0.row(f);
      PhiCt.middleCols(i * d, d) += R(0, k) * sid.Phi.middleRows(f * d, d).transpose();
      combo_local.push_back(local[f]);
      combo_value.push_back(R(0, k));
    }
    combo_offset.push_back(static_cast<int>(combo_local.size()));
    const double ring = d == 2 ? 2.0 * M_PI * xc0(i, 0) : 1.0;
    weight(i) = cs.collocation_weights(i) * ring;
  }
  checkOutwardNormal(*this, body, cs);
}

Eigen::VectorXd CollocatedSurface::bodyPoint(int i, const Eigen::VectorXd& u) const {
  SpaceVector xb;
  bodyPoint(i, u, xb);
  return xb;
}

void CollocatedSurface::bodyPoint(int i, const Eigen::VectorXd& u, SpaceVector& xb) const {
  xb = xc0.row(i).transpose();
  if (u.size() == 0) return;
  for (int k = combo_offset[i]; k < combo_offset[i + 1]; ++k)
    xb += combo_value[k] * u.segment(combo_local[k] * dim, dim);
}

Eigen::VectorXd CollocatedSurface::pointDisplacement(int i, const Eigen::VectorXd& u) const {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(dim);
  if (u.size() == 0) return d;
  for (int k = combo_offset[i]; k < combo_offset[i + 1]; ++k)
    d += combo_value[k] * u.segment(combo_local[k] * dim, dim);
  return d;
}

double CollocatedSurface::size() const {
  Eigen::MatrixXd P(cps.size(), dim);
  for (std::size_t i = 0; i < cps.size(); ++i) P.row(i) = P0.row(cps[i]);
  return (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
}

bool CollocatedSurface::planar() const {
  const SurfacePoint c = centre(P0);
  const Eigen::VectorXd n = surface.normal(c.dx);
  double off = 0.0;
  for (const int k : cps) off = std::max(off, std::abs(n.dot(P0.row(k).transpose() - c.x)));
  return off <= 1e-12 * size();
}

SurfacePoint CollocatedSurface::centre(const Eigen::MatrixXd& points) const {
  SurfacePoint sp;
  centre(points, sp);
  return sp;
}

void CollocatedSurface::centre(const Eigen::MatrixXd& points, SurfacePoint& sp) const {
  const ParamVector mid = 0.5 * (surface.domainLower() + surface.domainUpper());
  int e = surface.findElement(mid.data());
  if (e < 0) e = 0;
  surface.evaluate(e, mid.data(), points, 1, sp);
}

}  // namespace ffriga
