#include "runtime/bodies/floating_body.h"

#include <cstring>
#include <functional>
#include <map>
#include <mutex>

#include "common/base/error.h"
#include "runtime/bodies/rotation.h"

namespace ffriga {

FloatingBody3d::FloatingBody3d(std::string name, std::shared_ptr<const FlexibleBodySid> sid)
    : BodyModel(std::move(name), std::move(sid)) {
  const FlexibleBodySid& s = *sid_;
  if (s.space_dim != 3) {
    throw InputError(Str() << "body '" << name_ << "': a floating 3D body needs 3D SID data, found "
                           << "space_dim " << s.space_dim);
  }
  const int nq = s.nq();
  if (s.Cr0.rows() != nq || s.Cr0.cols() != 3 || static_cast<int>(s.Cr1.size()) != nq ||
      static_cast<int>(s.J1.size()) != nq) {
    throw InputError(Str() << "body '" << name_ << "': SID rotational invariants Cr0 ("
                           << s.Cr0.rows() << "x" << s.Cr0.cols() << "), Cr1 (" << s.Cr1.size()
                           << "), J1 (" << s.J1.size() << ") do not match nq = " << nq);
  }
  checkCentrifugalInvariants();
  for (int j = 0; j < nq; ++j) {
    if (s.Cr1[j].rows() != 3 || s.Cr1[j].cols() != nq) {
      throw InputError(Str() << "body '" << name_ << "': SID Cr1[" << j << "] is "
                             << s.Cr1[j].rows() << "x" << s.Cr1[j].cols() << ", expected 3x" << nq);
    }
  }
  coupling_ = sharedCoupling(s, name_);
}

std::shared_ptr<const RotationalCoupling> FloatingBody3d::sharedCoupling(
    const FlexibleBodySid& sid, const std::string& body) {
  // One tensor per SID object while a body holds it (the body also holds the SID, so its
  // address is not reused meanwhile).
  static std::mutex mutex;
  static std::map<const FlexibleBodySid*, std::weak_ptr<const RotationalCoupling>> registry;
  const std::lock_guard<std::mutex> lock(mutex);
  if (auto found = registry[&sid].lock()) return found;
  for (auto it = registry.begin(); it != registry.end();)  // forget SIDs no body holds
    it = it->second.expired() ? registry.erase(it) : std::next(it);
  auto made = std::make_shared<const RotationalCoupling>(sid, body);
  registry[&sid] = made;
  return made;
}

namespace {
const Eigen::Matrix<double, Eigen::Dynamic, 3>& cachedProduct(
    const Eigen::VectorXd& x, Eigen::VectorXd& key, Eigen::Matrix<double, Eigen::Dynamic, 3>& G,
    bool& valid, const std::function<void()>& compute) {
  // memcmp only on non-empty data (a rigid body has nq = 0 and null data pointers).
  if (valid && key.size() == x.size() &&
      (x.size() == 0 || std::memcmp(key.data(), x.data(), sizeof(double) * x.size()) == 0))
    return G;
  compute();
  key = x;
  valid = true;
  return G;
}
}  // namespace

const Eigen::Matrix<double, Eigen::Dynamic, 3>& FloatingBody3d::couplingOfPositions(
    const Eigen::VectorXd& q) const {
  return cachedProduct(q, positions_.x, positions_.G, positions_.valid,
                       [&] { coupling_->apply(q, positions_.G); });
}

const Eigen::Matrix<double, Eigen::Dynamic, 3>& FloatingBody3d::couplingOfRates(
    const Eigen::VectorXd& qd) const {
  return cachedProduct(qd, rates_.x, rates_.G, rates_.valid, [&] {
    // Quasi-static coordinates keep qdot = 0: a column pass per non-zero entry is cheaper
    // than the full pass while at most a quarter of the entries are non-zero.
    const Eigen::Index nonzero = (qd.array() != 0.0).count();
    if (4 * nonzero <= qd.size())
      coupling_->applySparse(qd, rates_.G);
    else
      coupling_->apply(qd, rates_.G);
  });
}

void FloatingBody3d::checkCentrifugalInvariants() const {
  // Oe [w1^2, w2^2, w3^2, w1 w2, w2 w3, w1 w3]^T = int rho Phi^T w~ w~ x0 dV must equal
  // -1/2 [w^T J1_i w]_i (sid.h); the equations use J1, so a disagreement means one of the
  // two invariants was written with another convention. Checked at three angular velocities.
  const FlexibleBodySid& s = *sid_;
  const int nq = s.nq();
  if (s.Oe.rows() != nq || s.Oe.cols() != 6 || nq == 0 || s.Oe.isZero(0.0)) return;
  const Eigen::Vector3d ws[3] = {{1.0, 0.0, 0.0}, {0.3, -0.7, 0.5}, {-0.2, 0.4, 0.9}};
  double worst = 0.0, scale = 0.0;
  for (const Eigen::Vector3d& w : ws) {
    Eigen::Matrix<double, 6, 1> w6;
    w6 << w(0) * w(0), w(1) * w(1), w(2) * w(2), w(0) * w(1), w(1) * w(2), w(0) * w(2);
    const Eigen::VectorXd fromOe = s.Oe * w6;
    Eigen::VectorXd fromJ1(nq);
    for (int i = 0; i < nq; ++i) fromJ1(i) = -0.5 * w.dot(s.J1[i] * w);
    worst = std::max(worst, (fromOe - fromJ1).norm());
    scale = std::max(scale, fromJ1.norm() + fromOe.norm());
  }
  if (worst > 1e-8 * scale) {
    throw InputError(Str() << "body '" << name_ << "': SID invariants Oe and J1 disagree (|Oe w6 + "
                           << "1/2 w^T J1 w| = " << worst << " against " << scale
                           << "); see common/sid/sid.h for their definitions");
  }
}

FloatingBody3d::Invariants FloatingBody3d::invariants(const Eigen::VectorXd& q) const {
  const FlexibleBodySid& s = *sid_;
  Invariants inv;
  inv.mc = s.first_moment + s.Ct.transpose() * q;
  inv.J = s.inertia;
  for (int j = 0; j < nq(); ++j)
    if (q(j) != 0.0) inv.J += q(j) * s.J1[j];
  inv.CrT = (s.Cr0 - couplingOfPositions(q)).transpose();
  return inv;
}

Eigen::MatrixXd FloatingBody3d::massMatrix(const Eigen::VectorXd& q) const {
  const Invariants inv = invariants(q);
  const int n = 6 + nq();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  M.topLeftCorner<3, 3>() = sid_->mass * Eigen::Matrix3d::Identity();
  M.block<3, 3>(3, 0) = skew(inv.mc);
  M.block<3, 3>(0, 3) = skew(inv.mc).transpose();
  M.block<3, 3>(3, 3) = inv.J;
  M.block(6, 0, nq(), 3) = sid_->Ct;
  M.block(0, 6, 3, nq()) = sid_->Ct.transpose();
  M.block(6, 3, nq(), 3) = inv.CrT.transpose();
  M.block(3, 6, 3, nq()) = inv.CrT;
  M.bottomRightCorner(nq(), nq()) = sid_->Me;
  return M;
}

BodyPose FloatingBody3d::pose(const double* sp) const {
  BodyPose p;
  p.A = rotationMatrix(sp + 3);
  p.origin = Eigen::Map<const Eigen::Vector3d>(sp);
  p.q = Eigen::Map<const Eigen::VectorXd>(sp + 7, nq());
  return p;
}

void FloatingBody3d::positionRates(const double* sp, const double* sv, double* spdot) const {
  const Eigen::Matrix3d A = rotationMatrix(sp + 3);
  const Eigen::Map<const Eigen::Vector3d> v(sv), w(sv + 3);
  Eigen::Map<Eigen::Vector3d> rdot(spdot);
  rdot = A * v;
  quaternionRate(sp + 3, w, spdot + 3);
  for (int j = 0; j < nq(); ++j) spdot[7 + j] = sv[6 + j];
}

void FloatingBody3d::accelerations(const double* sp, const double* sv, const double* h_applied,
                                   const Eigen::Vector3d& gravity, double* accel) const {
  const FlexibleBodySid& s = *sid_;
  const int n = nq();
  const Eigen::Map<const Eigen::VectorXd> q(sp + 7, n), qd(sv + 6, n);
  const Eigen::Map<const Eigen::Vector3d> v(sv), w(sv + 3);
  const Invariants inv = invariants(q);
  const double m = s.mass;

  // Rate-dependent sums.
  const Eigen::Vector3d ctqd = s.Ct.transpose() * qd;
  Eigen::Matrix3d Jdot = Eigen::Matrix3d::Zero();
  for (int j = 0; j < n; ++j)
    if (qd(j) != 0.0) Jdot += qd(j) * s.J1[j];
  const Eigen::Vector3d P = m * v + w.cross(inv.mc) + ctqd;
  const Eigen::Vector3d l = inv.mc.cross(v) + inv.J * w + inv.CrT * qd;

  Eigen::VectorXd h = Eigen::Map<const Eigen::VectorXd>(h_applied, 6 + n);
  // Quadratic velocity vector (header comment; (sum_j qdot_j Cr1_j) qdot = 0).
  h.head<3>() -= w.cross(ctqd) + w.cross(P);
  h.segment<3>(3) -= ctqd.cross(v) + Jdot * w + w.cross(l) + v.cross(P);
  if (n > 0) {
    // (sum_j qdot_j Cr1_j)^T w - [w . Cr1_i qdot]_i = -2 Y w.
    Eigen::VectorXd hq = -2.0 * (couplingOfRates(qd) * w) + s.Ct * w.cross(v);
    for (int i = 0; i < n; ++i) hq(i) -= 0.5 * w.dot(s.J1[i] * w);
    if (exactly_diagonal_) {
      h.tail(n) -= hq + k_.cwiseProduct(q) + c_.cwiseProduct(qd);  // O(nq): Eq. 13
    } else {
      h.tail(n) -= hq + s.Ke * q + De_ * qd;
    }
  }
  // Gravity.
  const Eigen::Vector3d gb = rotationMatrix(sp + 3).transpose() * gravity;
  h.head<3>() += m * gb;
  h.segment<3>(3) += inv.mc.cross(gb);
  if (n > 0) h.tail(n) += s.Ct * gb;

  // Schur complement solve of M z = h.
  Eigen::Matrix<double, 6, 6> Mrr;
  Mrr.setZero();
  Mrr.topLeftCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
  Mrr.block<3, 3>(3, 0) = skew(inv.mc);
  Mrr.block<3, 3>(0, 3) = skew(inv.mc).transpose();
  Mrr.block<3, 3>(3, 3) = inv.J;
  Eigen::Map<Eigen::VectorXd> a(accel, 6 + n);
  if (n == 0) {
    a = Mrr.ldlt().solve(h.head<6>());
    return;
  }
  Eigen::MatrixXd C(n, 6);
  C.leftCols<3>() = s.Ct;
  C.rightCols<3>() = inv.CrT.transpose();
  // Me = E exactly: no solves.
  const Eigen::MatrixXd MeInvC = exactly_diagonal_ ? C : Eigen::MatrixXd(Me_llt_.solve(C));
  const Eigen::VectorXd MeInvHq =
      exactly_diagonal_ ? Eigen::VectorXd(h.tail(n)) : Eigen::VectorXd(Me_llt_.solve(h.tail(n)));
  const Eigen::Matrix<double, 6, 6> S = Mrr - C.transpose() * MeInvC;
  const Eigen::Matrix<double, 6, 1> ar = S.ldlt().solve(h.head<6>() - C.transpose() * MeInvHq);
  a.head<6>() = ar;
  a.tail(n) = MeInvHq - MeInvC * ar;
}

void FloatingBody3d::addRigidPointForce(const BodyPose& pose, const VectorRef& x,
                                        const VectorRef& f, double* h) const {
  const Eigen::Vector3d fb = pose.A.transpose() * f;
  const Eigen::Vector3d xb = x;
  Eigen::Map<Eigen::Vector3d>(h) += fb;
  Eigen::Map<Eigen::Vector3d>(h + 3) += xb.cross(fb);
}

double FloatingBody3d::kineticEnergy(const double* sp, const double* sv) const {
  const Eigen::Map<const Eigen::VectorXd> q(sp + 7, nq()), z(sv, 6 + nq());
  return 0.5 * z.dot(massMatrix(q) * z);
}

double FloatingBody3d::gravityEnergy(const double* sp, const Eigen::Vector3d& gravity) const {
  const Eigen::Map<const Eigen::VectorXd> q(sp + 7, nq());
  const Eigen::Map<const Eigen::Vector3d> r(sp);
  const Eigen::Vector3d mc = sid_->first_moment + sid_->Ct.transpose() * q;
  return -gravity.dot(sid_->mass * r + rotationMatrix(sp + 3) * mc);
}

void FloatingBody3d::momentum(const double* sp, const double* sv, Eigen::Vector3d& linear,
                              Eigen::Vector3d& angular) const {
  const Eigen::Map<const Eigen::VectorXd> q(sp + 7, nq()), qd(sv + 6, nq());
  const Eigen::Map<const Eigen::Vector3d> r(sp), v(sv), w(sv + 3);
  const Invariants inv = invariants(q);
  const Eigen::Matrix3d A = rotationMatrix(sp + 3);
  const Eigen::Vector3d P = sid_->mass * v + w.cross(inv.mc) + sid_->Ct.transpose() * qd;
  const Eigen::Vector3d l = inv.mc.cross(v) + inv.J * w + inv.CrT * qd;
  linear = A * P;
  angular = r.cross(linear) + A * l;
}

void FloatingBody3d::normalize(double* sp) const {
  Eigen::Map<Eigen::Vector4d> p(sp + 3);
  p /= p.norm();
}

}  // namespace ffriga

namespace ffriga {

void FloatingBody3d::solveMass(const double* sp, Eigen::MatrixXd& B) const {
  const int n = nq();
  if (!exactly_diagonal_) {
    const Eigen::Map<const Eigen::VectorXd> q(sp + 7, n);
    B = massMatrix(q).ldlt().solve(B);
    return;
  }
  // Me = E: Schur complement on the rigid rows (header comment), O(nq) per column.
  Eigen::MatrixXd C, Mrr;
  massBlocks(sp, C, Mrr);
  const Eigen::LDLT<Eigen::MatrixXd> S(Mrr - C.transpose() * C);
  const Eigen::MatrixXd zr = S.solve(B.topRows(6) - C.transpose() * B.bottomRows(n));
  B.bottomRows(n) -= C * zr;
  B.topRows(6) = zr;
}

void FloatingBody3d::massBlocks(const double* sp, Eigen::MatrixXd& C, Eigen::MatrixXd& Mrr) const {
  const Eigen::Map<const Eigen::VectorXd> q(sp + 7, nq());
  const Invariants inv = invariants(q);
  Mrr.setZero(6, 6);
  Mrr.topLeftCorner<3, 3>() = sid_->mass * Eigen::Matrix3d::Identity();
  Mrr.block<3, 3>(3, 0) = skew(inv.mc);
  Mrr.block<3, 3>(0, 3) = skew(inv.mc).transpose();
  Mrr.block<3, 3>(3, 3) = inv.J;
  C.resize(nq(), 6);
  C.leftCols<3>() = sid_->Ct;
  C.rightCols<3>() = inv.CrT.transpose();
}

// v = A (v_R + omega x x + u_dot), v_R and omega in body components (pointGradients' bv).
Eigen::VectorXd FloatingBody3d::pointVelocity(const BodyPose& pose, const double* sv,
                                              const VectorRef& x, const VectorRef& u_dot) const {
  const Eigen::Vector3d vR(sv[0], sv[1], sv[2]), omega(sv[3], sv[4], sv[5]);
  const Eigen::Vector3d xb = x;
  Eigen::Vector3d local = vR + omega.cross(xb);
  if (u_dot.size() > 0) local += Eigen::Vector3d(u_dot);
  return pose.A * local;
}

void FloatingBody3d::pointGradients(const BodyPose& pose, const VectorRef& x,
                                    const Eigen::MatrixXd& Phi_x, const VectorRef& n,
                                    Eigen::VectorXd& bv, Eigen::VectorXd& bp) const {
  const Eigen::Vector3d nb = pose.A.transpose() * n;
  const Eigen::Vector3d xb = x;
  bv.resize(numVelocities());
  bp.setZero(numPositions());
  bv.head<3>() = nb;
  bv.segment<3>(3) = xb.cross(nb);
  bp.head<3>() = n;
  if (nq() > 0) {
    bv.tail(nq()) = Phi_x.transpose() * nb;
    bp.tail(nq()) = bv.tail(nq());
  }
}

}  // namespace ffriga
