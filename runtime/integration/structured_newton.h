// The Newton matrix of the BDF corrector, N = I - gamma J, for a Jacobian with the structure
// of reduced flexible bodies (DESIGN.md, "Time integration"):
//
//   J = D + U V^T,
//
// D: 2 x 2 blocks d/dt [q_i; qdot_i] = [qdot_i; -k_i q_i - c_i qdot_i] of the elastic
//    coordinates (Me = E, Ke = diag(k), De = diag(c), Eq. 13), 1 x 1 blocks
//    d/dt y_j = -rate_j y_j of the quasi-static coordinates (runtime/bodies/
//    quasi_static_modes.h: rate = 1 / tau), zero elsewhere;
// U V^T: low rank r: the rigid-body rows and columns, the inertial coupling of the rigid and
//    elastic coordinates through M(q)^-1, and one term per active contact point (Eq. 17-18).
//
// N = Nd - gamma U V^T with Nd = I - gamma D is solved by the Sherman-Morrison-Woodbury
// formula,
//   N^-1 b = Nd^-1 b + gamma W (I_r - gamma V^T W)^-1 V^T Nd^-1 b,   W = Nd^-1 U,
// at O(n r^2 + r^3) per factorisation and O(n r) per solve, against O(n^3) and O(n^2) for a
// dense LU: the difference between minutes and seconds for 3D bodies with hundreds of
// elastic coordinates. Each 2 x 2 block of Nd, [[1, -g], [g k, 1 + g c]], has determinant
// 1 + g c + g^2 k >= 1 for k, c >= 0; a 1 x 1 block is 1 + g rate >= 1.
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace ffriga {

struct StructuredJacobian {
  int n = 0;                          // size of the state
  std::vector<int> q_index, v_index;  // state indices of each elastic pair (q_i, qdot_i)
  Eigen::VectorXd k, c;               // 1/s^2 and 1/s: stiffness and damping of each pair
  std::vector<int> f_index;           // state indices of the first-order (quasi-static) entries
  Eigen::VectorXd f_rate;             // 1/s: their decay rates
  Eigen::MatrixXd U, V;               // n x r
  Eigen::MatrixXd dense() const;      // D + U V^T (tests)
};

class StructuredNewtonMatrix {
 public:
  // Factorises N = I - gamma J. Returns false if the capacitance matrix is singular or the
  // result is not finite (CVODE then retries with a smaller step).
  bool factor(double gamma, const StructuredJacobian& J);
  // x = N^-1 b (x and b may alias).
  void solve(const double* b, double* x) const;

 private:
  void applyNdInverse(Eigen::Ref<Eigen::VectorXd> x) const;
  const StructuredJacobian* J_ = nullptr;
  double gamma_ = 0.0;
  Eigen::MatrixXd W_;  // Nd^-1 U
  Eigen::PartialPivLU<Eigen::MatrixXd> cap_;
  mutable Eigen::VectorXd t_, s_;
};

}  // namespace ffriga
