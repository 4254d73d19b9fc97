// Rotations of the body frame: unit quaternions p = (p0, p1, p2, p3) (scalar first) and the
// rotation matrix A (body -> inertial components, r = r_R + A x).
//
//   A = (p0^2 - |p_v|^2) E + 2 p_v p_v^T + 2 p0 p_v~,
//   dp/dt = 1/2 p (x) (0, w)  with w the angular velocity in body components:
//   dp0/dt = -1/2 p_v . w,  dp_v/dt = 1/2 (p0 w + p_v x w).
// The exact flow keeps |p| = 1; A is built from p / |p| so that round-off drift of |p| never
// distorts the body. Skew matrix: a~ b = a x b.
#pragma once

#include <Eigen/Dense>

namespace ffriga {

inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0.0, -a(2), a(1), a(2), 0.0, -a(0), -a(1), a(0), 0.0;
  return s;
}

inline Eigen::Matrix3d rotationMatrix(const double* p) {
  Eigen::Vector4d u(p[0], p[1], p[2], p[3]);
  u /= u.norm();
  const Eigen::Vector3d v = u.tail<3>();
  return (u(0) * u(0) - v.squaredNorm()) * Eigen::Matrix3d::Identity() + 2.0 * v * v.transpose() +
         2.0 * u(0) * skew(v);
}

inline void quaternionRate(const double* p, const Eigen::Vector3d& w, double* pdot) {
  const Eigen::Vector3d v(p[1], p[2], p[3]);
  pdot[0] = -0.5 * v.dot(w);
  const Eigen::Vector3d r = 0.5 * (p[0] * w + v.cross(w));
  pdot[1] = r(0);
  pdot[2] = r(1);
  pdot[3] = r(2);
}

}  // namespace ffriga
