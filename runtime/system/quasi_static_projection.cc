// Projection onto the quasi-static manifold (runtime/bodies/quasi_static_modes.h): after every
// step (CVodeSetProjFn) and for every output row, the quasi-static coordinates q_s of all
// bodies are moved so that their accelerations vanish, a_s(y) = 0, by Newton's method:
//
//   (K_s + K_c,ss) dq_s = a_s,     K_s = diag(k_i),   K_c,ss = sum_t k_t u_t u_t^T,
//
// with u_t the quasi-static rows of the contact stiffness term t ([bvC; -bvT] of
// contact_pair.h; both bodies' coordinates, since contact couples them), solved by the
// Woodbury formula with the P x P capacitance W^-1 + U^T K_s^-1 U (P = active points).
// Why: the relaxation keeps q_s on the manifold only to the accuracy of CVODE's Newton
// iteration, and where a collocation point enters or leaves contact the last Newton
// correction crosses the kink of the penalty force: the accepted state then lies off the
// manifold by a finite amount that the next step's error test sees at any step size (seen:
// "error test failed repeatedly" at h = 5e-13 s on sphere2d_g3 as two points separated).
// The projection removes that offset; it costs one or two contact evaluations per step.
// With friction (runtime/contact/coulomb_friction.h) the tangential forces follow the normal
// ones at the velocities of the moment: their kFrictionLoad terms k_t u_t v_t^T (u_t along
// the friction force, v_t along the normal) join the matrix, which is then not symmetric
// (the Woodbury formula with an LU of the capacitance); without them Newton converged only
// linearly, by about mu per iteration. The velocity terms do not enter (q_s only moves).
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/base/error.h"
#include "runtime/system/multibody_system.h"

namespace ffriga {

namespace {

// A quasi-static coordinate in the system's global list: body, state index of q_i, velocity
// index of the acceleration entry, stiffness.
struct Coordinate {
  int body, position, velocity;
  double k, phi;  // 1/s^2; max |Phi_i| (m per unit q_i)
};

// The global list of the quasi-static coordinates, body by body; first[b] is the list index
// of body b's first one (left at -1 for a body without).
std::vector<Coordinate> quasiStaticCoordinates(const MultibodySystem& system,
                                               std::vector<int>& first) {
  std::vector<Coordinate> list;
  for (int b = 0; b < system.numBodies(); ++b) {
    const BodyModel& body = system.body(b);
    const QuasiStaticModes& qs = body.quasiStatic();
    if (!qs.empty()) first[b] = static_cast<int>(list.size());
    for (int s = 0; s < qs.size(); ++s)
      list.push_back({b, system.positionOffset(b) + body.numRigidPositions() + qs.index[s],
                      body.numRigidVelocities() + qs.index[s], qs.stiffness(s), qs.reach(s)});
  }
  return list;
}

// Contact stiffness on the quasi-static coordinates: the columns u_t of U (n x P), the
// quasi-static rows of [bvC; -bvT] of each normal stiffness term t that reaches them, and the
// weights W = diag(k_t); friction's load terms as pairs (u_t, v_t) in `load` (v_t from
// [bpC; -bpT]: the elastic rows of bp and bv agree) with their weights in `load_weights`.
struct StiffnessColumns {
  std::vector<Eigen::VectorXd> columns;
  std::vector<double> weights;
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> load;
  std::vector<double> load_weights;
};

void contactStiffnessColumns(const MultibodySystem& system, const std::vector<Coordinate>& list,
                             StiffnessColumns& out) {
  const int n = static_cast<int>(list.size());
  auto rows = [&](const StiffnessTerm& t, const Eigen::VectorXd& c, const Eigen::VectorXd& tt,
                  bool positions, bool& any) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
    for (int j = 0; j < n; ++j) {
      const Coordinate& q = list[j];
      const int at = positions ? q.position - system.positionOffset(q.body) : q.velocity;
      if (q.body == t.body_c) u(j) += c(at);
      if (q.body == t.body_t) u(j) -= tt(at);
      any = any || q.body == t.body_c || q.body == t.body_t;
    }
    return u;
  };
  for (int e = 0; e < system.numForceElements(); ++e) {
    for (const StiffnessTerm& t : system.forceElement(e).stiffnessTerms()) {
      if (t.onVelocities() || !(t.k > 0.0)) continue;  // a point on the axis: no ring weight
      bool any = false;
      Eigen::VectorXd u = rows(t, t.bvC, t.bvT, false, any);
      if (!any) continue;
      if (t.kind == StiffnessTerm::Kind::kNormal) {
        out.columns.push_back(std::move(u));
        out.weights.push_back(t.k);
      } else {
        out.load.emplace_back(std::move(u), rows(t, t.bpC, t.bpT, true, any));
        out.load_weights.push_back(t.k);
      }
    }
  }
}

// The Newton step dq = A^-1 r, A = K + U W U^T (K = diag(k), U and W of
// contactStiffnessColumns), by Woodbury: A^-1 = K^-1 - K^-1 U (W^-1 + U^T K^-1 U)^-1 U^T K^-1.
void woodburyStep(const Eigen::VectorXd& k, const Eigen::VectorXd& r,
                  const std::vector<Eigen::VectorXd>& columns, const std::vector<double>& weights,
                  Eigen::VectorXd& dq) {
  // (the symmetric case: normal terms only)
  const int n = static_cast<int>(k.size());
  dq = r.cwiseQuotient(k);
  const int P = static_cast<int>(columns.size());
  if (P > 0) {
    Eigen::MatrixXd U(n, P), KU(n, P);
    for (int p = 0; p < P; ++p) U.col(p) = columns[p];
    KU = k.cwiseInverse().asDiagonal() * U;
    Eigen::MatrixXd C = U.transpose() * KU;
    for (int p = 0; p < P; ++p) C(p, p) += 1.0 / weights[p];
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(C);
    dq -= KU * ldlt.solve(U.transpose() * dq);
  }
}

// The same with friction's load terms: A = K + L R^T with L = [U W, U_l W_l], R = [U, V_l],
// A^-1 = K^-1 - K^-1 L (I + R^T K^-1 L)^-1 R^T K^-1 (an LU of the capacitance).
void woodburyStep(const Eigen::VectorXd& k, const Eigen::VectorXd& r, const StiffnessColumns& s,
                  Eigen::VectorXd& dq) {
  if (s.load.empty()) {
    woodburyStep(k, r, s.columns, s.weights, dq);
    return;
  }
  const int n = static_cast<int>(k.size());
  const int P = static_cast<int>(s.columns.size()), Q = static_cast<int>(s.load.size());
  Eigen::MatrixXd L(n, P + Q), R(n, P + Q);
  for (int p = 0; p < P; ++p) {
    L.col(p) = s.weights[p] * s.columns[p];
    R.col(p) = s.columns[p];
  }
  for (int p = 0; p < Q; ++p) {
    L.col(P + p) = s.load_weights[p] * s.load[p].first;
    R.col(P + p) = s.load[p].second;
  }
  const Eigen::MatrixXd KL = k.cwiseInverse().asDiagonal() * L;
  Eigen::MatrixXd C = R.transpose() * KL;
  C.diagonal().array() += 1.0;
  dq = r.cwiseQuotient(k);
  dq -= KL * C.partialPivLu().solve(R.transpose() * dq);
}

// Adds dq to the quasi-static coordinates in y; change and size (m): the largest point
// displacement of a coordinate's correction and of its new value.
void applyCorrection(const std::vector<Coordinate>& list, const Eigen::VectorXd& dq, double* y,
                     double& change, double& size) {
  for (int j = 0; j < static_cast<int>(list.size()); ++j) {
    y[list[j].position] += dq(j);
    change = std::max(change, std::abs(dq(j)) * list[j].phi);
    size = std::max(size, std::abs(y[list[j].position]) * list[j].phi);
  }
}

}  // namespace

bool MultibodySystem::hasQuasiStatic() const {
  for (const auto& b : bodies_)
    if (!b->quasiStatic().empty()) return true;
  return false;
}

void MultibodySystem::quasiStaticAccelerations(const double* y, const std::vector<int>& first,
                                               std::vector<Eigen::VectorXd>& accel) {
  if (!joints_.empty()) {
    // The joints couple the bodies: the constrained accelerations of all of them.
    Eigen::VectorXd rates(size_);
    constrainedAccelerations(y, rates.data(), nullptr, nullptr);
    for (int b = 0; b < numBodies(); ++b)
      if (first[b] >= 0) accel[b] = rates.segment(vel_offset_[b], bodies_[b]->numVelocities());
    return;
  }
  contactForces(y, h_, nullptr);
  addLineForces(y, h_, nullptr);
  for (int b = 0; b < numBodies(); ++b) {
    if (first[b] < 0) continue;
    accel[b].resize(bodies_[b]->numVelocities());
    bodies_[b]->accelerations(y + pos_offset_[b], y + vel_offset_[b], h_[b].data(), gravity_,
                              accel[b].data());
  }
}

bool MultibodySystem::projectQuasiStatic(double* y) {
  std::vector<int> first(bodies_.size(), -1);
  const std::vector<Coordinate> list = quasiStaticCoordinates(*this, first);
  const int n = static_cast<int>(list.size());
  if (n == 0) return true;
  Eigen::VectorXd k(n), r(n), dq(n);
  for (int j = 0; j < n; ++j) k(j) = list[j].k;
  std::vector<Eigen::VectorXd> accel(bodies_.size());
  // Newton's iteration on a_s = 0; false if it did not converge.
  const auto newton = [&]() {
    constexpr int kMaxIterations = 8;
    double previous = 0.0;  // the last iteration's change (m)
    for (int it = 0; it < kMaxIterations; ++it) {
      quasiStaticAccelerations(y, first, accel);
      for (int j = 0; j < n; ++j) r(j) = accel[list[j].body](list[j].velocity);
      StiffnessColumns columns;
      contactStiffnessColumns(*this, list, columns);
      woodburyStep(k, r, columns, dq);
      if (!dq.allFinite()) return false;
      double change = 0.0, size = 0.0;  // m: the largest point displacement of a coordinate
      applyCorrection(list, dq, y, change, size);
      // Converged when the correction moves no point by more than 1e-9 of the quasi-static
      // displacements or 1e-16 m (1e-4 of the default atol_position): the penalty force is
      // piecewise linear in q_s, so Newton is exact once the active set holds, up to the
      // neglected turning of the normal (~ gap / element size, 1e-3: a few iterations).
      if (change <= 1e-9 * size + 1e-16) return true;
      // Or when Newton has reached the noise of its residual: corrections that stopped
      // shrinking (more than half the last one) below 1e-7 of the displacements. Seen: a
      // soft contact (1e15 N/m^3, 40 active points) whose corrections hovered at 1.2e-9 ..
      // 8e-9 of the displacements for 6 iterations, in a build with other rounding.
      // The offset left is far below atol_position (1e-7 x ~1e-6 m = 1e-13 m).
      if (it >= 2 && change <= 1e-7 * size && change > 0.5 * previous) return true;
      previous = change;
    }
    return false;
  };
  if (!hasAnchors()) return newton();
  // Anchored friction: each point keeps its branch through the iteration, a slipping one
  // with its anchor on the slip limit (SurfaceContact::holdFrictionBranches); sticking
  // points whose spring ends beyond the limit turn to slip and the iteration runs again
  // (points only ever turn from stick to slip: at most one round per point); at the end
  // the slipping points' anchors are put on their limit, where both branches agree.
  struct HeldBranches {
    MultibodySystem& system;
    explicit HeldBranches(MultibodySystem& s) : system(s) {
      for (int c = 0; c < system.numContacts(); ++c) system.contact(c).holdFrictionBranches(true);
    }
    ~HeldBranches() {
      for (int c = 0; c < system.numContacts(); ++c) system.contact(c).holdFrictionBranches(false);
    }
    bool releaseExceeded() {
      bool any = false;
      for (int c = 0; c < system.numContacts(); ++c)
        any = system.contact(c).releaseExceeded() || any;
      return any;
    }
  } held(*this);
  constexpr int kMaxRounds = 8;
  for (int round = 0; round < kMaxRounds; ++round) {
    if (!newton()) return false;
    quasiStaticAccelerations(y, first, accel);  // the branches' state at the result
    if (!held.releaseExceeded()) {
      placeEachPairsAnchors(y, &SurfaceContact::settleAnchors);
      return true;
    }
  }
  return false;
}

}  // namespace ffriga
