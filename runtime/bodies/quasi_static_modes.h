// Quasi-static elastic coordinates: the stiff, high Craig-Bampton coordinates of a body
// follow the slow motion without inertia (the mode-acceleration idea; the reduced limit of
// a singular perturbation), instead of being damped (paper Sect. 5 damps them, and loses
// energy) or resolved in time (their periods of a few ns would set the step).
//
// For a body with Me = E and Ke = diag(k) (Eq. 13), the elastic equation of coordinate i is
//   qddot_i = a_i(y),   a_i = h_i - k_i q_i - (inertial coupling)   (body_model.h);
// a quasi-static coordinate keeps only its algebraic limit a_i = 0 (k_i q_i = h_i: the
// static response to the contact and inertial loads of the moment) and has no velocity
// (qdot_i = 0: no kinetic energy, no damping). The algebraic equation is given to the BDF
// integrator as a stiff relaxation (the epsilon-embedding of index-1 DAEs, Hairer & Wanner
// VI.1):
//   dq_i/dt = a_i / (k_i tau),        dqdot_i/dt = 0,
// i.e. tau dq_i/dt = q*_i - q_i with q*_i the quasi-static value. BDF is stable for the
// fast decay at any step (real eigenvalues -(1 + contact stiffness / k_i) / tau), so the
// step follows the dynamic coordinates only, and as tau -> 0 the discrete solution is
// BDF's solution of the DAE. The lag is q_i - q*_i = -tau dq_i/dt: with tau = 1e-6 /
// omega_cut (omega_cut = 2 pi f_cut), a relative lag of 1e-6 / (omega_cut T) for loads of
// duration T, and the energy the lag dissipates is the same fraction (~ pi^2 tau / T) of
// the energy stored in these coordinates: below 1e-8 for the impacts of Sect. 5-7.
// CVODE's Newton iteration holds the relaxation only to its tolerance, so after every step
// (and for every output row) the state is projected onto a_s = 0 exactly
// (runtime/system/quasi_static_projection.cc).
// The rest of the body's equations are untouched: the quasi-static coordinates move the
// contact surface and carry elastic energy 1/2 k_i q_i^2, so energy is conserved to the
// integrator's accuracy (no modal damping needed).
//
// Which coordinates: those with frequency sqrt(k_i) / (2 pi) >= f_cut (cutoff_hz). Their
// dynamic amplification under a load of duration T is ~ 1 / (1 - (1 / (f_i T))^2): for
// f_i T >= 10 (f_cut above 10 / T) the quasi-static response is within 1 % of the dynamic
// one for each such coordinate, and far less in the force (their share of the compliance
// is local). The rule that picks f_cut is runtime/bodies/quasi_static_rule.h.
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace ffriga {

struct QuasiStaticModes {
  static constexpr double kRelaxation = 1e-6;  // tau * omega_cut (see above)

  double cutoff_hz = 0.0;     // f_cut (Hz); meaningful when !index.empty()
  double tau = 0.0;           // relaxation time (s)
  std::vector<int> index;     // elastic coordinates (0 .. nq-1) treated quasi-statically
  Eigen::VectorXd stiffness;  // their k_i (1/s^2)
  Eigen::VectorXd reach;      // their max |Phi_i| over the body's points (m per unit q_i)
  int held_by_joints = 0;     // coordinates above the cutoff that joints keep dynamic (without)

  bool empty() const { return index.empty(); }
  int size() const { return static_cast<int>(index.size()); }

  // The coordinates of stiffness diagonal k with frequency >= cutoff_hz (all k_i > 0 there);
  // Phi: the body's mode shapes at its control points (rows), for `reach`.
  static QuasiStaticModes select(const Eigen::VectorXd& k, const Eigen::MatrixXd& Phi,
                                 double cutoff_hz);

  // The same coordinates less those listed in `dynamic` (elastic indices), which keep their
  // inertia (joints: runtime/bodies/body_marker.h jointHeldCoordinates).
  QuasiStaticModes without(const std::vector<int>& dynamic) const;

  // A body's rates (layout of body_model.h: spdot over its positions, accel over its
  // velocities, nrp / nrv rigid entries first): for each quasi-static coordinate i,
  // (dq_i/dt, dqdot_i/dt) = (v_i, a_i)  ->  (a_i / (k_i tau), 0).
  void apply(int nrp, int nrv, double* spdot, double* accel) const;
  // The same on the rows of a Jacobian-like matrix whose rows are a body's rates: row q_i
  // <- row qdot_i / (k_i tau), row qdot_i <- 0 (row indices pos0 + nrp + i, vel0 + nrv + i).
  template <class Matrix>
  void applyToRows(int posRow0, int velRow0, Matrix& J) const {
    for (int s = 0; s < size(); ++s) {
      const int i = index[s];
      J.row(posRow0 + i) = J.row(velRow0 + i) / (stiffness(s) * tau);
      J.row(velRow0 + i).setZero();
    }
  }
};

}  // namespace ffriga
