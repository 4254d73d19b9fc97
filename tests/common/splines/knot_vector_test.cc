#include "common/splines/knot_vector.h"

#include <catch2/catch.hpp>

#include "tests/support/test_util.h"

using namespace ffriga;

TEST_CASE("knot vector validation names the offending knot", "[knot_vector]") {
  CHECK(KnotVector::validate({0, 0, 0, 1, 1, 1}, 2).empty());
  CHECK(KnotVector::validate({0, 0, 0, 0.5, 0.5, 1, 1, 1}, 2).empty());
  const std::string decreasing = KnotVector::validate({0, 0, 0, 0.6, 0.4, 1, 1, 1}, 2);
  CHECK(decreasing.find("non-decreasing") != std::string::npos);
  CHECK(decreasing.find("knot 4") != std::string::npos);
  CHECK(KnotVector::validate({0, 0, 0.1, 1, 1, 1}, 2).find("clamped") != std::string::npos);
  CHECK(KnotVector::validate({0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}, 2).find("multiplicity") !=
        std::string::npos);
  CHECK(KnotVector::validate({0, 0, 1}, 2).find("at least 6") != std::string::npos);
  CHECK(KnotVector::validate({1, 1, 1, 1, 1, 1}, 2).find("empty") != std::string::npos);
  CHECK(KnotVector::validate({0, 0, 1, 1}, -1).find("degree") != std::string::npos);
  CHECK_THROWS_AS(KnotVector({0, 1, 0.5, 1}, 1), std::invalid_argument);
}

TEST_CASE("findSpan agrees with a linear search (Piegl & Tiller A2.1)", "[knot_vector]") {
  for (int trial = 0; trial < 50; ++trial) {
    const int p = test::uniformInt(0, 5);
    const KnotVector U = test::randomKnots(std::max(p, 1), test::uniformInt(0, 8));
    const auto& u = U.knots();
    for (int k = 0; k < 100; ++k) {
      const double x = test::uniform();
      const int s = U.findSpan(x);
      REQUIRE(u[s] <= x);
      REQUIRE(x < u[s + 1]);
    }
    // The right end belongs to the last non-empty span; knot values to the span they open.
    const int last = U.findSpan(1.0);
    CHECK(u[last] < u[last + 1]);
    CHECK(u[last + 1] == 1.0);
    for (double b : U.breaks()) {
      if (b < 1.0) CHECK(u[U.findSpan(b)] == b);
    }
  }
}

TEST_CASE("elements, breaks, multiplicities and Greville abscissae", "[knot_vector]") {
  const KnotVector U({0, 0, 0, 0.25, 0.5, 0.5, 1, 1, 1}, 2);
  CHECK(U.numBasis() == 6);
  CHECK(U.numElements() == 3);
  CHECK(U.elementSpans() == std::vector<int>{2, 3, 5});
  CHECK(U.multiplicity(0.5) == 2);
  CHECK(U.multiplicity(0.3) == 0);
  const std::vector<double> g = U.greville();
  REQUIRE(g.size() == 6u);
  CHECK(g[0] == 0.0);
  CHECK(g[1] == Approx(0.125));
  CHECK(g[5] == 1.0);
  const KnotVector V = KnotVector::uniform(3, 4);
  CHECK(V.numElements() == 4);
  CHECK(V.numBasis() == 7);
}
