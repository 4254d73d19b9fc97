// The first-order rotational coupling of a flexible 3D body, Cr1 of common/sid/sid.h, as three
// antisymmetric matrices: with G_c(j, i) = Cr1_j(c, i) = int rho (Phi_j x Phi_i)_c dV,
//
//   G_c^T = -G_c        (the cross product is antisymmetric),
//
// so the q-dependent coupling and the rate terms of floating_body.h reduce to two vectors
// per component, Z(:, c) = G_c q and Y(:, c) = G_c qdot (nq x 3 each):
//
//   Cr(q)       = Cr0 - Z                   (Cr(q)^T = Cr0^T + sum_j q_j Cr1_j),
//   (sum_j qdot_j Cr1_j)^T        = -Y,
//   (sum_j qdot_j Cr1_j) qdot     = -Y^T qdot = 0          (qdot^T G_c qdot = 0),
//   [w . (Cr1_i qdot)]_i          = (Y w)_i.
//
// Cost: G_c is stored once per SID as its strict upper triangle (3 nq (nq - 1) / 2 numbers,
// half of Cr1) and Z, Y take one pass over it, O(nq^2): Cr1 is dense and of full rank (the
// singular values of the G_c of sphere3d_coarse are 0.99 .. 1e-3 of the largest over all
// 607 coordinates; benchmarks/README.md), so no exact O(nq) form exists. What is O(nq):
// Y for a qdot with few non-zero entries (quasi-static coordinates have qdot = 0) costs
// O(nq) per non-zero entry, and a body caches Z and Y for the last q and qdot (the
// Jacobian's rigid columns change neither).
// Units: G_c dimensionless (kg m^2 / (kg^(1/2) m)^2), Z, Y in kg^(1/2) m and kg^(1/2) m/s.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "common/sid/sid.h"

namespace ffriga {

class RotationalCoupling {
 public:
  // Reads G_c from sid.Cr1. Throws InputError naming `body` if Cr1 is not antisymmetric to
  // 1e-10 of its largest entry (an SID from another convention or a broken writer).
  RotationalCoupling(const FlexibleBodySid& sid, const std::string& body);

  int nq() const { return nq_; }
  // Z(:, c) = G_c x for dense x.
  void apply(const Eigen::VectorXd& x, Eigen::Matrix<double, Eigen::Dynamic, 3>& Z) const;
  // The same, in O(nq) per non-zero entry of x (for rates with quasi-static zeros).
  void applySparse(const Eigen::VectorXd& x, Eigen::Matrix<double, Eigen::Dynamic, 3>& Z) const;
  // G_c(j, i).
  double entry(int c, int j, int i) const;

 private:
  // Row j of the strict upper triangle of G_c: entries (j, j + 1 .. nq - 1).
  const double* row(int c, int j) const { return upper_[c].data() + offset_[j]; }
  int nq_ = 0;
  std::vector<std::size_t> offset_;  // start of row j in upper_[c]
  std::vector<double> upper_[3];
};

}  // namespace ffriga
