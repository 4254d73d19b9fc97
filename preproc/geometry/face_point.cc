#include "preproc/geometry/face_point.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/base/error.h"
#include "common/splines/rational_basis.h"

namespace ffriga {

namespace {

// A point is degenerate when its face Jacobian is below this times size^(d-1).
constexpr double kDegenerateJacobian = 1e-9;

// The direction into the body at the point: the face-normal parametric derivative pointed
// inwards, or, where it vanishes (a collapsed direction), towards the control points'
// centroid.
Eigen::VectorXd inwardDirection(const NurbsPatch& patch, const PatchPoint& p, int n, bool upper,
                                double size) {
  Eigen::VectorXd v = p.dx.col(n) * (upper ? -1.0 : 1.0);
  if (v.norm() > kDegenerateJacobian * size) return v;
  return patch.points().colwise().mean().transpose() - p.x;
}

}  // namespace

bool FacePoint::degenerate() const {
  const int d = static_cast<int>(x.size());
  return !(jacobian > kDegenerateJacobian * std::pow(size, d - 1));
}

FacePoint facePoint(const NurbsPatch& patch, int face_direction, bool face_upper,
                    std::vector<double> xi) {
  const int d = patch.paramDim();
  if (d != patch.spaceDim() || d < 2)
    throw std::invalid_argument("face points need a 2D section or a 3D solid patch");
  const KnotVector& kn = patch.knots(face_direction);
  xi[face_direction] = face_upper ? kn.back() : kn.front();
  const PatchPoint p = patch.evaluate(xi.data(), 2);
  FacePoint f;
  f.x = p.x;
  f.size = (patch.points().colwise().maxCoeff() - patch.points().colwise().minCoeff()).norm();
  std::vector<int> along;
  for (int a = 0; a < d; ++a)
    if (a != face_direction) along.push_back(a);
  for (int a : along) f.tangents.push_back(p.dx.col(a));
  Eigen::VectorXd n(d);
  if (d == 2) {
    const Eigen::VectorXd& t = f.tangents[0];
    n << t(1), -t(0);
  } else {
    n = Eigen::Vector3d(f.tangents[0]).cross(Eigen::Vector3d(f.tangents[1]));
  }
  f.jacobian = n.norm();
  if (f.degenerate()) return f;
  n /= f.jacobian;
  if (n.dot(inwardDirection(patch, p, face_direction, face_upper, f.size)) > 0.0) n = -n;
  f.normal = n;
  // Fundamental forms over the face's directions.
  const int m = d - 1;
  Eigen::MatrixXd I(m, m), II(m, m);
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) {
      I(a, b) = f.tangents[a].dot(f.tangents[b]);
      const int col = secondDerivativeRow(d, along[a], along[b]) - 1 - d;
      II(a, b) = -n.dot(p.ddx.col(col));
    }
  }
  // I^-1 II is self-adjoint in I's inner product: the generalised symmetric eigenproblem.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(II, I);
  for (int a = 0; a < m; ++a) f.curvatures.push_back(eig.eigenvalues()(a));
  if (m < 2) return f;
  for (int a = 0; a < m; ++a) {
    Eigen::VectorXd t = Eigen::VectorXd::Zero(d);
    for (int b = 0; b < m; ++b) t += eig.eigenvectors()(b, a) * f.tangents[b];
    f.directions.push_back(t.normalized());
  }
  return f;
}

}  // namespace ffriga
