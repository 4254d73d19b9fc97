#include "common/mechanics/hertz.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <catch2/catch.hpp>

using namespace ffriga;

TEST_CASE("Hertz impact of the paper's steel spheres", "[hertz]") {
  const double pi = std::acos(-1.0);
  const double r = 0.01;
  const double m = 4.0 / 3.0 * pi * r * r * r * 7850.0;
  const HertzSphere s{2.11e11, 0.3, r, m};
  const HertzImpact h = hertzImpact(s, s, 0.2);
  // Closed forms evaluated independently: E* = E / (2 (1 - nu^2)), R* = r / 2, m* = m / 2.
  const double K = 4.0 / 3.0 * 2.11e11 / (2 * (1 - 0.09)) * std::sqrt(r / 2);
  CHECK(h.stiffness == Approx(K).epsilon(1e-14));
  const double dmax = std::pow(5.0 * (m / 2) * 0.04 / (4 * K), 0.4);
  CHECK(h.max_force == Approx(K * std::pow(dmax, 1.5)).epsilon(1e-13));
  // The duration constant 2 int_0^1 (1 - x^2.5)^-1/2 dx = 2.943521 (Johnson 1985, Sect. 11.4).
  CHECK(h.duration * 0.2 / dmax == Approx(2.9435).epsilon(1e-4));
  // Orders of magnitude of the paper's Fig. 8: about 145 N over about 80 microseconds.
  CHECK(h.max_force > 100.0);
  CHECK(h.max_force < 200.0);
  CHECK(h.duration > 60e-6);
  CHECK(h.duration < 100e-6);
}

TEST_CASE("Hertz force history peaks at F_max at T/2 and is symmetric", "[hertz]") {
  const HertzSphere s{2.11e11, 0.3, 0.01, 0.0329};
  const HertzImpact h = hertzImpact(s, s, 0.2);
  std::vector<double> t;
  for (int i = 0; i <= 1000; ++i) t.push_back(h.duration * i / 1000.0);
  const std::vector<double> f = hertzForceHistory(h, 0.2, t);
  const double fmax = *std::max_element(f.begin(), f.end());
  // RK4 with 20,000 steps: global error ~ (dt)^4, far below 1e-6 relative.
  CHECK(fmax == Approx(h.max_force).epsilon(1e-6));
  CHECK(f[500] == Approx(h.max_force).epsilon(1e-6));
  for (int i = 1; i < 500; ++i) CHECK(f[i] == Approx(f[1000 - i]).epsilon(1e-5).margin(1e-9));
}

// Under a steady load P (a ball's weight on a floor), against an independent integration of
// m* delta'' = P - K delta^(3/2) from (0, v): RK4 with 1 ns steps until delta turns negative
// (the crossing interpolated linearly; step error ~1e-12 relative, the crossing ~1e-9).
namespace {
struct LoadedImpact {
  double max_force, duration;
};
LoadedImpact integrateLoaded(double K, double m, double v, double P) {
  const double dt = 1e-9;
  auto acc = [&](double d) { return (P - K * std::pow(std::max(d, 0.0), 1.5)) / m; };
  double d = 0.0, w = v, t = 0.0, fmax = 0.0;
  for (;;) {
    const double k1d = w, k1w = acc(d);
    const double k2d = w + 0.5 * dt * k1w, k2w = acc(d + 0.5 * dt * k1d);
    const double k3d = w + 0.5 * dt * k2w, k3w = acc(d + 0.5 * dt * k2d);
    const double k4d = w + dt * k3w, k4w = acc(d + dt * k3d);
    const double dn = d + dt / 6.0 * (k1d + 2 * k2d + 2 * k3d + k4d);
    w += dt / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
    if (dn < 0.0) return {fmax, t + dt * d / (d - dn)};
    d = dn, t += dt;
    fmax = std::max(fmax, K * std::pow(d, 1.5));
  }
}
}  // namespace

TEST_CASE("Hertz impact under a steady load: energy balance and the integrated motion",
          "[hertz]") {
  const HertzSphere ball{2.11e11, 0.3, 0.01, 0.032882};
  const double inf = std::numeric_limits<double>::infinity();
  const HertzSphere floor{inf, 0.0, inf, inf};  // a rigid half-space
  const double v = 0.1, weight = 0.032882 * 9.81;
  const HertzImpact free = hertzImpact(ball, floor, v);
  CHECK(free.preload == 0.0);
  for (const double P : {weight, -weight, 50.0 * weight}) {
    const HertzImpact h = hertzImpact(ball, floor, v, P);
    CHECK(h.preload == P);
    // 1/2 m* v^2 + P delta_max = 2/5 K delta_max^(5/2) (Newton's root, to round-off).
    const double work = 0.4 * h.stiffness * std::pow(h.max_approach, 2.5);
    CHECK(0.5 * h.effective_mass * v * v + P * h.max_approach == Approx(work).epsilon(1e-13));
    const LoadedImpact ref = integrateLoaded(h.stiffness, h.effective_mass, v, P);
    CHECK(h.max_force == Approx(ref.max_force).epsilon(1e-8));
    CHECK(h.duration == Approx(ref.duration).epsilon(1e-7));
    CHECK(h.time_of_max == 0.5 * h.duration);
    // A load pressing the bodies together makes the impact harder and longer.
    CHECK((P > 0) == (h.max_force > free.max_force));
    CHECK((P > 0) == (h.duration > free.duration));
  }
  // The weight of the ball of ball_on_plane.yaml: +0.33 % force peak, +0.10 % duration.
  const HertzImpact h = hertzImpact(ball, floor, v, weight);
  CHECK(h.max_force / free.max_force - 1 == Approx(3.3e-3).epsilon(0.03));
  CHECK(h.duration / free.duration - 1 == Approx(1.0e-3).epsilon(0.05));
  // A vanishing load joins the closed form (the two branches agree; its own effect, ~3e-14,
  // is below the bound).
  const HertzImpact tiny = hertzImpact(ball, floor, v, 1e-11 * weight);
  CHECK(tiny.max_force == Approx(free.max_force).epsilon(1e-12));
  CHECK(tiny.duration == Approx(free.duration).epsilon(1e-12));
}
