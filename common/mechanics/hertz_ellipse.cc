#include "common/mechanics/hertz_ellipse.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/base/error.h"

namespace ffriga {

namespace {

// (B / A)(e) of the header, as a function of s = b / a in (0, 1]: decreasing from infinity
// (s -> 0) to 1 (s = 1). Near s = 1 both numerator and denominator vanish like e^2: the
// series K - E = pi e^2 / 4 (1 + 3 e^2 / 8 + ...), (E / s^2 - K) = pi e^2 / 4 (1 + 9 e^2 / 8
// + ...) keeps the quotient accurate there.
double curvatureRatio(double s) {
  const double e2 = 1.0 - s * s;
  if (e2 < 1e-6) return (1.0 + 9.0 * e2 / 8.0) / (1.0 + 3.0 * e2 / 8.0);
  const double e = std::sqrt(e2);
  const double K = std::comp_ellint_1(e), E = std::comp_ellint_2(e);
  return (E / (s * s) - K) / (K - E);
}

}  // namespace

double ellipseEccentricity(double b_over_a) {
  if (!(b_over_a >= 1.0) || b_over_a > 1e6)
    throw std::invalid_argument(Str()
                                << "curvature ratio B / A = " << b_over_a << " outside [1, 1e6]");
  if (b_over_a == 1.0) return 0.0;
  // Bisection on log s, s = b / a in [1e-9, 1]: 200 halvings reach round-off.
  double lo = std::log(1e-9), hi = 0.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (curvatureRatio(std::exp(mid)) > b_over_a ? lo : hi) = mid;
  }
  const double s = std::exp(0.5 * (lo + hi));
  return std::sqrt(1.0 - s * s);
}

RelativeCurvatures relativeCurvatures(double k1, double k2, double kp1, double kp2,
                                      double cos_alpha) {
  const double d = k1 - k2, dp = kp1 - kp2;
  const double cos2 = 2.0 * cos_alpha * cos_alpha - 1.0;
  const double sum = 0.5 * (k1 + k2 + kp1 + kp2);
  const double diff = 0.5 * std::sqrt(std::max(0.0, d * d + dp * dp + 2.0 * d * dp * cos2));
  return {0.5 * (sum - diff), 0.5 * (sum + diff)};
}

double ellipseApproachLength(double a, double b) {
  if (!(b > 0.0) || b >= a) return a;
  return 2.0 * b * std::comp_ellint_1(std::sqrt(1.0 - b * b / (a * a))) / M_PI;
}

HertzEllipse hertzEllipse(double A, double B, double effective_modulus, double force) {
  if (A > B) std::swap(A, B);
  if (!(A > 0.0) || !(effective_modulus > 0.0) || !(force > 0.0))
    throw std::invalid_argument(Str() << "elliptical Hertz contact needs A > 0, E* > 0, F > 0; "
                                      << "found A = " << A << " 1/m, E* = " << effective_modulus
                                      << " Pa, F = " << force << " N");
  HertzEllipse h;
  h.eccentricity = ellipseEccentricity(B / A);
  const double e = h.eccentricity, e2 = e * e;
  const double s = std::sqrt(1.0 - e2);  // b / a
  if (e2 < 1e-6) {  // the circle's limit: (K - E) / e^2 -> pi / 4 (1 + 3 e^2 / 8)
    h.semi_major = std::cbrt(3.0 * force * M_PI / 4.0 * (1.0 + 3.0 * e2 / 8.0) /
                             (2.0 * M_PI * effective_modulus * A));
  } else {
    const double K = std::comp_ellint_1(e), E = std::comp_ellint_2(e);
    h.semi_major = std::cbrt(3.0 * force * (K - E) / (2.0 * M_PI * effective_modulus * e2 * A));
  }
  h.semi_minor = s * h.semi_major;
  h.max_pressure = 3.0 * force / (2.0 * M_PI * h.semi_major * h.semi_minor);
  h.approach = h.max_pressure * h.semi_minor * std::comp_ellint_1(e) / effective_modulus;
  h.stiffness = force / std::pow(h.approach, 1.5);
  return h;
}

HertzImpact ellipticalHertzImpact(const RelativeCurvatures& r, const HertzSphere& a,
                                  const HertzSphere& b, double v, double preload) {
  const double m = 1.0 / (1.0 / a.mass + 1.0 / b.mass);
  return hertzImpact(hertzEllipse(r.A, r.B, effectiveModulus(a, b), 1.0).stiffness, m, v, preload);
}

}  // namespace ffriga
