// Knot vector of a B-spline basis of degree p (Piegl & Tiller, Sect. 2.2).
//
// U = [u_0, ..., u_{n+p}] defines n = |U| - p - 1 basis functions N_{i,p}, i = 0..n-1.
// Invariants checked on construction (always, a user can cause them):
//   * p >= 0 and p <= kMaxDegree,
//   * |U| >= 2(p + 1),
//   * U is non-decreasing and u_0 < u_{n+p},
//   * U is clamped (open): the first p+1 and the last p+1 knots are equal,
//   * interior knots have multiplicity <= p (the basis is at least C^0).
// Knots are dimensionless parameter values; no range is imposed, [0, 1] is customary.
#pragma once

#include <string>
#include <vector>

namespace ffriga {

// Highest polynomial degree supported by the fixed-size work arrays of the basis routines.
constexpr int kMaxDegree = 12;

class KnotVector {
 public:
  KnotVector() = default;
  // Throws std::invalid_argument with the reason when the invariants above do not hold.
  KnotVector(std::vector<double> knots, int degree);

  // Returns an empty string when `knots` is a valid clamped knot vector of degree `degree`,
  // otherwise a one-line reason naming the offending knot index and value.
  static std::string validate(const std::vector<double>& knots, int degree);

  // Open knot vector on [a, b] with `elements` equal spans and interior multiplicity 1.
  static KnotVector uniform(int degree, int elements, double a = 0.0, double b = 1.0);

  int degree() const { return degree_; }
  int size() const { return static_cast<int>(knots_.size()); }
  int numBasis() const { return size() - degree_ - 1; }
  const std::vector<double>& knots() const { return knots_; }
  const double* data() const { return knots_.data(); }
  double operator[](int i) const { return knots_[i]; }
  double front() const { return knots_.front(); }
  double back() const { return knots_.back(); }

  // Piegl & Tiller A2.1: the span index i with u_i <= u < u_{i+1}, p <= i <= n - 1. The
  // right end u = u_{n+p} belongs to the last non-empty span. u outside [front, back] is
  // clamped to the nearest end.
  int findSpan(double u) const;

  // Distinct knot values (breakpoints) in increasing order.
  std::vector<double> breaks() const;
  // Multiplicity of the knot value u (0 if u is not a knot).
  int multiplicity(double u) const;
  // Number of non-empty knot spans (elements along this direction).
  int numElements() const { return static_cast<int>(breaks().size()) - 1; }
  // Span index (as returned by findSpan) of every element, in increasing order.
  std::vector<int> elementSpans() const;
  // Greville abscissae: tau_i = (u_{i+1} + ... + u_{i+p}) / p (tau_i = midpoint for p = 0).
  std::vector<double> greville() const;

  bool operator==(const KnotVector& other) const {
    return degree_ == other.degree_ && knots_ == other.knots_;
  }

 private:
  std::vector<double> knots_;
  int degree_ = 0;
};

}  // namespace ffriga
