// A body designed from the impact it must resolve (body file key `design`, issue 26;
// schemas/body_design.md): instead of hand-given refinement, hierarchy boxes and contact
// region, the body file states where contact happens and what must be resolved there, and
// the rule below derives the model. The same rule for every case, no per-case tables.
//
// What must be resolved: Hertz's contact radius a, from the impact (the partner's radius
// and material, or the same body again, or a rigid plane, and the approach speed;
// common/mechanics/hertz.h: a = sqrt(R* delta_max)) or given directly as the largest
// contact radius expected.
//
// The rule works on a chart of the contact point (contact_chart.h): each parametric
// direction runs along the surface (to both sides, or to one where the contact point is on
// the patch's edge) or into the body: the half-disk of paper Eq. (19) at its pole (0, 1),
// the solid sphere at (1/2, 1, 1/8) turned to the contact direction, or an explicit patch at
// a point of a boundary face (convex, regular; face_point.h gives its curvature):
//
//   level 0   the paper's 400-element model (half-disk: degrees 4 x 3, 16 x 25 spans) or
//             sphere3d_coarse's (degrees 3 x 3 x 3, 4 x 4 x 16 spans); an explicit patch at
//             degree kLevel0Degree with uniform spans (kLevel0MinSpans below);
//   levels    the fewest halvings that bring every span at the contact point below a / N,
//             N = elements per contact radius (default 12 axisymmetric, 2 solid); an
//             elliptical contact (semi-axes a >= b): below b / N, its boxes and region
//             reaching as far as a;
//   boxes     box l (l = 1 .. L) reaches kRegionRadii a along the surface and
//             kFinestDepthRadii a in depth, plus kLayerCells cells of level l - 1 beyond,
//             each bound snapped outwards onto the level l - 1 grid, so that every level
//             keeps a layer of its own cells around the finer one (paper Fig. 6);
//   region    the contact region: kRegionRadii a along the surface, on the finest grid;
//   stress    a line along the normal under the contact point, kStressLineRadii a deep.
//
// Measured on the paper's Sect. 5 impact (a = 0.168 mm; schemas/body_design.md): finest
// spans of a / 12.2 (N = 12, 6 halvings) and a / 24.3 (N = 16 or 24, 7 halvings) give force
// peaks 0.035 % apart; boxes 0.5 a or 1 a deep, 2 or 4 layer cells, regions of 1.5 a to
// 3 a change it by less than 0.002 %. On Sect. 6 (3D), N = 3 moves it by 0.063 % from N = 2.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/mechanics/hertz.h"
#include "common/mechanics/isotropic_material.h"
#include "common/splines/hierarchical_space.h"
#include "preproc/geometry/body_geometry.h"

namespace ffriga {

// The rule's constants (header comment).
// Default accuracy level N per model: the axisymmetric section is cheap (2,042 ndof at
// N = 12 on the paper's impact), a 3D solid is not (N = 2: 17,781 ndof, nq 899; N = 3:
// 46,656 ndof).
constexpr double kDefaultElementsPerContactRadius = 12.0;
constexpr double kDefaultElementsPerContactRadiusSolid = 2.0;
// Fixed-interface normal modes of a designed solid whose body file does not give
// reduction.normal_modes: the 3D sphere has many modes below the quasi-static cutoff 4 f1
// (multiplicities 5, 7, ...), the axisymmetric section few. Measured on the Sect. 6 impact
// designed: 10 modes +1.03 % / -0.78 % from Hertz in 1427 steps, 50 modes +0.90 % / -0.62 %
// in 691 steps; on Sect. 5 (axisymmetric) 4, 10 and 30 modes agree to 0.001 % (the schema's
// default 10 stays).
constexpr int kDefaultNormalModesSolid = 50;
// Designed from an impact of duration T, a body whose file gives no normal_modes keeps every
// fixed-interface mode below kModeCutoffPeriods / T: a mode with more periods than that
// within the contact responds quasi-statically (its dynamic share of the force ~ 1/(f T)^2),
// which the constraint modes represent exactly. Measured on the Sect. 6 impact designed
// (T = 82.85 us): 25 / T = 302 kHz keeps 60 modes, force peak +0.90 % from Hertz as with
// 50 modes and with 180 (40 / T); 10 modes gave +1.03 %.
constexpr double kModeCutoffPeriods = 25.0;
constexpr double kRegionRadii = 2.0;       // contact region and finest box: 2 a of arc
constexpr double kFinestDepthRadii = 0.5;  // finest box depth: 0.5 a (Hertz's von Mises
                                           // maximum lies at 0.48 a)
constexpr int kLayerCells = 2;             // cells of the coarser level around each box
constexpr double kStressLineRadii = 3.5;   // the axis line's depth, in a
// Level 0 of an explicit patch: its degree raised to 3 where lower (as sphere3d_coarse),
// uniform spans, at least 8 across the shortest of its iso-curves through the contact point
// and of about that length along the others, on a grid holding the patch's own knots.
constexpr int kLevel0Degree = 3;
constexpr int kLevel0MinSpans = 8;
// A contact point designed from an impact is spherical where its principal curvatures agree
// within 1 % (Hertz's ellipse then has axes within 0.7 % of each other, Johnson (1985)
// Sect. 4.2), elliptical beyond (common/mechanics/hertz_ellipse.h) up to a ratio of 100
// (semi-axes a / b ~ 19: beyond, a contact line rather than an ellipse).
constexpr double kSphericalTolerance = 0.01;
constexpr double kMaxCurvatureRatio = 100.0;

// The body file's `design` block as read.
struct DesignRequest {
  enum class Partner { kSame, kPlane, kSphere };
  // Either the impact ...
  bool from_impact = true;
  Partner partner = Partner::kSame;
  HertzSphere partner_sphere{};  // kSphere: radius, material and mass
  double approach_speed = 0.0;   // m/s, relative normal speed at first touch
  // ... or the largest contact radius directly (from_impact = false), m.
  double contact_radius = 0.0;
  double elements_per_contact_radius = kDefaultElementsPerContactRadius;
};

// What the rule derives, with the figures it derived them from.
struct ImpactDesign {
  // What must be resolved.
  double contact_radius = 0.0;        // a, m (an ellipse's semi-major axis)
  double contact_minor_radius = 0.0;  // b, m: the ellipse's semi-minor axis (a for a circle);
                                      // the finest spans are sized from it
  std::optional<HertzImpact> hertz;  // the impact's Hertz solution (from_impact only)
  double max_pressure = 0.0;         // p0 at the force peak, Pa (from_impact only)
  double approach_speed = 0.0;       // m/s (from_impact only)
  double elements_per_contact_radius = 0.0;
  double mode_cutoff_hz = 0.0;  // kModeCutoffPeriods / T where the file gives no normal_modes
  // The model.
  RefinementConfig refinement;
  HierarchyOptions hierarchy;
  // Where: the contact point's face (eta_max for the built-in geometries), the point and
  // its outward normal (geometry coordinates), the surface's radius of curvature there (m;
  // 0 where its principal curvatures differ by more than kSphericalTolerance).
  int face_direction = 1;
  bool face_upper = true;
  Eigen::VectorXd contact_point, contact_normal;
  double surface_radius = 0.0;
  // The surface's two principal curvatures there (1/m, ascending; a sphere's 1 / r twice,
  // an axisymmetric section's on-axis one twice) and the unit direction of the first
  // (geometry coordinates; empty where they agree within kSphericalTolerance).
  std::array<double, 2> principal_curvatures{};
  Eigen::VectorXd principal_direction;
  // The contact region on that face: one [lo, hi] per direction along it ([xi], or
  // [xi], [zeta]).
  std::vector<std::array<double, 2>> region;
  double finest_arc = 0.0;    // largest finest span at the contact point along the surface, m
  double finest_depth = 0.0;  // finest span into the body there, m
  Eigen::VectorXd stress_from, stress_to;  // the axis line, geometry coordinates (m)
  int stress_points = 0;
  // One line per derived number with its reason, for igaprep's printout.
  std::vector<std::string> reasons;
};

// The design for a sphere of radius r, material `material` and mass m against the
// request's partner: the half-disk (axisymmetric, contact at its pole) and the solid sphere
// (contact at (1/2, 1, 1/8), which the geometry puts on `direction` from the centre:
// geometry_builders.h). Throws std::invalid_argument for what no rule can design (a
// contact radius beyond the face).
ImpactDesign designHalfDiskImpact(double radius, const IsotropicMaterial& material, double mass,
                                  const DesignRequest& request);
ImpactDesign designSphereImpact(double radius, const IsotropicMaterial& material, double mass,
                                const DesignRequest& request,
                                const Eigen::Vector3d& direction = Eigen::Vector3d::UnitZ());

// The design for an explicit patch (a 2D axisymmetric section or a 3D solid, knot vectors
// on [0, 1]) at the point `parameters` (one knot coordinate per direction along the face,
// in direction order) of its boundary face {xi[face_direction] = 0 or 1}: level 0 by the
// rule above, the chart from the patch's iso-curves (contact_chart.h), Hertz's impact with
// the surface's radius of curvature there and the mass density x volume. Throws
// std::invalid_argument for a point off the face, degenerate, off the axis (axisymmetric),
// on the face's edge (solid), on a C0 knot line, not convex, or elliptical (from an impact).
ImpactDesign designPatchImpact(const NurbsPatch& patch, bool axisymmetric,
                               const IsotropicMaterial& material, int face_direction,
                               bool face_upper, const std::vector<double>& parameters,
                               const DesignRequest& request);

// The mass of the full sphere of radius r, kg.
double sphereMass(double radius, double density);

}  // namespace ffriga
