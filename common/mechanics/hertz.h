// Hertz's solution for the central impact of two elastic spheres (the analytical
// reference of paper Sect. 5-7). Johnson, "Contact Mechanics" (1985), Sect. 4.2 and 11.4;
// Goldsmith, "Impact" (1960), Ch. IV.
//
// With the approach delta (decrease of the centre distance) the contact force is
//   F = K delta^(3/2),  K = 4/3 E* sqrt(R*),
//   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,  1/R* = 1/R1 + 1/R2,  1/m* = 1/m1 + 1/m2,
// and m* d2(delta)/dt2 = -F. Energy conservation from the relative speed v gives
//   delta_max = (5 m* v^2 / (4 K))^(2/5),   F_max = K delta_max^(3/2),
//   duration  T = 2 (delta_max / v) int_0^1 dx / sqrt(1 - x^(5/2))  ~= 2.94352 delta_max / v.
// The quasi-static theory neglects wave propagation and plastic flow; for the paper's
// steel spheres at 0.2 m/s it is accurate to well below 1 %.
// Under a steady load P pressing the bodies together (a ball's weight on the floor),
//   m* delta'' = P - K delta^(3/2),   1/2 m* v^2 + P delta_max = 2/5 K delta_max^(5/2),
//   T = 2 int_0^delta_max d(delta) / sqrt(v^2 + 2 P delta / m* - 4/5 K delta^(5/2) / m*)
// (the motion is time-reversible, so the peak is at T / 2). For the flagship's sphere on a
// floor at 0.1 m/s the weight (0.32 N, 0.2 % of the force peak) raises the peak by 0.33 %
// and the duration by 0.10 %.
// Units: Pa, m, kg, m/s, N, s.
#pragma once

#include <vector>

namespace ffriga {

struct HertzSphere {
  double youngs_modulus;  // Pa
  double poisson_ratio;   // -
  double radius;          // m
  double mass;            // kg
};

struct HertzImpact {
  double stiffness;       // K, N/m^(3/2)
  double effective_mass;  // m*, kg
  double max_approach;    // delta_max, m
  double max_force;       // F_max, N
  double duration;        // T, s
  double time_of_max;     // T / 2, s
  double preload = 0.0;   // P, N (0: two free bodies, or no gravity along the normal)
};

// E* of 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, Pa, and R* of 1/R* = 1/R1 + 1/R2, m (an
// infinite E or R: a rigid body or a plane; both rigid: E* = infinity).
double effectiveModulus(const HertzSphere& a, const HertzSphere& b);
double effectiveRadius(const HertzSphere& a, const HertzSphere& b);

// K = 4/3 E* sqrt(R*) of F = K delta^(3/2), N/m^(3/2) (masses are not used).
double hertzStiffness(const HertzSphere& a, const HertzSphere& b);

// Central impact at relative normal speed v > 0 (m/s), pressed together by the steady load
// P (N, default none; a negative load pulls them apart, e.g. gravity away from a wall).
HertzImpact hertzImpact(const HertzSphere& a, const HertzSphere& b, double v, double preload = 0.0);
// The same for any contact law F = K delta^(3/2) (an elliptical contact: hertz_ellipse.h) and
// effective mass m*.
HertzImpact hertzImpact(double stiffness, double effective_mass, double v, double preload = 0.0);

// Contact force at times t (s, measured from first touch), by integrating
// m* delta'' = P - K delta^(3/2) (fourth-order Runge-Kutta, 20,000 steps per contact; the
// result agrees with max_force to 1e-9 relative). Zero outside [0, duration].
std::vector<double> hertzForceHistory(const HertzImpact& h, double v, const std::vector<double>& t);

// The contact patch of two spheres pressed together by a force F (Johnson eq. 4.22-4.24):
//   a = (3 F R* / (4 E*))^(1/3),   p0 = 3 F / (2 pi a^2).
struct HertzContactPatch {
  double radius;        // a, m
  double max_pressure;  // p0, Pa
};
HertzContactPatch hertzContactPatch(const HertzSphere& a, const HertzSphere& b, double force);

// The stresses on the axis of symmetry at depth z >= 0 below the centre of a Hertz contact
// patch of radius a and peak pressure p0, in a body of Poisson ratio nu (Johnson eq. 3.72):
//   sigma_r = sigma_theta = p0 (-(1 + nu) (1 - (z/a) atan(a/z)) + 1 / (2 (1 + z^2/a^2))),
//   sigma_z = -p0 / (1 + z^2/a^2),
// principal stresses, so that von Mises = |sigma_z - sigma_r| (maximum ~0.62 p0 at
// z ~ 0.48 a for nu = 0.3). Pa.
struct HertzAxisStress {
  double sigma_r, sigma_z, von_mises;
};
HertzAxisStress hertzAxisStress(double z, double a, double p0, double nu);

// The maximum of the von Mises stress on the axis (golden-section search in 0 < z < 2 a,
// to 1e-12 a): its depth z / a and value / p0 (0.4805 and 0.6199 for nu = 0.3).
struct HertzAxisMaximum {
  double depth_over_a, von_mises_over_p0;
};
HertzAxisMaximum hertzAxisMaximum(double nu);

}  // namespace ffriga
