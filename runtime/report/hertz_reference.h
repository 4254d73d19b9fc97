// Hertz's prediction (common/mechanics/hertz.h) for a contact pair of a scene whose two bodies are
// spheres: both SIDs describe a geometry of type half_disk or sphere (radius and material
// from the SID's /geometry and /material), or a designed explicit patch whose contact point
// faces the partner along the line between the bodies' positions, and the scene gives their
// initial positions and velocities. The approach speed is the relative velocity along the
// line of centres at t = 0 (uniform gravity does not change it). A designed patch whose
// principal curvatures differ (/design/principal_curvatures and principal_direction) makes
// Hertz's elliptical contact (common/mechanics/hertz_ellipse.h) with its partner, the two
// surfaces' principal directions at their angle at t = 0. A sphere against a rigid obstacle
// (runtime/contact/rigid_obstacle.h) is Hertz's sphere on a rigid half-space or rigid
// sphere, or the elliptical contact of a solid sphere on a rigid cylinder: the obstacle
// infinitely stiff and heavy, the approach speed the body's speed along the obstacle's
// normal when it first touches, under gravity alone, and the body's weight along the normal
// a steady load during the contact. Used by ffrsim to print the maximum force and contact
// duration next to Hertz and write them to the result.
#pragma once

#include <optional>
#include <vector>

#include "common/mechanics/hertz.h"
#include "common/mechanics/hertz_ellipse.h"
#include "runtime/output/peak_stress_lines.h"
#include "runtime/scene/scene.h"

namespace ffriga {

struct HertzReference {
  HertzImpact impact;
  double approach_speed = 0.0;  // m/s
  HertzSphere sphere_a{}, sphere_b{};  // the pair's bodies A and B as Hertz sees them
  // The gap A x^2 + B y^2 before loading (1/m; A = B = 1 / (2 R*) for spheres); elliptical
  // where A < B (common/mechanics/hertz_ellipse.h: the impact with the ellipse's law).
  RelativeCurvatures curvatures;
  bool elliptical = false;
};

// Empty when a body is not a sphere, is held by a joint (its effective mass and approach
// speed are the mechanism's), or the bodies do not approach each other.
std::optional<HertzReference> hertzReference(const Scene& scene, int pair);

// Hertz's prediction for each contact pair of the scene (empty where it has none).
using HertzReferences = std::vector<std::optional<HertzReference>>;
HertzReferences hertzReferences(const Scene& scene);

// Each body's Hertz partner (the first pair with a reference that it is part of), for the
// stresses along its lines (runtime/output/peak_stress_lines.h).
std::vector<std::optional<HertzPartner>> hertzPartners(const Scene& scene,
                                                       const HertzReferences& hertz);

}  // namespace ffriga
