// Model order reduction of a free flexible body (paper Sect. 3.4, Eq. 13; Craig & Bampton,
// AIAA J. 6(7), 1968), with the floating frame's rigid-body content removed.
//
// Craig-Bampton: with the DOFs split into interior i and interface b,
//   fixed-interface normal modes  (K_ii - lambda M_ii) phi_i = 0   (ARPACK, shift-invert),
//   constraint modes              Psi_c = [-K_ii^{-1} K_ib; E]     (CHOLMOD, all RHS at once),
//   Psi = [[Phi_n, -K_ii^{-1} K_ib], [0, E]],
// reduced stiffness Psi^T K Psi = diag(lambda_n) (+) (K_bb - K_bi K_ii^{-1} K_ib).
// Modal: Psi = the lowest free-free elastic modes (K - lambda M) phi = 0 (shift sigma < 0
// because K is singular).
//
// Frame (the body frame K_R of the floating frame of reference, paper Sect. 2):
//   Buckens: Psi <- (E - R (R^T M R)^{-1} R^T M) Psi, i.e. every shape is M-orthogonal to
//     the rigid modes R (int rho u dV = 0, int rho x0 x u dV = 0);
//   tangent: Psi <- (E - R (C R)^{-1} C) Psi with C u = 0 the frame conditions (the
//     displacement, and in 3D the rotation, of a marker vanish).
// Either projection leaves nr directions of Psi dependent; the reduced mass matrix is
// orthonormalised in its range (eigenvalues below 1e-10 of the largest dropped: these are
// the rigid directions, reported) and the small eigenproblem K_r z = omega^2 M_r z gives
// Phi = Psi T with Phi^T M Phi = E and Phi^T K Phi = diag(omega^2) (Eq. 13).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "common/sid/body_kinds.h"
#include "preproc/assembly/elasticity_assembly.h"
#include "preproc/reduction/characteristic_constraint_modes.h"

namespace ffriga {

struct ReductionOptions {
  ReductionMethod method = ReductionMethod::kCraigBampton;
  FrameKind frame = FrameKind::kBuckens;
  int normal_modes = 0;              // fixed-interface (CB) or free-free (modal) modes
  // Craig-Bampton only, > 0: keep every fixed-interface mode below this frequency (Hz)
  // instead of a count; normal_modes is then the first guess of how many to solve for
  // (doubled until the highest lies above the cutoff).
  double mode_cutoff_hz = 0.0;
  std::vector<bool> interface;       // per DOF: on the Craig-Bampton interface
  // Craig-Bampton only, > 0: the interface's constraint modes are replaced by this many
  // elastic characteristic constraint modes (characteristic_constraint_modes.h), except the
  // DOFs marked in interface_retained (per DOF; empty: none), which keep theirs.
  int interface_modes = 0;
  std::vector<bool> interface_retained;
  // Craig-Bampton only: loads on the interface (interface DOFs in ascending order x P,
  // pressure_patches.h) whose static responses join the characteristic modes; no columns:
  // none. With loads, interface_modes may be 0.
  Eigen::MatrixXd interface_loads;
  // Whether the Craig-Bampton interface is reduced (characteristic modes or loads asked for).
  bool reducesInterface() const {
    return method == ReductionMethod::kCraigBampton &&
           (interface_modes > 0 || interface_loads.cols() > 0);
  }
  Eigen::MatrixXd interface_check_loads;  // the accuracy guard's (same layout; none: none)
  Eigen::MatrixXd rigid_modes;       // ndof x nr, the rigid-body fields
  Eigen::MatrixXd frame_conditions;  // nr x ndof, C for the tangent frame
};

struct ReducedModel {
  Eigen::MatrixXd Phi;     // ndof x nq, M-orthonormal
  Eigen::VectorXd omega2;  // nq, ascending, (rad/s)^2
  int rigid_dropped = 0;   // directions removed as rigid / dependent
  int normal_modes = 0;
  int constraint_modes = 0;  // interface coordinates in the basis (after any reduction)
  int interface_dofs = 0;    // DOFs on the Craig-Bampton interface
  // Interface reduction (options.interface_modes > 0): characteristic constraint modes kept
  // (zero ones, elastic ones) and every eigenvalue of the region's, (rad/s)^2.
  int characteristic_rigid = 0;
  int characteristic_elastic = 0;
  int patch_modes = 0;         // directions from the interface loads' static responses
  int interface_retained = 0;  // interface markers' DOFs that keep their constraint modes
  // The accuracy guard: the largest share of static compliance the reduced interface misses
  // for the check loads (characteristic_constraint_modes.h); -1: not computed.
  double interface_compliance_error = -1.0;
  Eigen::VectorXd characteristic_omega2;
  Eigen::VectorXd normal_mode_omega2;  // fixed-interface (CB) or free-free (modal) eigenvalues
  double factor_rcond = 0.0;           // CHOLMOD's estimate for K_ii (CB)
  double factor_nonzeros = 0.0;        // stored entries of K_ii's Cholesky factor (CB)
  double factor_flops = 0.0;           // operations of its numeric factorisation (CB)
  int arpack_iterations = 0;
  std::vector<std::pair<std::string, double>> timings;  // (step, wall time in s)
};

// Throws InputError for requests the model cannot satisfy (no interface, more modes than
// DOFs) and ComputeError when a factorisation or eigen solve fails; an interface that does
// not suppress every rigid motion (K_ii singular) is reported as such.
ReducedModel reduceBody(const SparseMatrix& K, const SparseMatrix& M,
                        const ReductionOptions& options);

}  // namespace ffriga
