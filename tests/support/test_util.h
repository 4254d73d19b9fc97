// Helpers shared by the unit tests: seeded random numbers, random knot vectors, and texts
// (scene files) with one part replaced.
#pragma once

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "common/splines/knot_vector.h"
#include "common/splines/nurbs_patch.h"

namespace ffriga::test {

inline std::mt19937& rng() {
  static std::mt19937 gen(20261122);
  return gen;
}
inline double uniform(double a = 0.0, double b = 1.0) {
  return std::uniform_real_distribution<double>(a, b)(rng());
}
inline int uniformInt(int a, int b) {
  return std::uniform_int_distribution<int>(a, b)(rng());
}

// Random clamped knot vector on [a, b] of degree p with `interior` distinct interior knots,
// some repeated (multiplicity <= p).
inline KnotVector randomKnots(int p, int interior, double a = 0.0, double b = 1.0) {
  std::vector<double> U(p + 1, a);
  std::vector<double> inner;
  for (int i = 0; i < interior; ++i)
    inner.push_back(uniform(a + 0.05 * (b - a), b - 0.05 * (b - a)));
  std::sort(inner.begin(), inner.end());
  for (double u : inner) {
    const int mult = p >= 2 && uniform() < 0.2 ? uniformInt(1, p) : 1;
    U.insert(U.end(), std::max(1, std::min(mult, p)), u);
  }
  U.insert(U.end(), p + 1, b);
  return KnotVector(U, p);
}

// Random NURBS patch with d parametric directions in s-dimensional space: degrees 1..4,
// 0..3 interior knots per direction, coordinates in [-1, 1], weights in [0.3, 2].
inline NurbsPatch randomPatch(int d, int s) {
  std::vector<KnotVector> U;
  int n = 1;
  for (int a = 0; a < d; ++a) {
    U.push_back(randomKnots(uniformInt(1, 4), uniformInt(0, 3)));
    n *= U.back().numBasis();
  }
  Eigen::MatrixXd P = Eigen::MatrixXd::Random(n, s);
  Eigen::VectorXd w(n);
  for (int k = 0; k < n; ++k) w(k) = uniform(0.3, 2.0);
  return NurbsPatch(U, P, w);
}

// `s` with the first occurrence of `from` replaced by `to` (the test fails if there is none).
inline std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const std::size_t pos = s.find(from);
  REQUIRE(pos != std::string::npos);
  return s.replace(pos, from.size(), to);
}

}  // namespace ffriga::test
