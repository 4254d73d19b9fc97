#include "preproc/geometry/geometry_builders.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "common/splines/gauss_legendre.h"
#include "common/splines/refinement.h"
#include "tests/support/test_util.h"

using namespace ffriga;

namespace {

const double kPi = std::acos(-1.0);

// Integral of f(x, detJ) over the patch by Gauss quadrature with n points per direction
// and element; returns sum f * |det J| * weights.
template <typename F>
double integrate(const NurbsPatch& patch, int n, F f) {
  const int d = patch.paramDim();
  std::vector<std::vector<double>> breaks;
  for (int a = 0; a < d; ++a) breaks.push_back(patch.knots(a).breaks());
  double sum = 0.0;
  std::vector<int> e(d, 0);
  while (true) {
    std::vector<QuadratureRule> rules;
    for (int a = 0; a < d; ++a)
      rules.push_back(gaussLegendre(n, breaks[a][e[a]], breaks[a][e[a] + 1]));
    const int nz = d > 2 ? n : 1;
    for (int k = 0; k < nz; ++k) {
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          double xi[3] = {rules[0].points[i], rules[1].points[j], d > 2 ? rules[2].points[k] : 0};
          double w = rules[0].weights[i] * rules[1].weights[j] * (d > 2 ? rules[2].weights[k] : 1);
          const PatchPoint pt = patch.evaluate(xi, 1);
          const double detJ = pt.dx.determinant();
          REQUIRE(detJ > 0.0);  // orientation and regularity at every interior Gauss point
          sum += f(pt.x) * detJ * w;
        }
      }
    }
    int a = 0;
    while (a < d && ++e[a] == static_cast<int>(breaks[a].size()) - 1) e[a++] = 0;
    if (a == d) break;
  }
  return sum;
}

NurbsPatch paperRefinedHalfDisk(double r) {
  // Sect. 5: degree raised by 2 (p = 4, q = 3), 15 and 24 knots inserted.
  NurbsPatch patch = halfDisk(r);
  patch = elevateDegree(elevateDegree(patch, 0, 2), 1, 2);
  patch = insertKnots(patch, 0, uniformInsertionKnots(patch.knots(0), 15));
  return insertKnots(patch, 1, uniformInsertionKnots(patch.knots(1), 24));
}

}  // namespace

TEST_CASE("half-disk of Eq. (19): boundary arcs on the exact circle", "[geometry]") {
  const double r = 0.01;
  for (const NurbsPatch& patch : {halfDisk(r), paperRefinedHalfDisk(r)}) {
    double worst = 0.0;
    for (int k = 0; k < 1000; ++k) {
      double xi[2] = {test::uniform(), k % 2 == 0 ? 0.0 : 1.0};
      worst = std::max(worst, std::abs(patch.evaluate(xi).x.norm() - r) / r);
    }
    // 1e-14 relative (issue #2): rational evaluation costs a few ulp.
    CHECK(worst <= 1e-14);
    double axis[2] = {0.0, test::uniform()};
    CHECK(std::abs(patch.evaluate(axis).x(0)) <= 1e-18);
  }
}

TEST_CASE("paper's refined half-disk has the hand-counted elements and control points",
          "[geometry]") {
  const NurbsPatch patch = paperRefinedHalfDisk(0.01);
  CHECK(patch.degree(0) == 4);
  CHECK(patch.degree(1) == 3);
  // 16 x 25 = 400 elements; n = elements + degree per direction.
  CHECK(patch.knots(0).numElements() == 16);
  CHECK(patch.knots(1).numElements() == 25);
  CHECK(patch.numElements() == 400);
  CHECK(patch.numBasis(0) == 20);
  CHECK(patch.numBasis(1) == 28);
  CHECK(patch.numControlPoints() == 560);
  // The collapsed edge xi = 1 keeps its 28 control points at (r, 0): one group.
  const auto groups = coincidentControlPoints(patch, 1e-14);
  REQUIRE(groups.size() == 1u);
  CHECK(groups[0].size() == 28u);
}

TEST_CASE("areas and volumes by Gauss quadrature", "[geometry]") {
  const double r = 0.01;
  const auto one = [](const Eigen::VectorXd&) { return 1.0; };
  // Half-disk area pi r^2 / 2 and, as body of revolution (dV = 2 pi x dA), 4/3 pi r^3.
  // The integrands are rational, not polynomial: Gauss quadrature converges exponentially
  // but is not exact, so the single-element patches get 20 points per direction.
  for (const auto& [patch, n] : {std::pair{halfDisk(r), 20}, {paperRefinedHalfDisk(r), 6}}) {
    const double area = integrate(patch, n, one);
    CHECK(std::abs(area / (kPi * r * r / 2) - 1.0) <= 1e-12);
    const double vol = integrate(patch, n, [](const Eigen::VectorXd& x) { return 2 * kPi * x(0); });
    CHECK(std::abs(vol / (4 * kPi * r * r * r / 3) - 1.0) <= 1e-12);
  }
  const double vs = integrate(solidSphere(r), 20, one);
  CHECK(std::abs(vs / (4 * kPi * r * r * r / 3) - 1.0) <= 1e-12);
  const double a = 0.002;
  const double L = 0.1;
  const double vr = integrate(solidRod(a, L), 20, one);
  CHECK(std::abs(vr / (kPi * a * a * L) - 1.0) <= 1e-12);
}

TEST_CASE("solid sphere: surface on the exact sphere, contact point at +z", "[geometry]") {
  const double r = 0.01;
  NurbsPatch refined = solidSphere(r);
  for (int a = 0; a < 3; ++a) refined = elevateDegree(refined, a, 1);
  for (int a = 0; a < 3; ++a) {
    refined = insertKnots(refined, a, uniformInsertionKnots(refined.knots(a), 3));
  }
  for (const NurbsPatch& patch : {solidSphere(r), refined}) {
    double worst = 0.0;
    for (int k = 0; k < 1000; ++k) {
      double xi[3] = {test::uniform(), k % 2 == 0 ? 0.0 : 1.0, test::uniform()};
      worst = std::max(worst, std::abs(patch.evaluate(xi).x.norm() - r) / r);
    }
    CHECK(worst <= 1e-14);
    const Eigen::VectorXd c = patch.evaluate(kSphereContactXi).x;
    CHECK((c - Eigen::Vector3d(0, 0, r)).norm() <= 1e-15 * r * 10);
    // The contact region around +z is regular: the surface Jacobian has full rank.
    const PatchPoint pt = patch.evaluate(kSphereContactXi, 1);
    const Eigen::Vector3d t0 = pt.dx.col(0);
    const Eigen::Vector3d t2 = pt.dx.col(2);
    CHECK(t0.cross(t2).norm() > 0.1 * r * r);
  }
  // Degenerate points are reported: axis, equator and seam have coincident control points.
  CHECK(!coincidentControlPoints(solidSphere(r), 1e-14).empty());
}

TEST_CASE("solid rod: lateral surface on the exact cylinder", "[geometry]") {
  const double a = 0.002;
  const double L = 0.1;
  const NurbsPatch rod = solidRod(a, L);
  double worst = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const int edge = k % 4;
    const double t = test::uniform();
    double xi[3] = {edge < 2 ? t : (edge == 2 ? 0.0 : 1.0), edge < 2 ? (edge == 0 ? 0.0 : 1.0) : t,
                    test::uniform()};
    const Eigen::VectorXd x = rod.evaluate(xi).x;
    worst = std::max(worst, std::abs(std::hypot(x(0), x(1)) - a) / a);
  }
  CHECK(worst <= 1e-14);
  CHECK(coincidentControlPoints(rod, 1e-14).empty());
  CHECK_THROWS_WITH(solidRod(-1.0, 1.0), Catch::Contains("radius must be a positive number"));
}
