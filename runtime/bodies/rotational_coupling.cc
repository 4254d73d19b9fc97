#include "runtime/bodies/rotational_coupling.h"

#include <cmath>

#include "common/base/error.h"

namespace ffriga {

namespace {
constexpr int kLanes = 8;  // partial sums of a row's dot product (two AVX2 vectors)
}  // namespace

RotationalCoupling::RotationalCoupling(const FlexibleBodySid& sid, const std::string& body)
    : nq_(sid.nq()) {
  offset_.resize(nq_ + 1);
  offset_[0] = 0;
  for (int j = 0; j < nq_; ++j) offset_[j + 1] = offset_[j] + (nq_ - j - 1);
  // Scale of the check: the largest entry, or the bound |Cr1_j(c, i)| <= sqrt(Me_jj Me_ii)
  // (Cauchy-Schwarz; 1 for mass-normalised modes) if that is larger: a body whose Cr1 is
  // round-off (e.g. modes along one line) must not be judged against its own noise.
  double largest = 0.0;
  for (int j = 0; j < nq_; ++j) largest = std::max(largest, sid.Cr1[j].cwiseAbs().maxCoeff());
  if (sid.Me.rows() == nq_ && nq_ > 0) largest = std::max(largest, sid.Me.diagonal().maxCoeff());
  double worst = 0.0;
  int wj = 0, wi = 0, wc = 0;
  for (int c = 0; c < 3; ++c) {
    upper_[c].resize(offset_[nq_]);
    for (int j = 0; j < nq_; ++j) {
      worst = std::max(worst, std::abs(sid.Cr1[j](c, j)));
      for (int i = j + 1; i < nq_; ++i) {
        const double a = sid.Cr1[j](c, i), b = sid.Cr1[i](c, j);
        if (std::abs(a + b) > worst) {
          worst = std::abs(a + b);
          wj = j, wi = i, wc = c;
        }
        upper_[c][offset_[j] + (i - j - 1)] = a;
      }
    }
  }
  if (worst > 1e-10 * largest) {
    throw InputError(Str() << "body '" << body << "': SID invariant Cr1 is not antisymmetric: "
                           << "Cr1_" << wj << "(" << wc << ", " << wi << ") + Cr1_" << wi << "("
                           << wc << ", " << wj << ") = " << worst << " against its largest entry "
                           << largest << " (Cr1_j(:, i) = int rho Phi_j~ Phi_i dV, common/sid/sid.h)");
  }
}

double RotationalCoupling::entry(int c, int j, int i) const {
  if (i == j) return 0.0;
  return i > j ? row(c, j)[i - j - 1] : -row(c, i)[j - i - 1];
}

void RotationalCoupling::apply(const Eigen::VectorXd& x,
                               Eigen::Matrix<double, Eigen::Dynamic, 3>& Z) const {
  Z.setZero(nq_, 3);
  for (int c = 0; c < 3; ++c) {
    double* __restrict z = Z.col(c).data();
    for (int j = 0; j + 1 < nq_; ++j) {
      // One pass over row j of the triangle for both of its uses:
      // z_j += sum_{i > j} G(j, i) x_i;  z_i += G(i, j) x_j = -G(j, i) x_j.
      const int len = nq_ - j - 1;
      const double* __restrict g = row(c, j);
      const double* __restrict xs = x.data() + j + 1;
      double* __restrict zs = z + j + 1;
      const double xj = x(j);
      double lane[kLanes] = {};  // kLanes partial sums: a fixed order, vectorisable
      int i = 0;
      for (; i + kLanes <= len; i += kLanes) {
        for (int l = 0; l < kLanes; ++l) {
          lane[l] += g[i + l] * xs[i + l];
          zs[i + l] -= xj * g[i + l];
        }
      }
      double sum = 0.0;
      for (int l = 0; l < kLanes; ++l) sum += lane[l];
      for (; i < len; ++i) {
        sum += g[i] * xs[i];
        zs[i] -= xj * g[i];
      }
      z[j] += sum;
    }
  }
}

void RotationalCoupling::applySparse(const Eigen::VectorXd& x,
                                     Eigen::Matrix<double, Eigen::Dynamic, 3>& Z) const {
  Z.setZero(nq_, 3);
  for (int k = 0; k < nq_; ++k) {
    const double xk = x(k);
    if (xk == 0.0) continue;
    for (int c = 0; c < 3; ++c) {
      // Column k of G_c: G(i, k) = G_c row i at k (i < k), -G_c row k at i (i > k).
      for (int i = 0; i < k; ++i) Z(i, c) += row(c, i)[k - i - 1] * xk;
      const int len = nq_ - k - 1;
      Z.col(c).segment(k + 1, len) -= xk * Eigen::Map<const Eigen::VectorXd>(row(c, k), len);
    }
  }
}

}  // namespace ffriga
