#include "preproc/geometry/geometry_builders.h"

#include <cmath>

#include "common/base/error.h"

namespace ffriga {

namespace {

// Unit circle as four rational quadratic quarter arcs: control points and weights.
void unitCircle(Eigen::MatrixXd& P, Eigen::VectorXd& w) {
  const double s = std::sqrt(0.5);
  P.resize(9, 2);
  P << 1, 0, 1, 1, 0, 1, -1, 1, -1, 0, -1, -1, 0, -1, 1, -1, 1, 0;
  w.resize(9);
  w << 1, s, 1, s, 1, s, 1, s, 1;
}

KnotVector circleKnots() {
  return KnotVector({0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}, 2);
}

// Rotation taking the unit vector a onto the unit vector b (Rodrigues); b = -a: the half
// turn about an axis normal to a.
Eigen::Matrix3d rotationOnto(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d v = a.cross(b);
  const double c = a.dot(b);
  if (c < -1.0 + 1e-12) {
    const Eigen::Vector3d axis = a.unitOrthogonal();
    return 2.0 * axis * axis.transpose() - Eigen::Matrix3d::Identity();
  }
  Eigen::Matrix3d K;
  K << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return Eigen::Matrix3d::Identity() + K + K * K / (1.0 + c);
}

void checkPositive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(Str() << what << " must be a positive number, found " << value);
  }
}

}  // namespace

NurbsPatch halfDisk(double r) {
  checkPositive(r, "radius");
  // Eq. (19), P(i, j) with i along xi (3 points), j along eta (2 points).
  Eigen::MatrixXd P(6, 2);
  Eigen::VectorXd w(6);
  const double s = std::sqrt(0.5);
  // j = 0 (lower arc), i = 0, 1, 2
  P.row(0) << 0, -r;
  P.row(1) << r, -r;
  P.row(2) << r, 0;
  // j = 1 (upper arc)
  P.row(3) << 0, r;
  P.row(4) << r, r;
  P.row(5) << r, 0;
  w << 1, s, 1, 1, s, 1;
  return NurbsPatch({KnotVector({0, 0, 0, 1, 1, 1}, 2), KnotVector({0, 0, 1, 1}, 1)}, P, w);
}

NurbsPatch solidSphere(double r, const Eigen::Vector3d& direction) {
  checkPositive(r, "radius");
  const NurbsPatch disk = halfDisk(r);
  Eigen::MatrixXd C;
  Eigen::VectorXd wc;
  unitCircle(C, wc);
  const int nd = disk.numControlPoints();
  Eigen::MatrixXd P(nd * 9, 3);
  Eigen::VectorXd w(nd * 9);
  // Revolve (x, y) about the y axis: (x cos t, y, x sin t); weights multiply.
  for (int k = 0; k < 9; ++k) {
    for (int a = 0; a < nd; ++a) {
      const double x = disk.points()(a, 0);
      const double y = disk.points()(a, 1);
      P.row(a + nd * k) << x * C(k, 0), y, x * C(k, 1);
      w(a + nd * k) = disk.weights()(a) * wc(k);
    }
  }
  NurbsPatch sphere({disk.knots(0), disk.knots(1), circleKnots()}, P, w);
  // Rotate the designated contact point onto the direction.
  if (!(direction.norm() > 0.0))
    throw std::invalid_argument("the sphere's contact direction is zero");
  const Eigen::Vector3d c = sphere.evaluate(kSphereContactXi).x.normalized();
  const Eigen::Matrix3d R = rotationOnto(c, direction.normalized());
  Eigen::MatrixXd Q = P * R.transpose();
  return NurbsPatch(sphere.knotVectors(), Q, w);
}

NurbsPatch solidRod(double radius, double length) {
  checkPositive(radius, "radius");
  checkPositive(length, "length");
  const double c = radius * std::sqrt(0.5);
  const double e = radius * std::sqrt(2.0);
  const double s = std::sqrt(0.5);
  Eigen::MatrixXd D(9, 2);
  D << -c, -c, 0, -e, c, -c,  //
      -e, 0, 0, 0, e, 0,      //
      -c, c, 0, e, c, c;
  Eigen::VectorXd wd(9);
  wd << 1, s, 1, s, 1, s, 1, s, 1;
  Eigen::MatrixXd P(18, 3);
  Eigen::VectorXd w(18);
  for (int k = 0; k < 2; ++k) {
    for (int a = 0; a < 9; ++a) {
      P.row(a + 9 * k) << D(a, 0), D(a, 1), k * length;
      w(a + 9 * k) = wd(a);
    }
  }
  const KnotVector q2({0, 0, 0, 1, 1, 1}, 2);
  return NurbsPatch({q2, q2, KnotVector({0, 0, 1, 1}, 1)}, P, w);
}

}  // namespace ffriga
