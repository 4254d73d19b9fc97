#include "preproc/input/visualisation_config.h"

#include <cmath>

#include "common/base/error.h"
#include "common/splines/point_inversion.h"

namespace ffriga {

namespace {

Eigen::VectorXd parsePoint(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                           int s) {
  if (static_cast<int>(node.size()) != s) {
    throw inputError(doc, node, key, Str() << "expected " << s << " coordinates, found " << node.size());
  }
  Eigen::VectorXd x(s);
  for (int c = 0; c < s; ++c) x(c) = getDouble(doc, node[c], key);
  return x;
}

// Inverts every point of the line onto the patch; a point outside the body is an input error.
void invertLine(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                const NurbsPatch& patch, double size, StressLineConfig* line) {
  const double tolerance = 1e-10 * size;
  for (int i = 0; i < line->points; ++i) {
    const double t = line->points == 1 ? 0.0 : static_cast<double>(i) / (line->points - 1);
    const Eigen::VectorXd x = (1.0 - t) * line->from + t * line->to;
    const InversionResult r = invertPoint(patch, x, tolerance);
    if (!r.found) {
      Str where;
      where << "point " << i << " (";
      for (int c = 0; c < x.size(); ++c) where << (c ? ", " : "") << x(c);
      where << ") m lies outside the body (nearest body point " << r.distance << " m away)";
      throw inputError(doc, node, key, where);
    }
    line->parameters.push_back(r.xi);
  }
}

}  // namespace

VisualisationConfig readVisualisation(const YamlDocument& doc, const YAML::Node& node, int d) {
  VisualisationConfig v;
  v.subdivisions = d == 2 ? 2 : 1;
  if (!node) return v;
  if (node["subdivisions"]) {
    v.subdivisions = getInt(doc, node["subdivisions"], "visualisation.subdivisions");
  }
  const YAML::Node lines = node["stress_lines"];
  for (std::size_t i = 0; lines && i < lines.size(); ++i) {
    const std::string key = Str() << "visualisation.stress_lines[" << i << "]";
    StressLineConfig line;
    line.name = getString(doc, lines[i]["name"], key + ".name");
    for (const auto& other : v.stress_lines) {
      if (other.name == line.name) {
        throw inputError(doc, lines[i]["name"], key + ".name",
                         "stress line name '" + line.name + "' is used twice");
      }
    }
    line.from = parsePoint(doc, lines[i]["from"], key + ".from", d);
    line.to = parsePoint(doc, lines[i]["to"], key + ".to", d);
    line.points = getInt(doc, lines[i]["points"], key + ".points");
    v.stress_lines.push_back(std::move(line));
  }
  return v;
}

void invertStressLines(const YamlDocument& doc, const NurbsPatch& geometry,
                       VisualisationConfig& v) {
  if (v.stress_lines.empty()) return;
  const Eigen::MatrixXd& P = geometry.points();
  const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
  const YAML::Node& root = doc.root;  // const: looking up creates no entries
  const YAML::Node lines =
      root["visualisation"] ? root["visualisation"]["stress_lines"] : YAML::Node();
  const std::size_t given = lines ? lines.size() : 0;
  for (std::size_t i = 0; i < v.stress_lines.size(); ++i) {
    // Lines after the given ones were derived by the design block (body_config.h).
    const bool derived = i >= given;
    const std::string key =
        derived ? std::string("design") : Str() << "visualisation.stress_lines[" << i << "]";
    invertLine(doc, derived ? root["design"] : lines[i], key, geometry, size, &v.stress_lines[i]);
  }
}

}  // namespace ffriga
