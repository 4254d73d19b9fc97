// Interface reduction of a Craig-Bampton basis by characteristic constraint modes (Castanier,
// Tan & Pierre, AIAA J. 39(6), 2001): the nb constraint modes of a contact region are
// replaced by the few shapes of the interface that are soft, which is what a smooth contact
// pressure excites.
//
// With the Craig-Bampton basis Psi = [normal modes, constraint modes] (craig_bampton.h), the
// interface block of its reduced matrices is the statically condensed (Guyan) interface
//   K_c = K_bb - K_bi K_ii^{-1} K_ib,   M_c = Psi_b^T M Psi_b,
// and the interface splits into region DOFs c and retained DOFs m (the control points of
// interface markers, whose joints need an exact attachment). The characteristic constraint
// modes are the eigenvectors of the region block with the retained DOFs fixed,
//   K_cc v_j = lambda_j M_cc v_j,   V^T M_cc V = E,   ascending,
// of which the lowest `count` elastic ones are kept; a cluster of equal eigenvalues (the
// pairs of a symmetric region) is kept whole, so the basis keeps the region's symmetry. The
// zero ones are the rigid motions of the interface that the retained DOFs leave free (all
// of them for a body without interface markers); their constraint modes are rigid motions of
// the whole body, which the frame projection removes (craig_bampton.h), so they are left out
// and count as dropped rigid directions. A retained DOF keeps its physical constraint mode,
// with the region responding statically:
//   s_m = [-K_cc^+ K_cm e_m; e_m],   K_cc^+ = sum over elastic j of v_j v_j^T / lambda_j,
// so that, with the zero modes, the interface basis contains every rigid motion of the
// interface exactly: for a rigid r, K_c r = 0 gives r_c = -K_cc^+ K_cm r_m + a zero-mode part.
// Loads f on the interface (pressure_patches.h) add their static responses through the
// elastic spectrum, u = K_cc^+ f_c (a free body: the loads' rigid part is balanced by
// inertia), M_cc-orthonormalised together with the kept modes (nearly parallel responses
// dropped): the basis Q of the region. The reduced coordinates become Psi T with
//   T = diag(E_nm, [Q, S]),
// the normal modes untouched. Every reduced matrix transforms as T^T A T.
//
// Accuracy guard: for check loads g (patches the basis was not built from), the share of the
// region's static compliance the basis misses,
//   e = 1 - c_Q / c,   c = g_c^T K_cc^+ g_c,   c_Q = (Q^T g_c)^T (Q^T K_cc Q)^{-1} (Q^T g_c),
// (0 <= e <= 1: Q spans a subspace of the elastic interface, so c_Q <= c, Rayleigh-Ritz).
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace ffriga {

struct InterfaceReduction {
  Eigen::MatrixXd T;    // (nm + nb) x (nm + elastic + patch_modes + retained)
  int rigid = 0;        // zero-eigenvalue characteristic modes (rigid motions), left out
  int elastic = 0;      // elastic characteristic modes kept (>= the count asked for)
  int patch_modes = 0;  // further directions from the loads' static responses
  Eigen::VectorXd compliance_error;  // per check load, e of the header comment
  int retained = 0;                  // retained interface DOFs (interface markers)
  Eigen::VectorXd omega2;  // every characteristic eigenvalue of the region, (rad/s)^2, ascending
};

// Mr, Kr: the reduced mass and stiffness of the Craig-Bampton basis (before any frame
// projection), nm normal modes first, then the nb interface DOFs in the basis' order;
// retained[k]: interface DOF k keeps its physical constraint mode. count: elastic
// characteristic modes asked for (capped at what the region has; 0 only with loads).
// loads: nb x P generalized forces on the interface (none: no columns); check_loads: the
// guard's, nb x C (none: no columns). Throws ComputeError
// if an eigen solve fails or the region's mass block is not positive definite.
InterfaceReduction characteristicConstraintModes(
    const Eigen::MatrixXd& Mr, const Eigen::MatrixXd& Kr, int nm, const std::vector<bool>& retained,
    int count, const Eigen::MatrixXd& loads = Eigen::MatrixXd(),
    const Eigen::MatrixXd& check_loads = Eigen::MatrixXd());

}  // namespace ffriga
