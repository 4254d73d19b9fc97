// The body file's `visualisation` key (schemas/body.schema.json): how finely igaprep samples
// the body for pictures (the visualisation mesh, common/sid/sid.h VisualisationMesh) and the
// lines of points along which the runtime recovers stresses (e.g. the symmetry axis under
// the contact point, for the paper's Fig. 10). Lines are given in the geometry's
// coordinates (m) and inverted onto the exact patch when the file is checked, so that a line
// leaving the body is refused with the file, key and line.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/splines/nurbs_patch.h"
#include "common/input/yaml_input.h"

namespace ffriga {

struct StressLineConfig {
  std::string name;
  Eigen::VectorXd from, to;  // geometry coordinates, m
  int points = 101;          // evenly spaced from `from` to `to`, both included
  // Patch parameters of each point (filled by invertStressLines).
  std::vector<std::array<double, 3>> parameters;
};

struct VisualisationConfig {
  // Cells per element and parametric direction of the visualisation mesh; 0: no mesh.
  int subdivisions = 0;
  std::vector<StressLineConfig> stress_lines;
};

// Reads `visualisation` of a body with d parametric directions (and as many coordinates).
// Default subdivisions: 2 for plane sections (cheap), 1 for solids (memory grows with
// points x nq). node may be absent (the defaults, no stress lines).
VisualisationConfig readVisualisation(const YamlDocument& doc, const YAML::Node& node, int d);

// Inverts every point of every stress line onto the exact patch (their `parameters`); a
// point outside the body is an InputError naming the line's key.
void invertStressLines(const YamlDocument& doc, const NurbsPatch& geometry,
                       VisualisationConfig& visualisation);

}  // namespace ffriga
