#include "common/mechanics/hertz.h"

#include <algorithm>
#include <cmath>

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
