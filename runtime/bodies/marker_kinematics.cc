#include "runtime/bodies/marker_kinematics.h"

#include "runtime/bodies/rotation.h"

namespace ffriga {

void markerPoint(const FloatingBody3d& body, const double* sp, const double* sv,
                 const BodyMarker& m, MarkerKinematics& k) {
  const int nq = body.nq();
  const Eigen::Matrix3d A = rotationMatrix(sp + 3);
  const Eigen::Map<const Eigen::Vector3d> r(sp), v(sv), w(sv + 3);
  Eigen::Vector3d p = m.x0, phiQd = Eigen::Vector3d::Zero();
  if (nq > 0) {
    p += m.Phi * Eigen::Map<const Eigen::VectorXd>(sp + 7, nq);
    phiQd = m.Phi * Eigen::Map<const Eigen::VectorXd>(sv + 6, nq);
  }
  k.value = r + A * p;
  k.G.resize(3, 6 + nq);
  k.G.leftCols<3>() = A;
  k.G.middleCols<3>(3) = -A * skew(p);
  if (nq > 0) k.G.rightCols(nq) = A * m.Phi;
  k.rate = A * (v + w.cross(p) + phiQd);
  k.bias = A * (w.cross(v) + w.cross(w.cross(p)) + 2.0 * w.cross(phiQd));
}

void markerVector(const FloatingBody3d& body, const double* sp, const double* sv,
                  const BodyMarker& m, const Eigen::Vector3d& u0, MarkerKinematics& k) {
  const int nq = body.nq();
  const Eigen::Matrix3d A = rotationMatrix(sp + 3);
  const Eigen::Map<const Eigen::Vector3d> w(sv + 3);
  Eigen::Vector3d u = u0, du = Eigen::Vector3d::Zero();
  if (nq > 0) {
    const Eigen::Vector3d theta = m.Psi * Eigen::Map<const Eigen::VectorXd>(sp + 7, nq);
    const Eigen::Vector3d thetaDot = m.Psi * Eigen::Map<const Eigen::VectorXd>(sv + 6, nq);
    u += theta.cross(u0);
    du = thetaDot.cross(u0);
  }
  k.value = A * u;
  k.G.setZero(3, 6 + nq);
  k.G.middleCols<3>(3) = -A * skew(u);
  if (nq > 0) k.G.rightCols(nq) = -A * skew(u0) * m.Psi;
  k.rate = A * (w.cross(u) + du);
  k.bias = A * (w.cross(w.cross(u)) + 2.0 * w.cross(du));
}

void groundKinematics(const Eigen::Vector3d& value, MarkerKinematics& k) {
  k.value = value;
  k.rate.setZero();
  k.bias.setZero();
  k.G.resize(3, 0);
}

void addMarkerForce(const FloatingBody3d& body, const double* sp, const BodyMarker& m,
                    const Eigen::Vector3d& f, double* h) {
  const int nq = body.nq();
  const Eigen::Vector3d fb = rotationMatrix(sp + 3).transpose() * f;
  Eigen::Vector3d p = m.x0;
  if (nq > 0) p += m.Phi * Eigen::Map<const Eigen::VectorXd>(sp + 7, nq);
  Eigen::Map<Eigen::Vector3d>(h) += fb;
  Eigen::Map<Eigen::Vector3d>(h + 3) += p.cross(fb);
  if (nq > 0) Eigen::Map<Eigen::VectorXd>(h + 6, nq) += m.Phi.transpose() * fb;
}

}  // namespace ffriga
