#include "preproc/reduction/pressure_patches.h"

#include <cmath>

#include "common/base/error.h"
#include "common/splines/extracted_surface.h"

namespace ffriga {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The centre's surface parameters (PressurePatchOptions::centre, or its default).
Eigen::VectorXd centreParameters(const ExtractedSurface& es, const Eigen::MatrixXd& points,
                                 bool axisymmetric, const PressurePatchOptions& o) {
  const int dc = es.dim();
  if (!o.centre.empty()) {
    if (static_cast<int>(o.centre.size()) != dc) {
      throw InputError(Str() << "pressure patches: the centre needs " << dc
                             << " surface parameter(s), found " << o.centre.size());
    }
    return Eigen::Map<const Eigen::VectorXd>(o.centre.data(), dc);
  }
  if (!axisymmetric) return 0.5 * (es.domainLower() + es.domainUpper());
  // A ring about the axis: the end of the region nearer the axis.
  SurfacePoint lo, hi;
  const Eigen::VectorXd a = es.domainLower(), b = es.domainUpper();
  es.evaluate(es.findElement(a.data()), a.data(), points, 0, lo);
  es.evaluate(es.findElement(b.data()), b.data(), points, 0, hi);
  return std::abs(lo.x(0)) <= std::abs(hi.x(0)) ? a : b;
}

// The centre's frame: outward normal n_c, tangent t_1 along the first surface parameter and
// (3D) t_2 = n_c x t_1. Throws InputError where the surface is degenerate.
struct CentreFrame {
  Eigen::VectorXd n, t1, t2;
};

CentreFrame centreFrame(const ExtractedSurface& es, const SurfacePoint& c) {
  CentreFrame f;
  f.n = es.normal(c.dx);
  f.t1 = c.dx.col(0).normalized();
  if (es.dim() == 2) f.t2 = Eigen::Vector3d(f.n).cross(Eigen::Vector3d(f.t1)).normalized();
  if (!f.n.allFinite() || !f.t1.allFinite() || !f.t2.allFinite()) {
    throw InputError(
        "pressure patches: the surface is degenerate at the centre (no tangent "
        "plane); give another reduction.pressure_patches.centre");
  }
  return f;
}

// The moments' exponents (i, j), i + j <= degree (axisymmetric: (i, 0), i <= degree).
std::vector<std::pair<int, int>> moments(int degree, bool axisymmetric) {
  std::vector<std::pair<int, int>> m;
  for (int total = 0; total <= degree; ++total)
    for (int i = total; i >= 0; --i)
      if (!axisymmetric || i == total) m.emplace_back(i, total - i);
  return m;
}

// Adds the generalized forces of the traction p dir over the collocation weight `weight`
// (m^2; N per unit pressure) at a point of element e with basis values R (row 0) to the
// interface DOFs' column F.
void addPointLoad(const ExtractedSurface& es, int e, const Eigen::MatrixXd& R, const DofMap& dofs,
                  const std::vector<int>& interface_index, double weight, double p,
                  const Eigen::VectorXd& dir, Eigen::Ref<Eigen::VectorXd> F) {
  for (int f = 0; f < es.numFunctions(e); ++f) {
    const int cp = es.functions(e)[f];
    for (int c = 0; c < dir.size(); ++c) {
      const int dof = dofs.dof(cp, c);
      const double load = weight * R(0, f) * p * dir(c);
      if (dof < 0 || load == 0.0) continue;
      if (interface_index[dof] < 0) {
        throw InputError(Str() << "pressure patches: contact surface '" << es.surface().name
                               << "' loads control point " << cp
                               << ", which is not on the Craig-Bampton interface");
      }
      F(interface_index[dof]) += load;
    }
  }
}

}  // namespace

PressurePatchLoads pressurePatchLoads(const SplineSpace& space, const DofMap& dofs,
                                      const ContactSurface& surface, bool axisymmetric,
                                      const std::vector<int>& interface_index,
                                      const PressurePatchOptions& o) {
  FFRIGA_CHECK(o.radius > 0.0 && o.radii >= 1 && o.degree >= 0, "pressure patch options");
  const ExtractedSurface es(surface, space.weights());
  const Eigen::MatrixXd& points = space.controlPoints();
  const Eigen::VectorXd sc = centreParameters(es, points, axisymmetric, o);
  const int ec = es.findElement(sc.data());
  if (ec < 0) {
    throw InputError(Str() << "pressure patches: the centre (surface parameters " << sc.transpose()
                           << ") lies outside contact surface '" << surface.name << "'");
  }
  SurfacePoint centre;
  es.evaluate(ec, sc.data(), points, 1, centre);
  // Directions: 0 the local normal, then the centre's tangents (axisymmetric: the meridian's).
  const CentreFrame frame = centreFrame(es, centre);
  std::vector<Eigen::VectorXd> tangents;
  if (o.tangential) tangents.push_back(frame.t1);
  if (o.tangential && es.dim() == 2) tangents.push_back(frame.t2);
  const int directions = 1 + static_cast<int>(tangents.size());
  const std::vector<std::pair<int, int>> mom = moments(o.degree, axisymmetric);
  const int nb = [&] {
    int n = 0;
    for (int i : interface_index) n += i >= 0;
    return n;
  }();
  const int per_radius = static_cast<int>(mom.size()) * directions;
  PressurePatchLoads out;
  out.centre = centre.x;
  std::vector<double> radii;
  for (int k = 0; k < o.radii; ++k) {
    const double a = o.radius * (k + 1 - o.radius_offset) / o.radii;
    if (a >= o.smallest_radius) radii.push_back(a);
  }
  out.F.setZero(nb, static_cast<int>(radii.size()) * per_radius);
  Eigen::MatrixXd R;
  SurfacePoint x;
  for (int g = 0; g < surface.collocation_points.rows(); ++g) {
    const int e = surface.collocation_element[g];
    const Eigen::VectorXd sg = surface.collocation_points.row(g).transpose();
    es.evaluate(e, sg.data(), points, 1, x);
    es.basis(e, sg.data(), 0, R);
    const Eigen::VectorXd normal = es.normal(x.dx);
    const Eigen::VectorXd dx = x.x - centre.x;
    const double r = dx.norm();
    double weight = surface.collocation_weights(g);
    if (axisymmetric) weight *= 2.0 * kPi * std::abs(x.x(0));
    for (int k = 0; k < static_cast<int>(radii.size()); ++k) {
      const double a = radii[k];
      if (r >= a) continue;
      const double hertz = std::sqrt(1.0 - (r * r) / (a * a));
      const double u = axisymmetric ? r / a : dx.dot(frame.t1) / a;
      const double v = axisymmetric ? 0.0 : dx.dot(frame.t2) / a;
      for (std::size_t m = 0; m < mom.size(); ++m) {
        const double p = hertz * std::pow(u, mom[m].first) * std::pow(v, mom[m].second);
        for (int d = 0; d < directions; ++d) {
          // Normal tractions follow the local normal; tangential ones the centre's frame.
          const Eigen::VectorXd& dir = d == 0 ? normal : tangents[d - 1];
          const int col = k * per_radius + static_cast<int>(m) * directions + d;
          addPointLoad(es, e, R, dofs, interface_index, weight, p, dir, out.F.col(col));
        }
      }
    }
  }
  return out;
}

}  // namespace ffriga
