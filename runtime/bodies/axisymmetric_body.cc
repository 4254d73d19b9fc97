#include "runtime/bodies/axisymmetric_body.h"

#include <cmath>

#include "common/base/error.h"

namespace ffriga {

AxisymmetricBody::AxisymmetricBody(std::string name, std::shared_ptr<const FlexibleBodySid> sid,
                                   double axis_sign)
    : BodyModel(std::move(name), std::move(sid)), sign_(axis_sign) {
  if (sid_->space_dim != 2) {
    throw InputError(Str() << "body '" << name_ << "': an axisymmetric body needs 2D SID data, "
                           << "found space_dim " << sid_->space_dim);
  }
  FFRIGA_CHECK(std::abs(std::abs(sign_) - 1.0) < 1e-15, "axis sign " << sign_);
  ct_ = sid_->Ct.col(1);
  MeInvCt_ = nq() > 0 ? Eigen::VectorXd(Me_llt_.solve(ct_)) : Eigen::VectorXd();
  schur_ = sid_->mass - (nq() > 0 ? ct_.dot(MeInvCt_) : 0.0);
  if (!(schur_ > 0.0)) {
    throw InputError(Str() << "body '" << name_ << "': mass matrix not positive definite (m - "
                           << "ct^T Me^-1 ct = " << schur_ << ")");
  }
}

BodyPose AxisymmetricBody::pose(const double* sp) const {
  BodyPose p;
  p.A = Eigen::Matrix2d::Identity();
  p.A(1, 1) = sign_;
  p.origin = Eigen::Vector2d(0.0, sp[0]);
  p.q = Eigen::Map<const Eigen::VectorXd>(sp + 1, nq());
  return p;
}

void AxisymmetricBody::positionRates(const double*, const double* sv, double* spdot) const {
  for (int i = 0; i < 1 + nq(); ++i) spdot[i] = sv[i];
}

void AxisymmetricBody::accelerations(const double* sp, const double* sv, const double* h_applied,
                                     const Eigen::Vector3d& gravity, double* accel) const {
  const int n = nq();
  const double hY = h_applied[0] + sid_->mass * gravity(1);
  if (n == 0) {
    accel[0] = hY / sid_->mass;
    return;
  }
  const Eigen::Map<const Eigen::VectorXd> q(sp + 1, n), qd(sv + 1, n);
  Eigen::VectorXd hq =
      Eigen::Map<const Eigen::VectorXd>(h_applied + 1, n) + sign_ * ct_ * gravity(1);
  if (exactly_diagonal_) {
    hq -= k_.cwiseProduct(q) + c_.cwiseProduct(qd);  // Me = E, diagonal Ke, De: O(nq)
  } else {
    hq -= sid_->Ke * q + De_ * qd;
  }
  const Eigen::VectorXd MeInvHq = exactly_diagonal_ ? hq : Eigen::VectorXd(Me_llt_.solve(hq));
  // Schur complement on the rigid row: (m - ct^T Me^-1 ct) aY = hY - s ct^T Me^-1 hq.
  const double aY = (hY - sign_ * ct_.dot(MeInvHq)) / schur_;
  accel[0] = aY;
  Eigen::Map<Eigen::VectorXd>(accel + 1, n) = MeInvHq - sign_ * aY * MeInvCt_;
}

void AxisymmetricBody::addRigidPointForce(const BodyPose&, const VectorRef&, const VectorRef& f,
                                          double* h) const {
  h[0] += f(1);
}

double AxisymmetricBody::kineticEnergy(const double*, const double* sv) const {
  const Eigen::Map<const Eigen::VectorXd> qd(sv + 1, nq());
  return 0.5 * sid_->mass * sv[0] * sv[0] + sign_ * sv[0] * ct_.dot(qd) +
         0.5 * qd.dot(sid_->Me * qd);
}

double AxisymmetricBody::gravityEnergy(const double* sp, const Eigen::Vector3d& gravity) const {
  const Eigen::Map<const Eigen::VectorXd> q(sp + 1, nq());
  return -gravity(1) * (sid_->mass * sp[0] + sign_ * (sid_->first_moment(1) + ct_.dot(q)));
}

void AxisymmetricBody::momentum(const double*, const double* sv, Eigen::Vector3d& linear,
                                Eigen::Vector3d& angular) const {
  const Eigen::Map<const Eigen::VectorXd> qd(sv + 1, nq());
  linear = Eigen::Vector3d(0.0, sid_->mass * sv[0] + sign_ * ct_.dot(qd), 0.0);
  angular.setZero();
}

}  // namespace ffriga

namespace ffriga {

void AxisymmetricBody::solveMass(const double*, Eigen::MatrixXd& B) const {
  const int n = nq();
  if (n == 0) {
    B /= sid_->mass;
    return;
  }
  // Schur complement on the rigid row, as in accelerations().
  const Eigen::MatrixXd MeInvBq = Me_llt_.solve(B.bottomRows(n));
  const Eigen::RowVectorXd aY = (B.row(0) - sign_ * ct_.transpose() * MeInvBq) / schur_;
  B.row(0) = aY;
  B.bottomRows(n) = MeInvBq - sign_ * MeInvCt_ * aY;
}

void AxisymmetricBody::massBlocks(const double*, Eigen::MatrixXd& C, Eigen::MatrixXd& Mrr) const {
  // M = [[m, s ct^T], [s ct, Me]] (constant).
  C = sign_ * ct_;
  Mrr = Eigen::MatrixXd::Constant(1, 1, sid_->mass);
}

// v = (0, s_v(0)) + A u_dot: the axial translation and the elastic velocity (pointGradients'
// bv).
Eigen::VectorXd AxisymmetricBody::pointVelocity(const BodyPose& pose, const double* sv,
                                                const VectorRef&, const VectorRef& u_dot) const {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(2);
  v(1) = sv[0];
  if (u_dot.size() > 0) v += pose.A * u_dot;
  return v;
}

void AxisymmetricBody::pointGradients(const BodyPose& pose, const VectorRef&,
                                      const Eigen::MatrixXd& Phi_x, const VectorRef& n,
                                      Eigen::VectorXd& bv, Eigen::VectorXd& bp) const {
  bv.resize(numVelocities());
  bv(0) = n(1);
  if (nq() > 0) {
    // A^T n first, then Phi^T (A^T n) straight into bv: no temporaries on the heap.
    SpaceVector nb;
    nb.noalias() = pose.A.transpose() * n;
    bv.tail(nq()).noalias() = Phi_x.transpose() * dynamic(nb);
  }
  bp = bv;
}

}  // namespace ffriga
