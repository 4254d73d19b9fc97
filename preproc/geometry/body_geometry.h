// The geometry of a body, from its exact patch to the spline space everything else works on
// (body file keys `geometry`, `refinement`, `hierarchy`; schemas/body.schema.json):
//
//   exact patch     half-disk (paper Eq. 19), solid sphere, solid rod
//                   (preproc/geometry/geometry_builders.h) or an explicit NURBS patch
//   refined patch   degree elevation, then uniform knot insertion, then explicit knots, per
//                   direction (Piegl & Tiller A5.9, A5.4); the geometry is unchanged
//   body space      the hierarchical space over the refined patch (THB or HB, boxes in its
//                   knot coordinates), or with as_global_reference its tensor reference
//
// and what the body's DOFs are on it: control points that coincide (poles, collapsed edges,
// seams) share their DOFs, and on the axis of an axisymmetric section u_r = 0:
//   ndof = s * (functions - tied) - on_axis.
#pragma once

#include <string>
#include <vector>

#include "common/splines/hierarchical_space.h"
#include "common/splines/nurbs_patch.h"

namespace ffriga {

enum class GeometryKind { kHalfDisk, kSphere, kRod, kNurbs };

// The body file's `geometry`: a built-in shape with its sizes, or an explicit patch.
struct GeometryConfig {
  GeometryKind kind = GeometryKind::kNurbs;
  double radius = 0.0;  // m: half_disk, sphere, rod (0 otherwise)
  double length = 0.0;  // m: rod (0 otherwise)
  NurbsPatch patch;     // kNurbs: the patch as given
  // kSphere: the direction from the centre on which its contact point (1/2, 1, 1/8) lies
  // (a designed sphere's design.contact_point.direction; +z otherwise).
  Eigen::Vector3d contact_direction = Eigen::Vector3d::UnitZ();
  // Parametric and space dimension (2 for the half-disk, 3 for the sphere and the rod).
  int paramDim() const;
};

// The body file's `refinement`, per parametric direction (empty: none).
struct RefinementConfig {
  std::vector<int> elevate_degree;          // degree elevation
  std::vector<int> insert_knots;            // knots inserted in every non-empty span
  std::vector<std::vector<double>> insert;  // explicit knots, after the above
};

// The exact, unrefined patch. Throws std::invalid_argument for sizes the builders refuse.
NurbsPatch exactPatch(const GeometryConfig& geometry);
// The globally refined patch; std::invalid_argument ("direction a: ...") for an explicit
// knot the patch refuses. Hierarchy boxes refer to its knot coordinates.
NurbsPatch refinedPatch(const NurbsPatch& exact, const RefinementConfig& refinement);
// The hierarchical space over the refined patch or, with global_reference, the tensor space
// (one level) of its global reference (common/splines/hierarchical_space.h).
HierarchicalSpace bodySpace(const NurbsPatch& refined, const HierarchyOptions& hierarchy,
                            bool global_reference);

// Why the boundary face of `patch` at the lower (upper = false) or upper end of direction
// `dir` is degenerate, or "" if it is regular. Degenerate: its control net collapses along
// another direction (every line of that direction is one point: an axis, a pole line, an
// equator) or coincides with the opposite face (a closed seam). Such faces carry tied
// control points, and a box or contact region touching them would refine or load a
// degenerate point (DESIGN.md). A face that merely lies on the symmetry axis, like the
// edge xi = 0 of the half-disk (x = 0, u_r = 0 there, but not collapsed), is regular.
// Tolerance: 1e-12 of the patch size, as for tied control points.
std::string degenerateFace(const NurbsPatch& patch, int dir, bool upper);

// Groups of control points whose DOFs are tied: coincident points (1e-12 of the body size)
// of the same level (collapsed edges, poles, seams), read from the THB control points, also
// for an HB space. Coincidences across levels occur on regular boundaries (along the axis,
// where the section is linear in eta, a level-l and a level-(l+1) function can share a
// control point) and stay distinct DOFs.
std::vector<std::vector<int>> tiedControlPoints(const HierarchicalSpace& space);

// Displacement DOFs of a body space (what igaprep reports as ndof).
struct DofCount {
  int groups = 0;   // groups of tied control points
  int tied = 0;     // control points tied to another one
  int on_axis = 0;  // distinct control points on the axis (axisymmetric: x = 0, u_r = 0)
  int ndof = 0;
};
DofCount countDofs(const HierarchicalSpace& space, bool axisymmetric);

}  // namespace ffriga
