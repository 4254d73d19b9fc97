// Flexible body in 3D in the floating frame of reference: paper Eq. (1) with the SID
// invariants of common/sid/sid.h (first order in q, Wallrapp's SID).
//
// Body-frame velocity of a material point x = x0 + Phi q:  v + w x x + Phi qdot, so with
// z = [v, w, qdot] the kinetic energy is T = 1/2 z^T M(q) z with (Eq. 1)
//
//   M = [ m E      m c~^T   Ct^T   ]     m c(q) = m c0 + Ct^T q
//       [ m c~     J(q)     Cr(q)^T]     J(q)   = J0 + sum_j q_j J1_j
//       [ Ct       Cr(q)    Me     ]     Cr(q)^T = Cr0^T + sum_j q_j Cr1_j.
//
// The quadratic velocity vector h_omega follows from T by the Euler-Poincare equations in
// body components (so linear momentum, angular momentum and energy of this T are
// conserved exactly by the continuous equations):
//   P = m v + w x m c + Ct^T qdot,            l = m c x v + J w + Cr^T qdot,
//   h_omega,v = w x (Ct^T qdot) + w x P,
//   h_omega,w = (Ct^T qdot) x v + (sum_j qdot_j J1_j) w + (sum_j qdot_j Cr1_j) qdot
//               + w x l + v x P,
//   h_omega,q = (sum_j qdot_j Cr1_j)^T w + Ct (w x v) - 1/2 [w^T J1_i w]_i - [w^T Cr1_i qdot]_i.
// The centrifugal elastic load -1/2 w^T J1_i w equals the SID's Oe term (sid.h), which is
// therefore not needed. Inner forces h_e = Ke q + De qdot; gravity g (inertial):
// h_b = [m g_b, m c x g_b, Ct g_b] with g_b = A^T g.
// The mass matrix is solved by the Schur complement on the 6 rigid rows,
// S = M_rr - C^T Me^-1 C with C = [Ct, Cr], which costs O(nq) for Me = E.
// The Cr1 sums are evaluated through the antisymmetry of Cr1 (rotational_coupling.h):
// with Z = [G_c q] and Y = [G_c qdot], Cr(q) = Cr0 - Z, (sum_j qdot_j Cr1_j)^T = -Y, the
// term (sum_j qdot_j Cr1_j) qdot vanishes and the Coriolis load on q is -2 Y w.
#pragma once

#include <vector>

#include "runtime/bodies/body_model.h"
#include "runtime/bodies/rotational_coupling.h"

namespace ffriga {

class FloatingBody3d : public BodyModel {
 public:
  FloatingBody3d(std::string name, std::shared_ptr<const FlexibleBodySid> sid);

  int numRigidPositions() const override { return 7; }
  int numRigidVelocities() const override { return 6; }

  BodyPose pose(const double* sp) const override;
  void positionRates(const double* sp, const double* sv, double* spdot) const override;
  void accelerations(const double* sp, const double* sv, const double* h_applied,
                     const Eigen::Vector3d& gravity, double* accel) const override;
  void solveMass(const double* sp, Eigen::MatrixXd& B) const override;
  void massBlocks(const double* sp, Eigen::MatrixXd& C, Eigen::MatrixXd& Mrr) const override;
  Eigen::VectorXd pointVelocity(const BodyPose& pose, const double* sv, const VectorRef& x,
                                const VectorRef& u_dot) const override;
  void pointGradients(const BodyPose& pose, const VectorRef& x, const Eigen::MatrixXd& Phi_x,
                      const VectorRef& n, Eigen::VectorXd& bv, Eigen::VectorXd& bp) const override;
  void addRigidPointForce(const BodyPose& pose, const VectorRef& x, const VectorRef& f,
                          double* h) const override;
  double kineticEnergy(const double* sp, const double* sv) const override;
  double gravityEnergy(const double* sp, const Eigen::Vector3d& gravity) const override;
  void momentum(const double* sp, const double* sv, Eigen::Vector3d& linear,
                Eigen::Vector3d& angular) const override;
  void normalize(double* sp) const override;

  // The q-dependent invariants at q.
  struct Invariants {
    Eigen::Vector3d mc;   // m c(q)
    Eigen::Matrix3d J;    // J(q)
    Eigen::MatrixXd CrT;  // Cr(q)^T, 3 x nq
  };
  Invariants invariants(const Eigen::VectorXd& q) const;
  // G_c q and G_c qdot (rotational_coupling.h), from the cache when q (qdot) is bit for bit
  // the last one asked for.
  const Eigen::Matrix<double, Eigen::Dynamic, 3>& couplingOfPositions(const Eigen::VectorXd& q) const;
  const Eigen::Matrix<double, Eigen::Dynamic, 3>& couplingOfRates(const Eigen::VectorXd& qd) const;
  // Throws InputError if the SID's Oe (when present) contradicts J1 (sid.h).
  void checkCentrifugalInvariants() const;
  // Full mass matrix M(q) (6 + nq square), for tests and energies.
  Eigen::MatrixXd massMatrix(const Eigen::VectorXd& q) const;

 private:
  static std::shared_ptr<const RotationalCoupling> sharedCoupling(const FlexibleBodySid& sid,
                                                                  const std::string& body);
  // Shared by the bodies of one SID.
  std::shared_ptr<const RotationalCoupling> coupling_;
  // Last arguments and results of couplingOf*: accelerations() is called with the same q
  // for every rigid column of the Jacobian. Not for concurrent calls on one body.
  struct CouplingCache {
    Eigen::VectorXd x;
    Eigen::Matrix<double, Eigen::Dynamic, 3> G;
    bool valid = false;
  };
  mutable CouplingCache positions_, rates_;
};

}  // namespace ffriga
