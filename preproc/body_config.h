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

}  // namespace ffriga
