#include "common/mechanics/hertz.h"

#include <algorithm>
#include <cmath>

#include "common/base/error.h"
#include "common/splines/gauss_legendre.h"

namespace ffriga {

namespace {

// I = int_0^1 dx / sqrt(1 - x^(5/2)). The substitution x = 1 - s^2 removes the
// inverse-square-root singularity at x = 1: I = int_0^1 2 s / sqrt(1 - (1 - s^2)^(5/2)) ds,
// a smooth integrand, which 40-point Gauss integrates to round-off.
double durationIntegral() {
  const QuadratureRule q = gaussLegendre(40, 0.0, 1.0);
  double I = 0.0;
  for (std::size_t i = 0; i < q.points.size(); ++i) {
    const double s = q.points[i];
    I += q.weights[i] * 2.0 * s / std::sqrt(1.0 - std::pow(1.0 - s * s, 2.5));
  }
  return I;
}

}  // namespace

double effectiveModulus(const HertzSphere& a, const HertzSphere& b) {
  return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
}

double effectiveRadius(const HertzSphere& a, const HertzSphere& b) {
  return 1.0 / (1.0 / a.radius + 1.0 / b.radius);
}

double hertzStiffness(const HertzSphere& a, const HertzSphere& b) {
  for (const HertzSphere* s : {&a, &b}) {
    FFRIGA_CHECK(
        s->youngs_modulus > 0 && s->radius > 0 && s->poisson_ratio > -1 && s->poisson_ratio < 0.5,
        "sphere E = " << s->youngs_modulus << ", R = " << s->radius);
  }
  return 4.0 / 3.0 * effectiveModulus(a, b) * std::sqrt(effectiveRadius(a, b));
}

namespace {

// delta_max under a steady load P: the root of f(d) = 2/5 K d^(5/2) - P d - 1/2 m* v^2,
// convex for d > 0 with f(0) < 0, so that its one positive root is found by Newton's method
// from any point to its right (monotone convergence): the unloaded root scaled up until
// f > 0.
double maxApproachUnderLoad(double K, double m, double v, double P) {
  auto f = [&](double d) { return 0.4 * K * std::pow(d, 2.5) - P * d - 0.5 * m * v * v; };
  auto df = [&](double d) { return K * std::pow(d, 1.5) - P; };
  double d = std::pow(5.0 * m * v * v / (4.0 * K), 0.4);
  while (f(d) <= 0.0) d *= 2.0;
  for (int it = 0; it < 200; ++it) {
    const double step = f(d) / df(d);
    d -= step;
    if (step <= 1e-15 * d) break;
  }
  return d;
}

// T = 2 int_0^dm dd / sqrt(g(d)), g(d) = v^2 + 2 P d / m - 4/5 K d^(5/2) / m, g(dm) = 0; with
// d = dm (1 - s^2) the integrand 2 dm s / sqrt(g) is smooth (g ~ -g'(dm) dm s^2 near s = 0).
double durationUnderLoad(double K, double m, double v, double P, double dm) {
  const QuadratureRule q = gaussLegendre(40, 0.0, 1.0);
  double I = 0.0;
  for (std::size_t i = 0; i < q.points.size(); ++i) {
    const double s = q.points[i], d = dm * (1.0 - s * s);
    const double g = v * v + 2.0 * P * d / m - 0.8 * K * std::pow(d, 2.5) / m;
    I += q.weights[i] * 2.0 * dm * s / std::sqrt(g);
  }
  return 2.0 * I;
}

}  // namespace

HertzImpact hertzImpact(const HertzSphere& a, const HertzSphere& b, double v, double preload) {
  FFRIGA_CHECK(v > 0.0, "relative speed v = " << v);
  FFRIGA_CHECK(std::isfinite(preload), "steady load P = " << preload);
  for (const HertzSphere* s : {&a, &b}) {
    FFRIGA_CHECK(s->youngs_modulus > 0 && s->radius > 0 && s->mass > 0 && s->poisson_ratio > -1 &&
                     s->poisson_ratio < 0.5,
                 "sphere E = " << s->youngs_modulus << ", R = " << s->radius);
  }
  return hertzImpact(hertzStiffness(a, b), 1.0 / (1.0 / a.mass + 1.0 / b.mass), v, preload);
}

HertzImpact hertzImpact(double stiffness, double effective_mass, double v, double preload) {
  FFRIGA_CHECK(v > 0.0 && stiffness > 0.0 && effective_mass > 0.0,
               "speed v = " << v << ", K = " << stiffness << ", m* = " << effective_mass);
  HertzImpact h;
  h.effective_mass = effective_mass;
  h.stiffness = stiffness;
  h.preload = preload;
  if (preload == 0.0) {  // closed form
    h.max_approach = std::pow(5.0 * h.effective_mass * v * v / (4.0 * h.stiffness), 0.4);
    h.duration = 2.0 * h.max_approach / v * durationIntegral();
  } else {
    h.max_approach = maxApproachUnderLoad(h.stiffness, h.effective_mass, v, preload);
    h.duration = durationUnderLoad(h.stiffness, h.effective_mass, v, preload, h.max_approach);
  }
  h.max_force = h.stiffness * std::pow(h.max_approach, 1.5);
  h.time_of_max = 0.5 * h.duration;
  return h;
}

std::vector<double> hertzForceHistory(const HertzImpact& h, double v,
                                      const std::vector<double>& t) {
  // Integrate (delta, delta') from (0, v) over [0, T]; tabulate, then interpolate
  // linearly (the table is fine enough that interpolation adds < 1e-8 relative).
  const int n = 20000;
  const double dt = h.duration / n;
  const double c = h.stiffness / h.effective_mass, p = h.preload / h.effective_mass;
  auto acc = [c, p](double d) { return d > 0.0 ? p - c * std::pow(d, 1.5) : 0.0; };
  std::vector<double> force(n + 1, 0.0);
  double d = 0.0;
  double w = v;
  for (int i = 0; i < n; ++i) {
    const double k1d = w, k1w = acc(d);
    const double k2d = w + 0.5 * dt * k1w, k2w = acc(d + 0.5 * dt * k1d);
    const double k3d = w + 0.5 * dt * k2w, k3w = acc(d + 0.5 * dt * k2d);
    const double k4d = w + dt * k3w, k4w = acc(d + dt * k3d);
    d += dt / 6.0 * (k1d + 2 * k2d + 2 * k3d + k4d);
    w += dt / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
    force[i + 1] = d > 0.0 ? h.stiffness * std::pow(d, 1.5) : 0.0;
  }
  std::vector<double> out(t.size(), 0.0);
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] <= 0.0 || t[k] >= h.duration) continue;
    const double x = t[k] / dt;
    const int i = std::min(static_cast<int>(x), n - 1);
    const double f = x - i;
    out[k] = (1.0 - f) * force[i] + f * force[i + 1];
  }
  return out;
}

HertzContactPatch hertzContactPatch(const HertzSphere& a, const HertzSphere& b, double force) {
  HertzContactPatch p;
  p.radius = std::cbrt(3.0 * force * effectiveRadius(a, b) / (4.0 * effectiveModulus(a, b)));
  p.max_pressure = p.radius > 0.0 ? 3.0 * force / (2.0 * std::acos(-1.0) * p.radius * p.radius) : 0.0;
  return p;
}

HertzAxisStress hertzAxisStress(double z, double a, double p0, double nu) {
  const double zeta = z / a;
  // (z/a) atan(a/z) -> 0 as z -> 0.
  const double g = zeta > 0.0 ? zeta * std::atan(1.0 / zeta) : 0.0;
  HertzAxisStress s;
  s.sigma_r = p0 * (-(1.0 + nu) * (1.0 - g) + 0.5 / (1.0 + zeta * zeta));
  s.sigma_z = -p0 / (1.0 + zeta * zeta);
  s.von_mises = std::abs(s.sigma_z - s.sigma_r);
  return s;
}

HertzAxisMaximum hertzAxisMaximum(double nu) {
  auto f = [nu](double z) { return hertzAxisStress(z, 1.0, 1.0, nu).von_mises; };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0.0, hi = 2.0;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  while (hi - lo > 1e-12) {
    if (f1 < f2) {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + g * (hi - lo), f2 = f(x2);
    } else {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - g * (hi - lo), f1 = f(x1);
    }
  }
  const double z = 0.5 * (lo + hi);
  return {z, f(z)};
}

}  // namespace ffriga
