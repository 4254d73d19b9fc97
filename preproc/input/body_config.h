// The body file of igaprep (schemas/body.schema.json): material, exact geometry, refinement,
// hierarchy, contact regions, markers, reduction and visualisation of one flexible body, SI
// units. Read in two phases, each error naming the file, the YAML line and the key:
//
//   read   (body_config.cc) the schema, then every value into BodyConfig, with the checks
//          the document alone decides (list lengths per parametric direction, knot vectors,
//          names used twice, keys that need or exclude each other);
//   check  (body_checks.cc) against the geometry the values build: the model against the
//          patch's dimensions, the size estimate against the memory limit (before anything
//          large is allocated), the refinement, the hierarchy's boxes (snapped onto the
//          level grids), faces and regions off degenerate faces and off each other, markers
//          and stress lines inside the body.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/input/yaml_input.h"
#include "common/mechanics/isotropic_material.h"
#include "common/sid/body_kinds.h"
#include "common/splines/hierarchical_space.h"
#include "common/splines/nurbs_patch.h"
#include "preproc/design/impact_design.h"
#include "preproc/geometry/body_geometry.h"
#include "preproc/input/visualisation_config.h"

namespace ffriga {

// The YAML spelling of geometry.type (the model's and reduction's: common/sid/body_kinds.h).
const char* toString(GeometryKind geometry);
bool parseKind(std::string_view text, GeometryKind* kind);

// A contact region: a box on a boundary face, knot coordinates. The schema's short form
// `contact` gives one (named "contact" by default), `contacts` several, each named.
struct ContactConfig {
  std::string key = "contact";   // the YAML key it came from ("contacts[1]"), for errors
  int item = -1;                 // its index in `contacts`; -1: the short form `contact`
  std::string name = "contact";  // of its contact surface in the SID file
  int direction = 1;             // parametric direction normal to the face
  bool upper = true;             // face at the upper end of the direction
  std::vector<std::array<double, 2>> bounds;  // per remaining direction, increasing order
  bool gauss = false;  // collocation: Gauss-Legendre points (else the paper's Botella points)
  bool designed = false;  // derived by the `design` block (errors then name that key)
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

// reduction.pressure_patches (preproc/reduction/pressure_patches.h): pressure patches whose
// static responses span the contact region's interface.
struct PressurePatchConfig {
  bool given = false;
  double radius = 0.0;  // m, the largest patch; 0: 1.2 times a designed body's a
  int radii = 8;
  int degree = 2;
  bool tangential = true;
  std::vector<double> centre;  // surface parameters; empty: the default centre
};

struct ReductionConfig {
  // Defaults as the schema's (tests/schemas/code_defaults_test.cc); they apply to a
  // body file without a `reduction` block.
  ReductionMethod method = ReductionMethod::kCraigBampton;  // craig_bampton | modal
  int normal_modes = 10;
  // A designed body without reduction.normal_modes (impact_design.h): every fixed-interface
  // mode below this frequency, Hz (normal_modes the first guess); 0: normal_modes as given.
  double mode_cutoff_hz = 0.0;
  // > 0: the contact regions' constraint modes are replaced by this many elastic
  // characteristic constraint modes (preproc/reduction/characteristic_constraint_modes.h);
  // 0: the full Craig-Bampton interface.
  int interface_modes = 0;
  PressurePatchConfig pressure_patches;
  FrameKind frame = FrameKind::kBuckens;  // buckens | tangent
  std::string frame_marker;               // tangent frame only
  std::vector<DampingBand> damping;
  // Damping ratio of a mode of frequency f_hz on a body whose lowest elastic frequency is
  // f1_hz (the last matching band wins; 0 if none).
  double dampingRatio(double f_hz, double f1_hz) const;
};

struct BodyConfig {
  YamlDocument source;  // the file as read (path, text, parsed tree)
  std::string name;
  ModelKind model = ModelKind::kSolid;
  IsotropicMaterial material;
  GeometryConfig geometry;
  RefinementConfig refinement;  // one entry per parametric direction
  // Hierarchical refinement of the globally refined patch (levels = 1: none). After the
  // checks the boxes are snapped onto the level grids (HierarchicalSpace's box semantics).
  HierarchyOptions hierarchy;
  bool global_reference = false;        // hierarchy.as_global_reference
  std::vector<ContactConfig> contacts;  // file order; empty: no contact region
  std::vector<MarkerConfig> markers;
  ReductionConfig reduction;
  VisualisationConfig visualisation;
  // The design block's result (key `design`): refinement, hierarchy, the contact region and
  // the stress line 'axis' above were derived by preproc/design/impact_design.h.
  std::optional<ImpactDesign> design;
};

// Reads and checks a body file (both phases of the header comment). Throws InputError
// (file, line, key). memory_limit_bytes: inputs whose size estimate
// (preproc/geometry/size_estimate.h) exceeds it are refused before refinement; 0: this
// machine's physical memory. sets: command-line overrides "KEY=VALUE"
// (common/input/yaml_overrides.h), applied before the schema check.
BodyConfig loadBodyConfig(const std::string& path, double memory_limit_bytes = 0.0,
                          const std::vector<std::string>& sets = {});
BodyConfig parseBodyConfig(YamlDocument doc, double memory_limit_bytes = 0.0);

// The read phase alone (no geometry is built).
BodyConfig readBodyConfig(YamlDocument doc);

// The YAML node of a contact region (`contact` or `contacts[item]`), for errors found after
// the read phase.
YAML::Node contactNode(const YamlDocument& doc, const ContactConfig& contact);

// A level's entry `level` of hierarchy.boxes is one box or a list of boxes: whether it is a
// list, the YAML node of its box `member` and that box's key ("hierarchy.boxes[b]" or
// "hierarchy.boxes[b][member]"), for errors found after the read phase.
bool listOfBoxes(const YAML::Node& level);
YAML::Node hierarchyBoxNode(const YAML::Node& level, int member);
std::string hierarchyBoxKey(const YAML::Node& level, int b, int member);

// The body's refined patch and spline space (preproc/geometry/body_geometry.h).
NurbsPatch refinedPatch(const BodyConfig& config);
HierarchicalSpace bodySpace(const BodyConfig& config);

}  // namespace ffriga
