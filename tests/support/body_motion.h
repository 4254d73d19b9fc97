// Test fixtures: exact motions of FloatingBody3d states (runtime/bodies/floating_body.h) and
// difference quotients along them, for checking Jacobians and velocity-quadratic terms.
//
// Under constant velocities z = [v, w, qdot] (body components) the positions move as
//   A(t) = A0 exp(t w~)                 (dA/dt = A w~),
//   p(t) = p0 (x) (cos(|w| t / 2), sin(|w| t / 2) w / |w|)   (dp/dt = 1/2 p (x) (0, w)),
//   r(t) = r0 + A0 S(t) v,   S(t) = int_0^t exp(s w~) ds
//        = t E + (1 - cos |w| t) / |w|^2 w~ + (t - sin(|w| t) / |w|) / |w|^2 w~^2,
//   q(t) = q0 + t qdot.
// Along it dz/dt = 0, so any f(positions) has df/dt = (its Jacobian) z and d2f/dt2 = (its
// velocity-quadratic bias): the "J z" and "bias" of a constraint or a marker.
#pragma once

#include <cmath>
#include <functional>
#include <random>

#include <Eigen/Dense>

#include "runtime/bodies/rotation.h"

namespace ffriga::test {

// Positions s_p (7 + nq) after time t from sp under the constant velocities sv (6 + nq).
inline Eigen::VectorXd flowPositions(const Eigen::VectorXd& sp, const Eigen::VectorXd& sv,
                                     double t) {
  const int nq = static_cast<int>(sp.size()) - 7;
  const Eigen::Vector3d v = sv.head<3>(), w = sv.segment<3>(3);
  const double th = w.norm();
  const Eigen::Matrix3d W = skew(w);
  Eigen::Matrix3d S;
  double c, s;  // cos(|w| t / 2) and sin(|w| t / 2) / |w|
  if (th * std::abs(t) < 1e-3) {
    // Taylor series to the order whose remainder is below round-off ((th t)^6 < 1e-18).
    const double x2 = th * th * t * t;
    S = t * Eigen::Matrix3d::Identity() + t * t * (0.5 - x2 / 24.0 + x2 * x2 / 720.0) * W +
        t * t * t * (1.0 / 6.0 - x2 / 120.0 + x2 * x2 / 5040.0) * W * W;
    c = 1.0 - x2 / 8.0 + x2 * x2 / 384.0;
    s = 0.5 * t * (1.0 - x2 / 24.0 + x2 * x2 / 1920.0);
  } else {
    S = t * Eigen::Matrix3d::Identity() + (1.0 - std::cos(th * t)) / (th * th) * W +
        (t - std::sin(th * t) / th) / (th * th) * W * W;
    c = std::cos(0.5 * th * t);
    s = std::sin(0.5 * th * t) / th;
  }
  Eigen::VectorXd out = sp;
  const Eigen::Matrix3d A0 = rotationMatrix(sp.data() + 3);
  out.head<3>() = sp.head<3>() + A0 * (S * v);
  const double a0 = sp(3);
  const Eigen::Vector3d a = sp.segment<3>(4), b = s * w;
  out(3) = a0 * c - a.dot(b);
  out.segment<3>(4) = a0 * b + c * a + a.cross(b);
  if (nq > 0) out.tail(nq) = sp.tail(nq) + t * sv.tail(nq);
  return out;
}

// Fourth-order central difference quotients of f at t = 0 with step h: the first
// derivative (error h^4 f^(5) / 30) and the second (error h^4 f^(6) / 90).
inline Eigen::VectorXd firstDerivative(const std::function<Eigen::VectorXd(double)>& f, double h) {
  return (f(-2 * h) - 8.0 * f(-h) + 8.0 * f(h) - f(2 * h)) / (12.0 * h);
}
inline Eigen::VectorXd secondDerivative(const std::function<Eigen::VectorXd(double)>& f, double h) {
  return (-f(-2 * h) + 16.0 * f(-h) - 30.0 * f(0.0) + 16.0 * f(h) - f(2 * h)) / (12.0 * h * h);
}

// Random numbers from a generator the test owns (so that a test's draws do not depend on,
// or change, those of other tests): a uniform number in [a, b], a random unit quaternion
// (scalar first), a matrix with entries in [-a, a] and a random rotation matrix.
inline double uniform(std::mt19937& g, double a, double b) {
  return std::uniform_real_distribution<double>(a, b)(g);
}
inline Eigen::Vector4d randomQuaternion(std::mt19937& g) {
  Eigen::Vector4d p(uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1));
  return p.normalized();
}
inline Eigen::MatrixXd randomMatrix(std::mt19937& g, int rows, int cols, double a = 1.0) {
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) m(i, j) = uniform(g, -a, a);
  return m;
}
inline Eigen::Matrix3d randomRotation(std::mt19937& g) {
  const Eigen::Vector4d p = randomQuaternion(g);
  return rotationMatrix(p.data());
}

}  // namespace ffriga::test
