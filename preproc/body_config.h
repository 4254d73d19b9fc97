// The body file of igaprep (schemas/body.schema.json): material, exact geometry and global
// refinement of one flexible body, read and checked up front. SI units.
#pragma once

#include <string>
#include <vector>

#include "common/hierarchical_space.h"
#include "common/nurbs_patch.h"
#include "common/yaml_input.h"

namespace ffriga {

enum class BodyModel { kAxisymmetric, kSolid };

// One table from enum to YAML spelling.
const char* toString(BodyModel model);

struct Material {
  double youngs_modulus = 0.0;  // E, Pa
  double poisson_ratio = 0.0;   // nu, dimensionless, -1 < nu < 1/2
  double density = 0.0;         // rho, kg/m^3
};

struct BodyConfig {
  YamlDocument source;  // the file as read (path, text, parsed tree)
  std::string name;
  BodyModel model = BodyModel::kSolid;
  Material material;
  std::string geometry_type;                // half_disk | sphere | rod | nurbs
  NurbsPatch geometry;                      // the exact, unrefined patch
  std::vector<int> elevate_degree;          // per parametric direction
  std::vector<int> insert_knots;            // per direction: knots per non-empty span
  std::vector<std::vector<double>> insert;  // per direction: explicit knots (after the above)
  // Hierarchical refinement of the globally refined patch (levels = 1: none). The boxes are
  // validated and snapped onto the level grids (HierarchicalSpace's box semantics).
  HierarchyOptions hierarchy;
  bool global_reference = false;  // hierarchy.as_global_reference
};

// Loads, validates against the body schema and checks the semantics (list lengths match
// the parametric dimension, knot vectors valid, one weight per control point, the model
// matches the geometry). Throws InputError (file, key, line).
BodyConfig loadBodyConfig(const std::string& path);
BodyConfig parseBodyConfig(YamlDocument doc);

// The globally refined patch: degree elevation, then uniform knot insertion, then the
// explicit knots, per direction. Hierarchy boxes refer to this patch's knot coordinates.
NurbsPatch refinedPatch(const BodyConfig& config);

// The body's spline space: the hierarchical space over refinedPatch() or, with
// hierarchy.as_global_reference, the tensor space (one level) of its global reference.
HierarchicalSpace bodySpace(const BodyConfig& config);

// Displacement DOFs of a body space (what igaprep reports as ndof):
//   ndof = s * (functions - tied) - on_axis,
// tied: control points that coincide (1e-12 of the body size) with another one of the same
// level and share its DOFs (collapsed edges, poles, seams; judged on the THB control points,
// also for an HB space); coincidences across levels
// occur on regular boundaries (along the axis, where the section is linear in eta, a
// level-l and a level-(l+1) function can share a control point) and stay distinct DOFs;
// on_axis (axisymmetric): distinct control points with x = 0, where u_r = 0.
struct DofCount {
  int groups = 0;   // groups of tied control points
  int tied = 0;     // control points tied to another one
  int on_axis = 0;  // distinct control points on the axis
  int ndof = 0;
};
DofCount countDofs(const HierarchicalSpace& space, BodyModel model);

}  // namespace ffriga
