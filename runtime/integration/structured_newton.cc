#include "runtime/integration/structured_newton.h"

#include "common/base/error.h"

namespace ffriga {

Eigen::MatrixXd StructuredJacobian::dense() const {
  Eigen::MatrixXd J = U * V.transpose();
  for (std::size_t i = 0; i < q_index.size(); ++i) {
    J(q_index[i], v_index[i]) += 1.0;
    J(v_index[i], q_index[i]) -= k(i);
    J(v_index[i], v_index[i]) -= c(i);
  }
  for (std::size_t i = 0; i < f_index.size(); ++i) J(f_index[i], f_index[i]) -= f_rate(i);
  return J;
}

void StructuredNewtonMatrix::applyNdInverse(Eigen::Ref<Eigen::VectorXd> x) const {
  // Nd is the identity outside the elastic pairs; on a pair, the inverse of
  // [[1, -g], [g k, 1 + g c]] is [[1 + g c, g], [-g k, 1]] / (1 + g c + g^2 k).
  const StructuredJacobian& J = *J_;
  const double g = gamma_;
  for (std::size_t i = 0; i < J.q_index.size(); ++i) {
    const int p = J.q_index[i], v = J.v_index[i];
    const double det = 1.0 + g * J.c(i) + g * g * J.k(i);
    const double xp = x(p), xv = x(v);
    x(p) = ((1.0 + g * J.c(i)) * xp + g * xv) / det;
    x(v) = (-g * J.k(i) * xp + xv) / det;
  }
  for (std::size_t i = 0; i < J.f_index.size(); ++i) x(J.f_index[i]) /= 1.0 + g * J.f_rate(i);
}

bool StructuredNewtonMatrix::factor(double gamma, const StructuredJacobian& J) {
  FFRIGA_ASSERT(J.U.rows() == J.n && J.V.rows() == J.n && J.U.cols() == J.V.cols(),
                "structured Jacobian: U " << J.U.rows() << "x" << J.U.cols() << ", V " << J.V.rows()
                                          << "x" << J.V.cols() << ", n " << J.n);
  J_ = &J;
  gamma_ = gamma;
  W_ = J.U;
  for (int j = 0; j < W_.cols(); ++j) applyNdInverse(W_.col(j));
  const int r = static_cast<int>(W_.cols());
  t_.resize(J.n);
  if (r == 0) return true;
  Eigen::MatrixXd C = Eigen::MatrixXd::Identity(r, r);
  C.noalias() -= gamma * (J.V.transpose() * W_);
  cap_.compute(C);
  const auto d = cap_.matrixLU().diagonal();
  return d.allFinite() && (d.array() != 0.0).all() && W_.allFinite();
}

void StructuredNewtonMatrix::solve(const double* b, double* x) const {
  const StructuredJacobian& J = *J_;
  t_ = Eigen::Map<const Eigen::VectorXd>(b, J.n);
  applyNdInverse(t_);
  if (W_.cols() > 0) {
    s_.noalias() = J.V.transpose() * t_;
    s_ = cap_.solve(s_);
    t_.noalias() += gamma_ * (W_ * s_);
  }
  Eigen::Map<Eigen::VectorXd>(x, J.n) = t_;
}

}  // namespace ffriga
