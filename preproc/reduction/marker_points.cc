#include "preproc/reduction/marker_points.h"

#include <map>

#include "common/base/error.h"
#include "common/splines/gauss_legendre.h"

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

namespace {

// Physical gradients of the basis functions at xi (3D): row j = grad R_{index[j]}.
struct BasisGradients {
  PatchBasis basis;
  Eigen::MatrixXd grad;  // n x 3
};

BasisGradients basisGradients(const SplineSpace& space, const std::string& name,
                              const std::vector<double>& xi) {
  checkInside(space, name, xi);
  const int d = space.paramDim();
  BasisGradients out;
  PatchBasis& basis = out.basis;
  space.elementBasis(space.findElement(xi.data()), xi.data(), 1, basis);
  const int nb = static_cast<int>(basis.index.size());
  const Eigen::MatrixXd& P = space.controlPoints();
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int j = 0; j < nb; ++j)
    for (int a = 0; a < d; ++a)
      J.col(a) += basis.table(1 + a, j) * P.row(basis.index[j]).transpose();
  if (!(std::abs(J.determinant()) > 1e-14 * J.norm() * J.norm() * J.norm())) {
    throw InputError(Str() << "marker '" << name << "': the geometry map is singular there; "
                           << "choose a marker away from the axis, poles and collapsed edges");
  }
  const Eigen::Matrix3d Jinv = J.inverse();
  out.grad.resize(nb, 3);
  for (int j = 0; j < nb; ++j)
    for (int c = 0; c < 3; ++c) {
      out.grad(j, c) = 0.0;
      for (int a = 0; a < 3; ++a) out.grad(j, c) += Jinv(a, c) * basis.table(1 + a, j);
    }
  return out;
}

}  // namespace

Eigen::MatrixXd markerRotationModes(const SplineSpace& space, const std::string& name,
                                    const std::vector<double>& xi, const Eigen::MatrixXd& Phi) {
  FFRIGA_CHECK(space.spaceDim() == 3, "rotation modes need a 3D body");
  const BasisGradients g = basisGradients(space, name, xi);
  Eigen::MatrixXd Psi = Eigen::MatrixXd::Zero(3, Phi.cols());
  for (std::size_t j = 0; j < g.basis.index.size(); ++j) {
    const Eigen::Vector3d gk = g.grad.row(static_cast<int>(j)).transpose();
    Eigen::Matrix3d S;
    S << 0.0, -gk(2), gk(1), gk(2), 0.0, -gk(0), -gk(1), gk(0), 0.0;
    Psi += 0.5 * S * Phi.middleRows(3 * g.basis.index[j], 3);
  }
  return Psi;
}

namespace {

// A quadrature point of a face: weight dA, position, basis values.
struct FacePoint {
  double dA;
  Eigen::Vector3d x;
  std::vector<int> index;
  Eigen::VectorXd R;
};

// The parameter of the face xi_direction = front (lower) or back (upper) of the domain.
double faceParameter(const SplineSpace& space, int direction, bool upper) {
  double lo = 1e300, hi = -1e300;
  for (int e = 0; e < space.numElements(); ++e) {
    lo = std::min(lo, space.element(e).lower[direction]);
    hi = std::max(hi, space.element(e).upper[direction]);
  }
  return upper ? hi : lo;
}

// The Gauss points of the face elements (gauss_points per direction), element by element.
std::vector<FacePoint> faceQuadrature(const SplineSpace& space, int direction, bool upper,
                                      double face, int gauss_points) {
  const int a0 = (direction + 1) % 3, a1 = (direction + 2) % 3;
  const Eigen::MatrixXd& P = space.controlPoints();
  std::vector<FacePoint> points;
  PatchBasis basis;
  for (int e = 0; e < space.numElements(); ++e) {
    const ElementBox box = space.element(e);
    if ((upper ? box.upper[direction] : box.lower[direction]) != face) continue;
    const int n0 = gauss_points, n1 = gauss_points;
    const QuadratureRule g0 = gaussLegendre(n0, box.lower[a0], box.upper[a0]);
    const QuadratureRule g1 = gaussLegendre(n1, box.lower[a1], box.upper[a1]);
    for (int i = 0; i < n0; ++i)
      for (int j = 0; j < n1; ++j) {
        double xi[3];
        xi[direction] = face;
        xi[a0] = g0.points[i];
        xi[a1] = g1.points[j];
        space.elementBasis(e, xi, 1, basis);
        FacePoint fp;
        fp.x.setZero();
        Eigen::Vector3d t0 = Eigen::Vector3d::Zero(), t1 = Eigen::Vector3d::Zero();
        for (std::size_t k = 0; k < basis.index.size(); ++k) {
          const Eigen::Vector3d pk = P.row(basis.index[k]).transpose();
          fp.x += basis.table(0, static_cast<int>(k)) * pk;
          t0 += basis.table(1 + a0, static_cast<int>(k)) * pk;
          t1 += basis.table(1 + a1, static_cast<int>(k)) * pk;
        }
        fp.dA = t0.cross(t1).norm() * g0.weights[i] * g1.weights[j];
        fp.index = basis.index;
        fp.R = basis.table.row(0).transpose();
        points.push_back(std::move(fp));
      }
  }
  return points;
}

// About the centroid xc of the face (area A): its area moment of inertia I_A, and per
// function w_k = int R_k dA / A and the moment int R_k r~ dA.
Eigen::Matrix3d faceMoments(const std::vector<FacePoint>& points, const Eigen::Vector3d& xc,
                            double A, std::map<int, double>& w,
                            std::map<int, Eigen::Matrix3d>& moment) {
  Eigen::Matrix3d IA = Eigen::Matrix3d::Zero();
  for (const FacePoint& fp : points) {
    const Eigen::Vector3d r = fp.x - xc;
    IA += fp.dA * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    Eigen::Matrix3d rs;
    rs << 0.0, -r(2), r(1), r(2), 0.0, -r(0), -r(1), r(0), 0.0;
    for (std::size_t k = 0; k < fp.index.size(); ++k) {
      const double Rk = fp.R(static_cast<int>(k));
      if (Rk == 0.0) continue;
      w[fp.index[k]] += Rk * fp.dA / A;
      auto it = moment.emplace(fp.index[k], Eigen::Matrix3d::Zero()).first;
      it->second += Rk * fp.dA * rs;
    }
  }
  return IA;
}

}  // namespace

Marker evaluateFaceMarker(const SplineSpace& space, const std::string& name, int direction,
                          bool upper, int gauss_points, const Eigen::MatrixXd& Phi) {
  FFRIGA_CHECK(space.spaceDim() == 3 && space.paramDim() == 3, "face markers need a 3D body");
  const double face = faceParameter(space, direction, upper);
  const std::vector<FacePoint> points = faceQuadrature(space, direction, upper, face, gauss_points);
  double A = 0.0;
  Eigen::Vector3d xc = Eigen::Vector3d::Zero();
  for (const FacePoint& fp : points) A += fp.dA, xc += fp.dA * fp.x;
  if (!(A > 0.0))
    throw InputError(Str() << "marker '" << name << "': the face has no area (a collapsed face)");
  xc /= A;
  std::map<int, double> w;                // int R_k dA / A
  std::map<int, Eigen::Matrix3d> moment;  // int R_k r~ dA
  const Eigen::Matrix3d IA = faceMoments(points, xc, A, w, moment);
  const Eigen::LDLT<Eigen::Matrix3d> IAinv(IA);
  Marker m;
  m.name = name;
  m.position = xc;
  m.values.resize(static_cast<int>(w.size()));
  m.Psi = Eigen::MatrixXd::Zero(3, Phi.cols());
  int j = 0;
  for (const auto& [k, wk] : w) {
    m.functions.push_back(k);
    m.values(j++) = wk;
    if (Phi.cols() > 0) m.Psi += IAinv.solve(moment.at(k)) * Phi.middleRows(3 * k, 3);
  }
  return m;
}

Eigen::MatrixXd tangentFrameConditions(const SplineSpace& space, const DofMap& dofs,
                                       const std::vector<double>& xi, bool axisymmetric) {
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(axisymmetric ? 1 : 6, dofs.numDofs());
  auto add = [&](int row, int k, int c, double v) {
    const int dof = dofs.dof(k, c);
    if (dof >= 0) C(row, dof) += v;
  };
  if (axisymmetric) {
    checkInside(space, "frame marker", xi);
    PatchBasis basis;
    space.elementBasis(space.findElement(xi.data()), xi.data(), 0, basis);
    for (std::size_t j = 0; j < basis.index.size(); ++j)
      add(0, basis.index[j], 1, basis.table(0, static_cast<int>(j)));
    return C;
  }
  const BasisGradients bg = basisGradients(space, "frame marker", xi);
  const PatchBasis& basis = bg.basis;
  for (std::size_t j = 0; j < basis.index.size(); ++j) {
    const int k = basis.index[j];
    const Eigen::Vector3d g = bg.grad.row(static_cast<int>(j)).transpose();
    for (int c = 0; c < 3; ++c) add(c, k, c, basis.table(0, static_cast<int>(j)));
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
