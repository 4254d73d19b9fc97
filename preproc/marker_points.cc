#include "preproc/marker_points.h"

#include "common/error.h"

namespace ffriga {

namespace {

void checkInside(const SplineSpace& space, const std::string& name, const std::vector<double>& xi) {
  const int d = space.paramDim();
  if (static_cast<int>(xi.size()) != d) {
    throw InputError(Str() << "marker '" << name << "': expected " << d << " parameters, found "
                           << xi.size());
  }
  for (int a = 0; a < d; ++a) {
    double lo = 1e300, hi = -1e300;
    for (int e = 0; e < space.numElements(); ++e) {
      lo = std::min(lo, space.element(e).lower[a]);
      hi = std::max(hi, space.element(e).upper[a]);
    }
    if (xi[a] < lo || xi[a] > hi) {
      throw InputError(Str() << "marker '" << name << "': parameter " << a << " = " << xi[a]
                             << " lies outside the domain [" << lo << ", " << hi << "]");
    }
  }
}

}  // namespace

Marker evaluateMarker(const SplineSpace& space, const std::string& name,
                      const std::vector<double>& xi) {
  checkInside(space, name, xi);
  PatchBasis basis;
  space.elementBasis(space.findElement(xi.data()), xi.data(), 0, basis);
  Marker m;
  m.name = name;
  m.functions = basis.index;
  m.values = basis.table.row(0).transpose();
  m.position = Eigen::VectorXd::Zero(space.spaceDim());
  for (std::size_t j = 0; j < basis.index.size(); ++j)
    m.position += m.values(j) * space.controlPoints().row(basis.index[j]).transpose();
  return m;
}

Eigen::MatrixXd tangentFrameConditions(const SplineSpace& space, const DofMap& dofs,
                                       const std::vector<double>& xi, bool axisymmetric) {
  checkInside(space, "frame marker", xi);
  const int d = space.paramDim();
  PatchBasis basis;
  space.elementBasis(space.findElement(xi.data()), xi.data(), 1, basis);
  const int nb = static_cast<int>(basis.index.size());
  const Eigen::MatrixXd& P = space.controlPoints();
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(axisymmetric ? 1 : 6, dofs.numDofs());
  auto add = [&](int row, int k, int c, double v) {
    const int dof = dofs.dof(k, c);
    if (dof >= 0) C(row, dof) += v;
  };
  if (axisymmetric) {
    for (int j = 0; j < nb; ++j) add(0, basis.index[j], 1, basis.table(0, j));
    return C;
  }
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int j = 0; j < nb; ++j)
    for (int a = 0; a < d; ++a)
      J.col(a) += basis.table(1 + a, j) * P.row(basis.index[j]).transpose();
  if (!(std::abs(J.determinant()) > 1e-14 * J.norm() * J.norm() * J.norm())) {
    throw InputError(
        "tangent frame: the geometry map is singular at the frame marker; choose a "
        "marker away from the axis, poles and collapsed edges");
  }
  const Eigen::Matrix3d Jinv = J.inverse();
  for (int j = 0; j < nb; ++j) {
    const int k = basis.index[j];
    Eigen::Vector3d g = Eigen::Vector3d::Zero();  // physical gradient of R_k
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a) g(c) += Jinv(a, c) * basis.table(1 + a, j);
    for (int c = 0; c < 3; ++c) add(c, k, c, basis.table(0, j));
    // w = 1/2 (d_y u_z - d_z u_y, d_z u_x - d_x u_z, d_x u_y - d_y u_x)
    add(3, k, 2, 0.5 * g(1));
    add(3, k, 1, -0.5 * g(2));
    add(4, k, 0, 0.5 * g(2));
    add(4, k, 2, -0.5 * g(0));
    add(5, k, 1, 0.5 * g(0));
    add(5, k, 0, -0.5 * g(1));
  }
  return C;
}

}  // namespace ffriga
