// Hertz's elliptical contact: two bodies whose surfaces at the contact point have principal
// curvatures that differ, pressed together by a force F. Johnson, "Contact Mechanics"
// (1985), Sect. 4.2 (eqs. 4.36-4.40), with the principal directions of the two surfaces
// aligned. With the relative curvatures A <= B (the gap h = A x^2 + B y^2 before loading,
// A = (k1' + k2') / 2, B = (k1'' + k2'') / 2 from the two bodies' principal curvatures) the
// contact is an ellipse of semi-axes a >= b (a along the direction of A), eccentricity
// e = sqrt(1 - b^2 / a^2), and with the complete elliptic integrals K(e), E(e):
//
//   B / A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e))     (e from the shape alone)
//   A = p0 b (K(e) - E(e)) / (E* e^2 a^2),  p0 = 3 F / (2 pi a b)
//       => a^3 = 3 F (K(e) - E(e)) / (2 pi E* e^2 A)
//   delta = p0 b K(e) / E*                             (approach)
//
// so that F = K_e delta^(3/2) with a constant K_e: the impact is Hertz's with that
// stiffness (hertz.h). For A = B it is the spheres' contact: a = b = sqrt(R* delta),
// R* = 1 / (2 A). Units: 1/m, Pa, N, m.
#pragma once

#include "common/mechanics/hertz.h"

namespace ffriga {

struct HertzEllipse {
  double semi_major = 0.0;    // a, m (along the direction of the smaller curvature A)
  double semi_minor = 0.0;    // b, m
  double eccentricity = 0.0;  // e = sqrt(1 - b^2 / a^2)
  double max_pressure = 0.0;  // p0 = 3 F / (2 pi a b), Pa
  double approach = 0.0;      // delta, m
  double stiffness = 0.0;     // K_e of F = K_e delta^(3/2), N/m^(3/2)
};

// The contact under the force F > 0 for relative curvatures 0 < A <= B (swapped if not) and
// effective modulus E*. Throws std::invalid_argument for A <= 0 or B / A beyond 1e6.
HertzEllipse hertzEllipse(double A, double B, double effective_modulus, double force);

// The relative curvatures (A, B), A <= B, of two convex surfaces with principal curvatures
// k1, k2 and kp1, kp2 (1/m; a plane 0, 0) whose directions of k1 and kp1 make the angle
// alpha (Johnson (1985) Sect. 2.1):
//   A + B = (k1 + k2 + kp1 + kp2) / 2,
//   B - A = sqrt((k1 - k2)^2 + (kp1 - kp2)^2 + 2 (k1 - k2)(kp1 - kp2) cos 2 alpha) / 2.
// Aligned (alpha = 0): A = (k1 + kp1) / 2, B = (k2 + kp2) / 2; two equal cylinders crossed at
// right angles (alpha = pi / 2): A = B, a circle.
struct RelativeCurvatures {
  double A = 0.0, B = 0.0;  // 1/m
};
RelativeCurvatures relativeCurvatures(double k1, double k2, double kp1, double kp2,
                                      double cos_alpha);

// The eccentricity e of the contact ellipse for B / A >= 1 (the shape's alone).
double ellipseEccentricity(double b_over_a);

// The length L with which the approach is delta = pi p0 L / (2 E*), as a circle's radius a
// is (delta = p0 a K(0) / E* = a^2 / R*): L = 2 b K(e) / pi for semi-axes a >= b, and a for
// a circle (b >= a, or b not given: b <= 0). `penalty_factor: auto` sets
// c_p = p0 / (eps delta) = 2 E* / (pi eps L) from it.
double ellipseApproachLength(double a, double b);

// Hertz's impact of two bodies whose surfaces make the relative curvatures r: the law's
// stiffness K_e from the ellipse at 1 N (F = K_e delta^(3/2) at every load), E* and the
// effective mass of the two bodies (their radii unused), approach speed v (m/s), a steady
// preload (N) as hertzImpact's.
HertzImpact ellipticalHertzImpact(const RelativeCurvatures& r, const HertzSphere& a,
                                  const HertzSphere& b, double v, double preload = 0.0);

}  // namespace ffriga
