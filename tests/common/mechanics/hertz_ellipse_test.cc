// Hertz's elliptical contact (common/mechanics/hertz_ellipse.h): the circle's limit against
// the spheres' closed form, Johnson's second curvature equation (which the solver does not
// use) satisfied by the ellipse found from the first, the load scaling a ~ F^(1/3),
// delta ~ F^(2/3), and the ellipse's aspect ratio against an independent solution of
// Johnson's shape equation (K and E by the trapezoidal rule on 400,001 points, a / b by
// bisection, numpy: 1.27500, 2.50071, 8.87618, 18.1871 for B / A = 1.44, 4, 30, 100) and
// Brewe & Hamrock's fit (NASA TN D-8510, 1977: a / b = 1.0339 (B / A)^0.636; within 3.5 %
// up to B / A = 30, 6 % off at 100); the relative curvatures of two surfaces at an angle
// against the eigenvalues of their summed curvature tensors.
#include <catch2/catch.hpp>

#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "common/mechanics/hertz.h"
#include "common/mechanics/hertz_ellipse.h"

namespace ffriga {
namespace {

constexpr double kEs = 1.16e11;  // steel on steel, E* = E / (2 (1 - nu^2)), Pa

TEST_CASE("elliptical Hertz: the circle's limit", "[hertz]") {
  const double R = 0.005;  // R* of two spheres r = 1 cm: A = B = 1 / (2 R*)
  for (double ratio : {1.0, 1.0 + 1e-9}) {
    const HertzEllipse h = hertzEllipse(0.5 / R, ratio * 0.5 / R, kEs, 146.0);
    const double a = std::cbrt(3.0 * 146.0 * R / (4.0 * kEs));
    CHECK(h.semi_major == Approx(a).epsilon(1e-8));
    CHECK(h.semi_minor == Approx(a).epsilon(1e-8));
    CHECK(h.approach == Approx(a * a / R).epsilon(1e-8));
    CHECK(h.stiffness == Approx(4.0 / 3.0 * kEs * std::sqrt(R)).epsilon(1e-8));
  }
  CHECK(ellipseEccentricity(1.0) == 0.0);
  CHECK(ellipseApproachLength(1e-4, 1e-4) == 1e-4);
  CHECK(ellipseApproachLength(1e-4, 0.0) == 1e-4);  // b not given
}

TEST_CASE("elliptical Hertz: relative curvatures of two surfaces at an angle", "[hertz]") {
  // Against the gap's quadratic form: h = x^T (C + C') x / 2 with the curvature tensors
  // C = k1 d1 d1^T + k2 d2 d2^T; A and B are the eigenvalues of (C + C') / 2.
  const auto tensor = [](double k1, double k2, double angle) {
    const Eigen::Vector2d d1(std::cos(angle), std::sin(angle)), d2(-d1(1), d1(0));
    return Eigen::Matrix2d(k1 * d1 * d1.transpose() + k2 * d2 * d2.transpose());
  };
  for (double alpha : {0.0, 0.3, 0.7854, 1.2, M_PI / 2}) {
    const double k1 = 55.6, k2 = 80.0, kp1 = 0.0, kp2 = 50.0;
    const Eigen::Vector2d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(
                                   0.5 * (tensor(k1, k2, 0.0) + tensor(kp1, kp2, alpha)))
                                   .eigenvalues();
    const RelativeCurvatures r = relativeCurvatures(k1, k2, kp1, kp2, std::cos(alpha));
    CHECK(r.A == Approx(ev(0)).epsilon(1e-12));
    CHECK(r.B == Approx(ev(1)).epsilon(1e-12));
  }
  // Aligned; a sphere on a cylinder; equal cylinders crossed at right angles: a circle.
  const RelativeCurvatures aligned = relativeCurvatures(1.0, 3.0, 2.0, 5.0, 1.0);
  CHECK(aligned.A == Approx(1.5));
  CHECK(aligned.B == Approx(4.0));
  const RelativeCurvatures onCylinder = relativeCurvatures(100.0, 100.0, 0.0, 50.0, 0.3);
  CHECK(onCylinder.A == Approx(50.0));
  CHECK(onCylinder.B == Approx(75.0));
  const RelativeCurvatures parallel = relativeCurvatures(0.0, 50.0, 0.0, 50.0, 1.0);
  CHECK(parallel.A == Approx(0.0).margin(1e-12));  // parallel cylinders: a line
  CHECK(parallel.B == Approx(50.0));
  const RelativeCurvatures square = relativeCurvatures(0.0, 50.0, 0.0, 50.0, std::cos(M_PI / 2));
  CHECK(square.A == Approx(25.0));
  CHECK(square.B == Approx(25.0));
}

TEST_CASE("elliptical Hertz: both curvature equations and the load scaling", "[hertz]") {
  const std::vector<std::pair<double, double>> cases = {
      {1.001, 0.0}, {1.44, 1.27500}, {4.0, 2.50071}, {30.0, 8.87618}, {100.0, 18.1871}};
  for (const auto& [ratio, aspect] : cases) {
    const double A = 50.0, B = ratio * A, F = 20.0;
    const HertzEllipse h = hertzEllipse(A, B, kEs, F);
    const double e = h.eccentricity, a = h.semi_major, b = h.semi_minor;
    const double K = std::comp_ellint_1(e), E = std::comp_ellint_2(e);
    // Johnson (4.39): A and B from p0, a, b, e.
    const double c = h.max_pressure * b / (kEs * e * e * a * a);
    CHECK(c * (K - E) == Approx(A).epsilon(1e-9));
    CHECK(c * (a * a / (b * b) * E - K) == Approx(B).epsilon(1e-9));
    CHECK(h.max_pressure == Approx(3.0 * F / (2.0 * M_PI * a * b)).epsilon(1e-14));
    // F = K_e delta^(3/2) at any load.
    const HertzEllipse h8 = hertzEllipse(A, B, kEs, 8.0 * F);
    CHECK(h8.semi_major == Approx(2.0 * a).epsilon(1e-12));
    CHECK(h8.approach == Approx(4.0 * h.approach).epsilon(1e-12));
    CHECK(h8.stiffness == Approx(h.stiffness).epsilon(1e-12));
    if (aspect > 0.0) CHECK(a / b == Approx(aspect).epsilon(1e-5));
    // The approach as a circle's: delta = pi p0 L / (2 E*).
    CHECK(h.approach ==
          Approx(M_PI * h.max_pressure * ellipseApproachLength(a, b) / (2.0 * kEs)).epsilon(1e-12));
    if (ratio <= 30.0) CHECK(a / b == Approx(1.0339 * std::pow(ratio, 0.636)).epsilon(0.035));
  }
}

TEST_CASE("elliptical Hertz: an impact with the elliptical law", "[hertz]") {
  // The law F = K_e delta^1.5 in hertzImpact: the spheres' impact for A = B.
  const HertzSphere s{2.11e11, 0.3, 0.01, 0.0329};
  const HertzImpact spheres = hertzImpact(s, s, 0.2);
  const HertzImpact law = hertzImpact(hertzStiffness(s, s), 0.0329 / 2, 0.2);
  CHECK(law.max_force == Approx(spheres.max_force).epsilon(1e-14));
  CHECK(law.duration == Approx(spheres.duration).epsilon(1e-14));
  CHECK_THROWS(hertzEllipse(0.0, 1.0, kEs, 1.0));
}

}  // namespace
}  // namespace ffriga
