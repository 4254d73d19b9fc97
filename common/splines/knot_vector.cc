#include "common/splines/knot_vector.h"

#include <algorithm>
#include <stdexcept>

#include "common/base/error.h"

namespace ffriga {

std::string KnotVector::validate(const std::vector<double>& U, int p) {
  if (p < 0 || p > kMaxDegree) {
    return Str() << "degree " << p << " is outside the supported range 0.." << kMaxDegree;
  }
  const int m = static_cast<int>(U.size());
  if (m < 2 * (p + 1)) {
    return Str() << "a knot vector of degree " << p << " needs at least " << 2 * (p + 1)
                 << " knots, found " << m;
  }
  for (int i = 1; i < m; ++i) {
    if (!(U[i] >= U[i - 1])) {
      return Str() << "knot " << i << " (" << U[i] << ") is smaller than knot " << i - 1 << " ("
                   << U[i - 1] << "): knots must be non-decreasing";
    }
  }
  if (!(U.front() < U.back())) {
    return Str() << "first and last knot are equal (" << U.front() << "): the domain is empty";
  }
  for (int i = 1; i <= p; ++i) {
    if (U[i] != U[0]) {
      return Str() << "knot vector is not clamped: the first " << p + 1
                   << " knots must be equal, knot " << i << " is " << U[i] << ", knot 0 is "
                   << U[0];
    }
    if (U[m - 1 - i] != U[m - 1]) {
      return Str() << "knot vector is not clamped: the last " << p + 1
                   << " knots must be equal, knot " << m - 1 - i << " is " << U[m - 1 - i]
                   << ", knot " << m - 1 << " is " << U[m - 1];
    }
  }
  // Interior multiplicity at most p.
  int i = p + 1;
  while (i < m - p - 1) {
    int j = i;
    while (j + 1 < m - p - 1 && U[j + 1] == U[i]) ++j;
    const int mult = j - i + 1;
    if (mult > p) {
      return Str() << "interior knot " << U[i] << " has multiplicity " << mult
                   << ", at most the degree " << p << " is allowed";
    }
    i = j + 1;
  }
  return "";
}

KnotVector::KnotVector(std::vector<double> knots, int degree)
    : knots_(std::move(knots)), degree_(degree) {
  const std::string reason = validate(knots_, degree_);
  if (!reason.empty()) throw std::invalid_argument(reason);
}

KnotVector KnotVector::uniform(int degree, int elements, double a, double b) {
  FFRIGA_CHECK(elements >= 1, "elements = " << elements);
  std::vector<double> U(degree + 1, a);
  for (int e = 1; e < elements; ++e) U.push_back(a + (b - a) * e / elements);
  U.insert(U.end(), degree + 1, b);
  return KnotVector(std::move(U), degree);
}

int KnotVector::findSpan(double u) const {
  const int n = numBasis();
  const int p = degree_;
  if (u >= knots_[n]) {
    // Last non-empty span: largest i <= n - 1 with u_i < u_{i+1}.
    int i = n - 1;
    while (i > p && knots_[i] == knots_[i + 1]) --i;
    return i;
  }
  if (u <= knots_[p]) {
    int i = p;
    while (i < n - 1 && knots_[i] == knots_[i + 1]) ++i;
    return i;
  }
  // Binary search on [p, n): u_low <= u < u_high.
  auto it = std::upper_bound(knots_.begin() + p, knots_.begin() + n + 1, u);
  return static_cast<int>(it - knots_.begin()) - 1;
}

std::vector<double> KnotVector::breaks() const {
  std::vector<double> b;
  for (double u : knots_) {
    if (b.empty() || u != b.back()) b.push_back(u);
  }
  return b;
}

int KnotVector::multiplicity(double u) const {
  return static_cast<int>(std::count(knots_.begin(), knots_.end(), u));
}

std::vector<int> KnotVector::elementSpans() const {
  std::vector<int> spans;
  for (int i = degree_; i < numBasis(); ++i) {
    if (knots_[i] < knots_[i + 1]) spans.push_back(i);
  }
  return spans;
}

std::vector<double> KnotVector::greville() const {
  const int n = numBasis();
  std::vector<double> tau(n);
  for (int i = 0; i < n; ++i) {
    if (degree_ == 0) {
      tau[i] = 0.5 * (knots_[i] + knots_[i + 1]);
      continue;
    }
    double s = 0.0;
    for (int k = 1; k <= degree_; ++k) s += knots_[i + k];
    tau[i] = s / degree_;
  }
  return tau;
}

}  // namespace ffriga
