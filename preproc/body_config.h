// The body file of igaprep (schemas/body.schema.json): material, exact geometry and global
// refinement of one flexible body, read and checked up front. SI units.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

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
  std::vector<double> parameters;  // parametric coordinates, one per direction
};

// Modal damping band: modes with from_hz <= f < to_hz get damping ratio `ratio`.
struct DampingBand {
  double from_hz = 0.0;
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
  double dampingRatio(double f_hz) const;
};

struct BodyConfig {
  YamlDocument source;  // the file as read (path, text, parsed tree)
  std::string name;
  BodyModel model = BodyModel::kSolid;
  Material material;
  std::string geometry_type;        // half_disk | sphere | rod | nurbs
  NurbsPatch geometry;              // the exact, unrefined patch
  std::vector<int> elevate_degree;  // per parametric direction
  std::vector<int> insert_knots;    // per direction: knots per non-empty span
  ContactConfig contact;
  std::vector<MarkerConfig> markers;
  ReductionConfig reduction;
};

// Loads, validates against the body schema and checks the semantics (list lengths match
// the parametric dimension, knot vectors valid, one weight per control point, the model
// matches the geometry). Throws InputError (file, key, line).
BodyConfig loadBodyConfig(const std::string& path);
BodyConfig parseBodyConfig(YamlDocument doc);

// The globally refined patch: degree elevation, then uniform knot insertion, per direction.
NurbsPatch refinedPatch(const BodyConfig& config);

}  // namespace ffriga
