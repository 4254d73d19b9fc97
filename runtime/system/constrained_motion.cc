// Joints and force elements of the multibody system: the constraint equations, the
// multipliers of the acceleration-level constraints and the projection onto the position
// and velocity constraints (formulas in runtime/system/multibody_system.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/base/error.h"
#include "runtime/bodies/marker_kinematics.h"
#include "runtime/system/multibody_system.h"
#include "runtime/system/system_state.h"

namespace ffriga {

void MultibodySystem::addLineForces(const double* y, std::vector<Eigen::VectorXd>& h,
                                    std::vector<LineForceState>* states) const {
  if (states) states->assign(line_forces_.size(), LineForceState());
  const SystemState at(*this, y);
  ForceStates out;
  out.line_forces = states;
  for (const auto& e : forces_)
    if (!e->hasStiffnessTerms()) e->addForces(at, h, out);
}

void MultibodySystem::sensorState(const double* y, int s, Eigen::Vector3d& position,
                                  Eigen::Vector3d& velocity) const {
  const MarkerEnd& e = sensors_[s].end;
  const double* sp = y + pos_offset_[e.body];
  const double* sv = y + vel_offset_[e.body];
  if (e.model) {
    MarkerKinematics k;
    markerPoint(*e.model, sp, sv, e.marker, k);
    position = k.value;
    velocity = k.rate;
    return;
  }
  // An axisymmetric body (runtime/bodies/axisymmetric_body.h): the meridian point
  // (r, y) + Phi q is at (r, Y + s y) in the world, and moves with (0, V) + A Phi qdot.
  const BodyModel& body = *bodies_[e.body];
  FFRIGA_CHECK(body.spaceDim() == 2, "sensor '" << sensors_[s].name << "' on body '"
                                                << body.name() << "': no marker kinematics");
  const BodyPose pose = body.pose(sp);
  const int n = body.nq();
  const Eigen::Vector2d local =
      e.marker.x0.head<2>() + e.marker.Phi.topRows<2>() * Eigen::Map<const Eigen::VectorXd>(sp + 1, n);
  const Eigen::Vector2d rate =
      e.marker.Phi.topRows<2>() * Eigen::Map<const Eigen::VectorXd>(sv + 1, n);
  position << pose.origin + pose.A * local, 0.0;
  velocity << Eigen::Vector2d(0.0, sv[0]) + pose.A * rate, 0.0;
}

bool MultibodySystem::dissipates() const {
  for (const auto& b : bodies_) {
    if (b->nq() == 0 || !b->damping().any()) continue;
    // Quasi-static coordinates have no velocity: damping on them alone takes nothing out
    // (the default for every SID body whose file damps its stiff modes).
    Eigen::VectorXd dynamic = Eigen::VectorXd::Ones(b->nq());
    for (const int i : b->quasiStatic().index) dynamic(i) = 0.0;
    if ((b->damping().cwiseAbs() * dynamic).any() ||
        (b->damping().cwiseAbs().transpose() * dynamic).any())
      return true;
  }
  // Line forces are evaluated (zero power for undamped springs and Hertz contacts).
  return hasFriction() || !line_forces_.empty();
}

bool MultibodySystem::hasFriction() const {
  for (int c = 0; c < numContacts(); ++c)
    if (contact(c).options().friction.active()) return true;
  return false;
}

double MultibodySystem::dissipationPower(const double* y) const {
  double power = 0.0;
  for (int b = 0; b < numBodies(); ++b) {
    const BodyModel& body = *bodies_[b];
    if (body.nq() == 0) continue;
    const Eigen::Map<const Eigen::VectorXd> qd(y + vel_offset_[b] + body.numRigidVelocities(),
                                               body.nq());
    // Diagonal De (to 1e-8 relative, BodyModel::diagonalElasticity): O(nq), as the rates.
    power += body.diagonalElasticity() ? qd.dot(body.dampingDiagonal().cwiseProduct(qd))
                                       : qd.dot(body.damping() * qd);
  }
  if (!line_forces_.empty())
    for (const LineForceState& s : lineForceStates(y)) power += s.dissipation;
  return power;
}

std::vector<LineForceState> MultibodySystem::lineForceStates(const double* y) const {
  std::vector<Eigen::VectorXd> h(bodies_.size());
  for (int b = 0; b < numBodies(); ++b) h[b].setZero(bodies_[b]->numVelocities());
  std::vector<LineForceState> states;
  addLineForces(y, h, &states);
  return states;
}

void MultibodySystem::constraintRows(const double* y, ConstraintRows& rows) const {
  const int m = num_constraints_, nv = totalVelocities();
  rows.g.resize(m);
  rows.bias.resize(m);
  rows.J.setZero(m, nv);
  rows.joints.resize(joints_.size());
  const int v0 = vel_offset_.empty() ? 0 : vel_offset_[0];
  int row = 0;
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const Joint& joint = *joints_[j];
    const int a = joint.end(0).body, b = joint.end(1).body;
    JointRows& r = rows.joints[j];
    joint.evaluate(a >= 0 ? y + pos_offset_[a] : nullptr, a >= 0 ? y + vel_offset_[a] : nullptr,
                   y + pos_offset_[b], y + vel_offset_[b], r);
    const int k = joint.numEquations();
    rows.g.segment(row, k) = r.g;
    rows.bias.segment(row, k) = r.bias;
    if (a >= 0) rows.J.block(row, vel_offset_[a] - v0, k, r.Ja.cols()) += r.Ja;
    rows.J.block(row, vel_offset_[b] - v0, k, r.Jb.cols()) += r.Jb;
    row += k;
  }
}

void MultibodySystem::inverseMassTimes(const double* y, const Eigen::MatrixXd& J,
                                       Eigen::MatrixXd& X) const {
  const int v0 = vel_offset_[0];
  X.setZero(J.cols(), J.rows());
  for (int b = 0; b < numBodies(); ++b) {
    const int c = vel_offset_[b] - v0, nv = bodies_[b]->numVelocities();
    if (J.middleCols(c, nv).isZero(0.0)) continue;  // no joint at this body
    Eigen::MatrixXd B = J.middleCols(c, nv).transpose();
    bodies_[b]->solveMass(y + pos_offset_[b], B);
    X.middleRows(c, nv) = B;
  }
}

void MultibodySystem::constraintMobility(const double* y, const Eigen::MatrixXd& J,
                                         Eigen::MatrixXd& X, Eigen::LLT<Eigen::MatrixXd>& S) const {
  inverseMassTimes(y, J, X);
  S.compute(J * X);
  if (S.info() != Eigen::Success)
    throw ComputeError(
        "joints: the constraint matrix J M^-1 J^T is singular (redundant or "
        "degenerate joints)");
}

void MultibodySystem::applyConstraints(const double* y, double* ydot) {
  // With quasi-static coordinates the joints do not act on them (detachQuasiStatic: their
  // columns of J are zero), and M^-1 is the full one: where a_s = 0 (the quasi-static
  // manifold) these multipliers are those of the mode-acceleration equations
  // (schemas/multibody.md "Joints and quasi-static coordinates").
  ConstraintRows rows;
  constraintRows(y, rows);
  Eigen::MatrixXd X;
  Eigen::LLT<Eigen::MatrixXd> S;
  constraintMobility(y, rows.J, X, S);
  Eigen::Map<Eigen::VectorXd> a(ydot + vel_offset_[0], totalVelocities());
  lambda_ = S.solve(-rows.bias - rows.J * a);
  a += X * lambda_;
}

std::vector<JointReaction> MultibodySystem::jointReactions(const double* y) {
  std::vector<JointReaction> out(joints_.size());
  if (joints_.empty()) return out;
  Eigen::VectorXd ydot(size_);
  evaluateRates(y, ydot.data(), nullptr, nullptr);  // sets lambda_; keeps lastRhsContacts()
  ConstraintRows rows;
  constraintRows(y, rows);
  int row = 0;
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const int k = joints_[j]->numEquations(), b = joints_[j]->end(1).body;
    out[j] = joints_[j]->reaction(y + pos_offset_[b], rows.joints[j], lambda_.segment(row, k));
    for (int i = 0; i < 2; ++i) {
      const MarkerEnd& e = joints_[j]->end(i);
      if (e.quasi_static_Phi.size() == 0) continue;
      const BodyModel& body = *bodies_[e.body];
      const Eigen::Map<const Eigen::VectorXd> q(y + pos_offset_[e.body] + body.numRigidPositions(),
                                                body.nq());
      out[j].quasi_static_offset =
          std::max(out[j].quasi_static_offset, (e.quasi_static_Phi * q).norm());
    }
    row += k;
  }
  return out;
}

bool MultibodySystem::projectionMobility(const double* y, const ConstraintRows& rows,
                                         bool rigidOnly, Eigen::MatrixXd& X,
                                         Eigen::LLT<Eigen::MatrixXd>& S) const {
  if (!rigidOnly) {
    constraintMobility(y, rows.J, X, S);
    // Quasi-static coordinates have no velocity and follow from the others: the projection
    // leaves them (their columns of J are zero, so S = J X is unchanged).
    const int v0 = vel_offset_[0];
    for (int b = 0; b < numBodies(); ++b)
      for (const int i : bodies_[b]->quasiStatic().index)
        X.row(vel_offset_[b] - v0 + bodies_[b]->numRigidVelocities() + i).setZero();
    return true;
  }
  // X = M_r^-1 J_r^T over the rigid velocity columns only (elastic coordinates held).
  const int v0 = vel_offset_[0];
  X.setZero(totalVelocities(), rows.J.rows());
  for (int b = 0; b < numBodies(); ++b) {
    const BodyModel& body = *bodies_[b];
    const int c = vel_offset_[b] - v0, nr = body.numRigidVelocities();
    if (rows.J.middleCols(c, nr).isZero(0.0)) continue;
    Eigen::MatrixXd C, Mrr;
    body.massBlocks(y + pos_offset_[b], C, Mrr);
    X.middleRows(c, nr) = Mrr.ldlt().solve(Eigen::MatrixXd(rows.J.middleCols(c, nr).transpose()));
  }
  S.compute(rows.J * X);
  return S.info() == Eigen::Success;  // false: the rigid motion alone cannot close the joints
}

bool MultibodySystem::closeConstraints(double* y, bool rigidOnly) {
  const int v0 = vel_offset_[0], nv = totalVelocities();
  ConstraintRows rows;
  Eigen::MatrixXd X;
  Eigen::LLT<Eigen::MatrixXd> S;
  Eigen::VectorXd dsp;
  // Newton to round-off: |g| <= 1e-15 (m, or 1 for directions; a few ulps of the scenes'
  // lengths), or |g| <= 1e-13 and no longer falling (round-off of larger coordinates). A
  // projection that stopped at 1e-13 moved the state by up to that much after every step:
  // with tight tolerances (rtol 1e-11, a coordinate near zero) that exceeds the local error
  // allowed, and CVODE's error test failed at any step size (a rigid pendulum near the top
  // of its swing, in a build with other rounding). From a step's drift Newton takes 1-3 steps.
  constexpr double kTolerance = 1e-13, kRoundOff = 1e-15;
  bool closed = false;
  double previous = std::numeric_limits<double>::infinity();
  for (int iter = 0; iter < 8 && !closed; ++iter) {
    constraintRows(y, rows);
    const double g = rows.g.lpNorm<Eigen::Infinity>();
    if (g <= kRoundOff || (g <= kTolerance && g > 0.5 * previous)) {
      closed = true;
      break;
    }
    previous = g;
    if (!projectionMobility(y, rows, rigidOnly, X, S)) return false;
    const Eigen::VectorXd dz = -X * S.solve(rows.g);
    for (int b = 0; b < numBodies(); ++b) {
      const BodyModel& body = *bodies_[b];
      double* sp = y + pos_offset_[b];
      dsp.resize(body.numPositions());
      body.positionRates(sp, dz.data() + (vel_offset_[b] - v0), dsp.data());
      Eigen::Map<Eigen::VectorXd>(sp, body.numPositions()) += dsp;
      body.normalize(sp);
    }
  }
  if (!closed) {
    constraintRows(y, rows);
    if (rows.g.lpNorm<Eigen::Infinity>() > kTolerance) return false;
  }
  // Velocities: one linear projection at the projected positions, in the same metric.
  if (!projectionMobility(y, rows, rigidOnly, X, S)) return false;
  Eigen::Map<Eigen::VectorXd> z(y + v0, nv);
  z -= X * S.solve(rows.J * z);
  return true;
}

bool MultibodySystem::projectState(double* y) {
  if (!joints_.empty()) {
    // By the rigid coordinates where they can close the joints, else in the mass metric
    // (header comment: the mass metric would move the light, stiff constraint modes).
    const Eigen::VectorXd saved = Eigen::Map<const Eigen::VectorXd>(y, size_);
    if (!closeConstraints(y, true)) {
      Eigen::Map<Eigen::VectorXd>(y, size_) = saved;
      if (!closeConstraints(y, false)) return false;
    }
  }
  if (!projectQuasiStatic(y)) return false;
  if (hasAnchors()) placeEachPairsAnchors(y, &SurfaceContact::followAnchors);
  return true;
}

bool MultibodySystem::projectStateRigidly(double* y) {
  return joints_.empty() || closeConstraints(y, true);
}

bool MultibodySystem::project(double, const double* y, double* corr) {
  Eigen::VectorXd p = Eigen::Map<const Eigen::VectorXd>(y, size_);
  if (!projectState(p.data())) return false;
  Eigen::Map<Eigen::VectorXd>(corr, size_) = p - Eigen::Map<const Eigen::VectorXd>(y, size_);
  return true;
}

}  // namespace ffriga
