// The body file of igaprep (schemas/body.schema.json): material, exact geometry and global
// refinement of one flexible body, read and checked up front. SI units.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "common/splines/hierarchical_space.h"
#include "common/splines/nurbs_patch.h"
#include "common/input/yaml_input.h"
#include "preproc/input/visualisation_config.h"

namespace ffriga {

enum class ModelKind { kAxisymmetric, kSolid };

// One table from enum to YAML spelling.
const char* toString(ModelKind model);

struct Material {
  double youngs_modulus = 0.0;  // E, Pa
  double poisson_ratio = 0.0;   // nu, dimensionless, -1 < nu < 1/2
  double density = 0.0;         // rho, kg/m^3
};

// The contact region (schema key `contact`): a box on a boundary face, knot coordinates.
struct ContactConfig {
  bool present = false;
  std::string name = "contact";
  int direction = 1;                          // parametric direction normal to the face
  bool upper = true;                          // face at the upper end of the direction
  std::vector<std::array<double, 2>> bounds;  // per remaining direction, increasing order
};

struct MarkerConfig {
  std::string name;
  std::vector<double> parameters;  // point marker: parametric coordinates, one per direction
  bool face = false;               // face marker (marker_points.h): the boundary face
  int face_direction = 0;          //   normal to parametric direction face_direction,
  bool face_upper = false;         //   at its upper end if face_upper
  bool interface = false;          // its control points join the Craig-Bampton interface
};

// Modal damping band: modes with from_hz <= f < to_hz get damping ratio `ratio`; with
// from_first_elastic = F > 0 instead, the lower limit is F times the body's lowest elastic
// frequency f_1 (a rule that scales with the body, like runtime/bodies/quasi_static_rule.h).
struct DampingBand {
  double from_hz = 0.0;
  double from_first_elastic = 0.0;
  double to_hz = std::numeric_limits<double>::infinity();
  double ratio = 0.0;
};

struct ReductionConfig {
  std::string method = "craig_bampton";  // craig_bampton | modal
  int normal_modes = 10;
  std::string frame = "buckens";  // buckens | tangent
  std::string frame_marker;       // tangent frame only
  std::vector<DampingBand> damping;
  // Damping ratio of a mode of frequency f (Hz): the last band containing f, else 0.
  // Damping ratio of a mode of frequency f_hz on a body whose lowest elastic frequency is
  // f1_hz (the last matching band wins; 0 if none).
  double dampingRatio(double f_hz, double f1_hz) const;
};

struct BodyConfig {
  YamlDocument source;  // the file as read (path, text, parsed tree)
  std::string name;
  ModelKind model = ModelKind::kSolid;
  Material material;
  std::string geometry_type;                // half_disk | sphere | rod | nurbs
  double geometry_radius = 0.0;             // m: half_disk, sphere, rod (0 otherwise)
  double geometry_length = 0.0;             // m: rod (0 otherwise)
  NurbsPatch geometry;                      // the exact, unrefined patch
  std::vector<int> elevate_degree;          // per parametric direction
  std::vector<int> insert_knots;            // per direction: knots per non-empty span
  std::vector<std::vector<double>> insert;  // per direction: explicit knots (after the above)
  // Hierarchical refinement of the globally refined patch (levels = 1: none). The boxes are
  // validated and snapped onto the level grids (HierarchicalSpace's box semantics).
  HierarchyOptions hierarchy;
  bool global_reference = false;  // hierarchy.as_global_reference
  ContactConfig contact;
  std::vector<MarkerConfig> markers;
  ReductionConfig reduction;
  VisualisationConfig visualisation;
};

// Loads, validates against the body schema and checks the semantics (list lengths match
// the parametric dimension, knot vectors valid, one weight per control point, the model
// matches the geometry). Throws InputError (file, key, line).
// memory_limit_bytes: inputs whose size estimate (preproc/input/size_estimate.h) exceeds it are
// refused before refinement; 0: this machine's physical memory.
// sets: command-line overrides "KEY=VALUE" (common/input/yaml_overrides.h), applied before the
// schema check.
BodyConfig loadBodyConfig(const std::string& path, double memory_limit_bytes = 0.0,
                          const std::vector<std::string>& sets = {});
BodyConfig parseBodyConfig(YamlDocument doc, double memory_limit_bytes = 0.0);

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
DofCount countDofs(const HierarchicalSpace& space, ModelKind model);
// Groups of control points whose DOFs are tied: coincident points of the same level
// (collapsed edges, poles, seams), read from the THB control points.
std::vector<std::vector<int>> tiedControlPoints(const HierarchicalSpace& space);

}  // namespace ffriga
