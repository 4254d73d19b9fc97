#include "preproc/input/body_config.h"

#include "preproc/input/size_estimate.h"

#include <array>
#include <map>

#include "common/input/json_schema.h"
#include "common/splines/refinement.h"
#include "common/input/schemas.h"
#include "common/input/yaml_overrides.h"
#include "preproc/geometry/contact_region.h"
#include "preproc/geometry/geometry_builders.h"

namespace ffriga {

const char* toString(ModelKind model) {
  switch (model) {
    case ModelKind::kAxisymmetric:
      return "axisymmetric";
    case ModelKind::kSolid:
      return "solid";
  }
  return "?";
}

namespace {

NurbsPatch explicitNurbs(const YamlDocument& doc, const YAML::Node& g) {
  const YAML::Node degrees = g["degrees"];
  const YAML::Node knots = g["knots"];
  const int d = static_cast<int>(degrees.size());
  if (static_cast<int>(knots.size()) != d) {
    throw inputError(
        doc, knots, "geometry.knots",
        Str() << "expected one knot vector per degree (" << d << "), found " << knots.size());
  }
  std::vector<KnotVector> U;
  int n = 1;
  for (int a = 0; a < d; ++a) {
    const std::string key = Str() << "geometry.knots[" << a << "]";
    std::vector<double> u;
    for (std::size_t i = 0; i < knots[a].size(); ++i) u.push_back(getDouble(doc, knots[a][i], key));
    const int p = getInt(doc, degrees[a], Str() << "geometry.degrees[" << a << "]");
    const std::string reason = KnotVector::validate(u, p);
    if (!reason.empty()) throw inputError(doc, knots[a], key, reason);
    U.emplace_back(std::move(u), p);
    n *= U.back().numBasis();
  }
  const YAML::Node cps = g["control_points"];
  const YAML::Node ws = g["weights"];
  if (static_cast<int>(cps.size()) != n) {
    throw inputError(doc, cps, "geometry.control_points",
                     Str() << "the knot vectors define " << n << " basis functions, so " << n
                           << " control points are expected; found " << cps.size());
  }
  if (static_cast<int>(ws.size()) != n) {
    throw inputError(
        doc, ws, "geometry.weights",
        Str() << "expected one weight per control point (" << n << "), found " << ws.size());
  }
  const int s = static_cast<int>(cps[0].size());
  Eigen::MatrixXd P(n, s);
  Eigen::VectorXd w(n);
  for (int k = 0; k < n; ++k) {
    const std::string key = Str() << "geometry.control_points[" << k << "]";
    if (static_cast<int>(cps[k].size()) != s) {
      throw inputError(doc, cps[k], key,
                       Str() << "expected " << s << " coordinates like the first point, found "
                             << cps[k].size());
    }
    for (int c = 0; c < s; ++c) P(k, c) = getDouble(doc, cps[k][c], key);
    w(k) = getDouble(doc, ws[k], Str() << "geometry.weights[" << k << "]");
  }
  return NurbsPatch(std::move(U), std::move(P), std::move(w));
}

std::vector<int> perDirection(const YamlDocument& doc, const YAML::Node& node,
                              const std::string& key, int d) {
  std::vector<int> v(d, 0);
  if (!node || node.IsNull()) return v;
  if (static_cast<int>(node.size()) != d) {
    throw inputError(doc, node, key,
                     Str() << "expected one entry per parametric direction (" << d << "), found "
                           << node.size());
  }
  for (int a = 0; a < d; ++a) v[a] = getInt(doc, node[a], Str() << key << "[" << a << "]");
  return v;
}

const char* const kDirectionNames[3] = {"xi", "eta", "zeta"};

// Why the boundary face of `patch` at the lower (upper = false) or upper end of direction
// `dir` is degenerate, or "" if it is regular. Degenerate: its control net collapses along
// another direction (every line of that direction is one point: an axis, a pole line, an
// equator) or coincides with the opposite face (a closed seam). Such faces carry tied
// control points, and a box or contact region touching them would refine or load a
// degenerate point (DESIGN.md). A face that merely lies on the symmetry axis, like the
// edge xi = 0 of the half-disk (x = 0, u_r = 0 there, but not collapsed), is regular.
// Tolerance: 1e-12 of the patch size, as for tied control points.
std::string degenerateFace(const NurbsPatch& patch, int dir, bool upper) {
  const Eigen::MatrixXd& X = patch.points();
  const double tol = 1e-12 * (X.colwise().maxCoeff() - X.colwise().minCoeff()).maxCoeff();
  const int d = patch.paramDim();
  std::array<int, 3> n{1, 1, 1};
  for (int a = 0; a < d; ++a) n[a] = patch.numBasis(a);
  const auto same = [&](std::array<int, 3> i, std::array<int, 3> j) {
    return (X.row(patch.linearIndex(i)) - X.row(patch.linearIndex(j))).norm() <= tol;
  };
  const auto allOnFace = [&](const auto& test) {  // test(i) for every i on the face
    std::array<int, 3> lo{0, 0, 0}, hi = n, i{};
    lo[dir] = upper ? n[dir] - 1 : 0;
    hi[dir] = lo[dir] + 1;
    for (i[2] = lo[2]; i[2] < hi[2]; ++i[2])
      for (i[1] = lo[1]; i[1] < hi[1]; ++i[1])
        for (i[0] = lo[0]; i[0] < hi[0]; ++i[0])
          if (!test(i)) return false;
    return true;
  };
  for (int b = 0; b < d; ++b) {
    if (b == dir) continue;
    if (allOnFace([&](std::array<int, 3> i) {
          if (i[b] == 0) return true;
          std::array<int, 3> j = i;
          --j[b];
          return same(i, j);
        })) {
      return Str() << "its control points collapse along " << kDirectionNames[b]
                   << ": an axis, a pole line or a collapsed edge";
    }
  }
  if (allOnFace([&](std::array<int, 3> i) {
        std::array<int, 3> j = i;
        j[dir] = upper ? 0 : n[dir] - 1;
        return same(i, j);
      })) {
    return "it coincides with the opposite face: a closed seam";
  }
  return "";
}

// The common end of the error messages about degenerate faces.
const char* const kDegenerateRule =
    "boxes and contact regions must stay off collapsed faces and seams (faces on the "
    "symmetry axis of an axisymmetric section are allowed)";

void parseContact(const YamlDocument& doc, const YAML::Node& node, const NurbsPatch& patch,
                  ContactConfig* c) {
  if (!node) return;
  c->present = true;
  if (node["name"]) c->name = getString(doc, node["name"], "contact.name");
  const std::string face = getString(doc, node["face"], "contact.face");
  parseFaceName(face, &c->direction, &c->upper);  // the schema's enum has checked the name
  const int d = patch.paramDim();
  if (c->direction >= d) {
    throw inputError(doc, node["face"], "contact.face",
                     Str() << "face '" << face << "' does not exist on a patch with " << d
                           << " parametric directions");
  }
  const std::string faceWhy = degenerateFace(patch, c->direction, c->upper);
  if (!faceWhy.empty()) {
    throw inputError(
        doc, node["face"], "contact.face",
        Str() << "face '" << face << "' is degenerate (" << faceWhy << "); " << kDegenerateRule);
  }
  const YAML::Node region = node["region"];
  if (static_cast<int>(region.size()) != d - 1) {
    throw inputError(doc, region, "contact.region",
                     Str() << "expected one [lo, hi] pair per parametric direction along the "
                           << "face (" << d - 1 << "), found " << region.size());
  }
  int s = 0;
  for (int a = 0; a < d; ++a) {
    if (a == c->direction) continue;
    const std::string key = Str() << "contact.region[" << s << "]";
    const double lo = getDouble(doc, region[s][0], key);
    const double hi = getDouble(doc, region[s][1], key);
    const double u0 = patch.knots(a).front(), u1 = patch.knots(a).back();
    if (!(lo < hi) || lo < u0 || hi > u1) {
      throw inputError(doc, region[s], key,
                       Str() << "expected lo < hi inside the knot range [" << u0 << ", " << u1
                             << "] of direction " << a << ", found [" << lo << ", " << hi << "]");
    }
    for (const bool up : {false, true}) {
      if ((up ? hi < u1 : lo > u0)) continue;
      const std::string why = degenerateFace(patch, a, up);
      if (!why.empty()) {
        throw inputError(doc, region[s], key,
                         Str() << "the region touches the degenerate face " << faceName(a, up)
                               << " (" << why << "); " << kDegenerateRule);
      }
    }
    c->bounds.push_back({lo, hi});
    ++s;
  }
}

void parseMarkers(const YamlDocument& doc, const YAML::Node& node, const NurbsPatch& patch,
                  std::vector<MarkerConfig>* markers) {
  if (!node) return;
  const int d = patch.paramDim();
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string key = Str() << "markers[" << i << "]";
    MarkerConfig m;
    m.name = getString(doc, node[i]["name"], key + ".name");
    for (const auto& other : *markers) {
      if (other.name == m.name) {
        throw inputError(doc, node[i]["name"], key + ".name",
                         "marker name '" + m.name + "' is used twice");
      }
    }
    if (node[i]["interface"]) m.interface = node[i]["interface"].as<bool>();
    if (bool(node[i]["parameters"]) == bool(node[i]["face"]))
      throw inputError(doc, node[i], key,
                       "expected either 'parameters' (a point) or 'face' (a boundary face)");
    if (node[i]["face"]) {
      const std::string face = getString(doc, node[i]["face"], key + ".face");
      parseFaceName(face, &m.face_direction, &m.face_upper);  // the schema's enum checked it
      if (d != 3 || m.face_direction >= d)
        throw inputError(doc, node[i]["face"], key + ".face",
                         "face markers are for 3D (solid) bodies");
      const std::string why = degenerateFace(patch, m.face_direction, m.face_upper);
      if (!why.empty())
        throw inputError(doc, node[i]["face"], key + ".face",
                         Str() << "face '" << face << "' is degenerate (" << why << ")");
      m.face = true;
      markers->push_back(std::move(m));
      continue;
    }
    const YAML::Node p = node[i]["parameters"];
    if (static_cast<int>(p.size()) != d) {
      throw inputError(doc, p, key + ".parameters",
                       Str() << "expected " << d << " parametric coordinates, found " << p.size());
    }
    for (int a = 0; a < d; ++a) {
      const double v = getDouble(doc, p[a], key + ".parameters");
      if (v < patch.knots(a).front() || v > patch.knots(a).back()) {
        throw inputError(doc, p[a], key + ".parameters",
                         Str() << "parameter " << a << " = " << v << " lies outside the knot "
                               << "range [" << patch.knots(a).front() << ", "
                               << patch.knots(a).back() << "]");
      }
      m.parameters.push_back(v);
    }
    markers->push_back(std::move(m));
  }
}

void parseReduction(const YamlDocument& doc, const YAML::Node& node, bool hasContact,
                    const std::vector<MarkerConfig>& markers, ReductionConfig* r) {
  if (node) {
    if (node["method"]) r->method = getString(doc, node["method"], "reduction.method");
    if (node["normal_modes"])
      r->normal_modes = getInt(doc, node["normal_modes"], "reduction.normal_modes");
    if (node["frame"]) r->frame = getString(doc, node["frame"], "reduction.frame");
    if (node["frame_marker"])
      r->frame_marker = getString(doc, node["frame_marker"], "reduction.frame_marker");
    const YAML::Node damping = node["damping"];
    for (std::size_t i = 0; damping && i < damping.size(); ++i) {
      const std::string key = Str() << "reduction.damping[" << i << "]";
      DampingBand b;
      if (bool(damping[i]["from_hz"]) == bool(damping[i]["from_first_elastic"]))
        throw inputError(doc, damping[i], key, "give either from_hz or from_first_elastic");
      if (damping[i]["from_hz"])
        b.from_hz = getDouble(doc, damping[i]["from_hz"], key + ".from_hz");
      else
        b.from_first_elastic =
            getDouble(doc, damping[i]["from_first_elastic"], key + ".from_first_elastic");
      if (damping[i]["to_hz"]) b.to_hz = getDouble(doc, damping[i]["to_hz"], key + ".to_hz");
      b.ratio = getDouble(doc, damping[i]["ratio"], key + ".ratio");
      if (!(b.to_hz > b.from_hz)) {
        throw inputError(
            doc, damping[i], key,
            Str() << "expected from_hz < to_hz, found [" << b.from_hz << ", " << b.to_hz << ")");
      }
      r->damping.push_back(b);
    }
  }
  const YAML::Node where = node ? node : doc.root;
  // Without a `reduction` block the file may still serve for geometry checks; igaprep -o
  // repeats this check (preprocessBody).
  bool interfaceMarker = false;
  for (const auto& m : markers) interfaceMarker = interfaceMarker || m.interface;
  if (node && r->method == "craig_bampton" && !hasContact && !interfaceMarker) {
    throw inputError(doc, where, "reduction.method",
                     "craig_bampton needs an interface: a contact region (key 'contact') or a "
                     "marker with 'interface: true'");
  }
  if (r->method == "modal" && r->normal_modes < 1) {
    throw inputError(doc, node["normal_modes"], "reduction.normal_modes",
                     "the modal method needs at least one normal mode, found 0");
  }
  if (r->frame == "tangent") {
    bool found = false;
    for (const auto& m : markers) found = found || m.name == r->frame_marker;
    if (!found) {
      throw inputError(doc, where, "reduction.frame_marker",
                       r->frame_marker.empty()
                           ? std::string("frame: tangent needs frame_marker, the name of a marker")
                           : "no marker named '" + r->frame_marker + "' (see key 'markers')");
    }
    for (const auto& m : markers)
      if (m.name == r->frame_marker && m.face)
        throw inputError(doc, node["frame_marker"], "reduction.frame_marker",
                         "the tangent frame's marker must be a point (parameters), not a face");
  }
}

void parseInsert(const YamlDocument& doc, const YAML::Node& node, int d, BodyConfig& c) {
  c.insert.assign(d, {});
  if (!node || node.IsNull()) return;
  if (static_cast<int>(node.size()) != d) {
    throw inputError(doc, node, "refinement.insert",
                     Str() << "expected one knot list per parametric direction (" << d
                           << "), found " << node.size());
  }
  for (int a = 0; a < d; ++a) {
    for (std::size_t i = 0; i < node[a].size(); ++i) {
      c.insert[a].push_back(getDouble(doc, node[a][i], Str() << "refinement.insert[" << a << "]"));
    }
  }
}

// Reads hierarchy.* and checks the boxes against the level grids of the refined patch.
void parseHierarchy(const YamlDocument& doc, const YAML::Node& h, const NurbsPatch& patch,
                    BodyConfig& c) {
  if (!h) return;
  const int d = patch.paramDim();
  c.hierarchy.levels = getInt(doc, h["levels"], "hierarchy.levels");
  if (h["truncated"]) c.hierarchy.truncated = h["truncated"].as<bool>();
  if (h["as_global_reference"]) c.global_reference = h["as_global_reference"].as<bool>();
  const std::string levelProblem = checkLevels(patch, c.hierarchy.levels);
  if (!levelProblem.empty()) throw inputError(doc, h["levels"], "hierarchy.levels", levelProblem);
  const YAML::Node boxes = h["boxes"];
  const int nb = boxes ? static_cast<int>(boxes.size()) : 0;
  if (nb != c.hierarchy.levels - 1) {
    throw inputError(doc, boxes ? boxes : h["levels"],
                     boxes ? "hierarchy.boxes" : "hierarchy.levels",
                     Str() << "expected one box per refined level (" << c.hierarchy.levels - 1
                           << " for levels = " << c.hierarchy.levels << "), found " << nb);
  }
  for (int b = 0; b < nb; ++b) {
    const std::string key = Str() << "hierarchy.boxes[" << b << "]";
    if (static_cast<int>(boxes[b].size()) != d) {
      throw inputError(doc, boxes[b], key,
                       Str() << "expected one [lo, hi] interval per parametric direction (" << d
                             << "), found " << boxes[b].size());
    }
    ParamBox box;
    for (int a = 0; a < d; ++a) {
      const std::string k = Str() << key << "[" << a << "]";
      box.lower[a] = getDouble(doc, boxes[b][a][0], k);
      box.upper[a] = getDouble(doc, boxes[b][a][1], k);
    }
    c.hierarchy.boxes.push_back(box);
  }
  const BoxProblem problem = validateBoxes(patch, c.hierarchy);
  if (!problem.reason.empty()) {
    if (problem.box < 0) throw inputError(doc, h["levels"], "hierarchy.levels", problem.reason);
    const YAML::Node node = problem.dir < 0 ? boxes[problem.box] : boxes[problem.box][problem.dir];
    std::string key = Str() << "hierarchy.boxes[" << problem.box << "]";
    if (problem.dir >= 0) key = Str() << key << "[" << problem.dir << "]";
    throw inputError(doc, node, key,
                     Str() << "box of level " << problem.box + 1 << ": " << problem.reason);
  }
  for (int b = 0; b < nb; ++b) {
    const ParamBox& box = c.hierarchy.boxes[b];
    for (int a = 0; a < d; ++a) {
      for (const bool up : {false, true}) {
        // Bounds are snapped onto knot lines by validateBoxes: exact comparison.
        if (up ? box.upper[a] < patch.knots(a).back() : box.lower[a] > patch.knots(a).front())
          continue;
        const std::string why = degenerateFace(patch, a, up);
        if (!why.empty()) {
          throw inputError(doc, boxes[b][a], Str() << "hierarchy.boxes[" << b << "][" << a << "]",
                           Str() << "box of level " << b + 1 << " touches the degenerate face "
                                 << faceName(a, up) << " (" << why << "); " << kDegenerateRule);
        }
      }
    }
  }
}

}  // namespace

double ReductionConfig::dampingRatio(double f_hz, double f1_hz) const {
  double zeta = 0.0;
  for (const DampingBand& b : damping) {
    const double from = b.from_first_elastic > 0.0 ? b.from_first_elastic * f1_hz : b.from_hz;
    if (f_hz >= from && f_hz < b.to_hz) zeta = b.ratio;
  }
  return zeta;
}

BodyConfig parseBodyConfig(YamlDocument doc, double memory_limit_bytes) {
  static const JsonSchema schema(kBodySchema, "body.schema.json");
  schema.validate(doc);
  BodyConfig c;
  const YAML::Node& root = doc.root;
  c.name = getString(doc, root["name"], "name");
  c.model = getString(doc, root["model"], "model") == "axisymmetric" ? ModelKind::kAxisymmetric
                                                                     : ModelKind::kSolid;
  const YAML::Node m = root["material"];
  c.material.youngs_modulus = getDouble(doc, m["youngs_modulus"], "material.youngs_modulus");
  c.material.poisson_ratio = getDouble(doc, m["poisson_ratio"], "material.poisson_ratio");
  c.material.density = getDouble(doc, m["density"], "material.density");

  const YAML::Node g = root["geometry"];
  c.geometry_type = getString(doc, g["type"], "geometry.type");
  try {
    if (c.geometry_type == "half_disk") {
      c.geometry_radius = getDouble(doc, g["radius"], "geometry.radius");
      c.geometry = halfDisk(c.geometry_radius);
    } else if (c.geometry_type == "sphere") {
      c.geometry_radius = getDouble(doc, g["radius"], "geometry.radius");
      c.geometry = solidSphere(c.geometry_radius);
    } else if (c.geometry_type == "rod") {
      c.geometry_radius = getDouble(doc, g["radius"], "geometry.radius");
      c.geometry_length = getDouble(doc, g["length"], "geometry.length");
      c.geometry = solidRod(c.geometry_radius, c.geometry_length);
    } else {
      c.geometry = explicitNurbs(doc, g);
    }
  } catch (const std::invalid_argument& e) {
    throw inputError(doc, g, "geometry", e.what());
  }
  const int d = c.geometry.paramDim();
  const int s = c.geometry.spaceDim();
  const bool axi = c.model == ModelKind::kAxisymmetric;
  if ((axi && (d != 2 || s != 2)) || (!axi && (d != 3 || s != 3))) {
    throw inputError(doc, root["model"], "model",
                     Str() << "model '" << toString(c.model) << "' needs "
                           << (axi ? "a 2D surface patch with 2D control points"
                                   : "a 3D volume patch with 3D control points")
                           << ", the geometry has " << d << " parametric directions and " << s
                           << " coordinates");
  }
  if (axi) {
    for (int k = 0; k < c.geometry.numControlPoints(); ++k) {
      if (c.geometry.points()(k, 0) < 0.0) {
        throw inputError(doc, g, "geometry",
                         Str() << "an axisymmetric section must lie in x >= 0 (x is the radius); "
                               << "control point " << k
                               << " has x = " << c.geometry.points()(k, 0));
      }
    }
  }
  const YAML::Node r = root["refinement"];
  c.elevate_degree =
      perDirection(doc, r ? r["elevate_degree"] : YAML::Node(), "refinement.elevate_degree", d);
  c.insert_knots =
      perDirection(doc, r ? r["insert_knots"] : YAML::Node(), "refinement.insert_knots", d);
  for (int a = 0; a < d; ++a) {
    if (c.geometry.degree(a) + c.elevate_degree[a] > kMaxDegree) {
      throw inputError(doc, r["elevate_degree"][a],
                       Str() << "refinement.elevate_degree[" << a << "]",
                       Str() << "degree " << c.geometry.degree(a) << " + " << c.elevate_degree[a]
                             << " exceeds the maximum degree " << kMaxDegree);
    }
  }
  parseInsert(doc, r ? r["insert"] : YAML::Node(), d, c);
  const double limit = memory_limit_bytes > 0.0 ? memory_limit_bytes : physicalMemoryBytes();
  checkSizeLimit(doc, r, estimateSize(c), limit);  // before the refinement allocates
  NurbsPatch refined;
  try {
    refined = refinedPatch(c);
  } catch (const std::invalid_argument& e) {
    throw inputError(doc, r["insert"], "refinement.insert", e.what());
  }
  parseHierarchy(doc, root["hierarchy"], refined, c);
  if (c.global_reference) checkSizeLimit(doc, r, estimateGlobalReferenceSize(c, refined), limit);
  if (!c.hierarchy.truncated && !c.global_reference) {
    try {
      HierarchicalSpace(refined, c.hierarchy);  // HB can fail (zero weights): report it now
    } catch (const std::invalid_argument& e) {
      throw inputError(doc, root["hierarchy"]["truncated"], "hierarchy.truncated", e.what());
    }
  }
  parseContact(doc, root["contact"], c.geometry, &c.contact);
  parseMarkers(doc, root["markers"], c.geometry, &c.markers);
  parseReduction(doc, root["reduction"], c.contact.present, c.markers, &c.reduction);
  c.visualisation = parseVisualisation(doc, root["visualisation"], c.geometry);
  c.source = std::move(doc);
  return c;
}

BodyConfig loadBodyConfig(const std::string& path, double memory_limit_bytes,
                          const std::vector<std::string>& sets) {
  YamlDocument doc = loadYamlFile(path);
  applyOverrides(doc, sets);
  return parseBodyConfig(std::move(doc), memory_limit_bytes);
}

NurbsPatch refinedPatch(const BodyConfig& config) {
  NurbsPatch patch = config.geometry;
  for (int a = 0; a < patch.paramDim(); ++a) {
    if (config.elevate_degree[a] > 0) patch = elevateDegree(patch, a, config.elevate_degree[a]);
  }
  for (int a = 0; a < patch.paramDim(); ++a) {
    if (config.insert_knots[a] > 0) {
      patch = insertKnots(patch, a, uniformInsertionKnots(patch.knots(a), config.insert_knots[a]));
    }
  }
  for (int a = 0; a < static_cast<int>(config.insert.size()); ++a) {
    if (!config.insert[a].empty()) {
      try {
        patch = insertKnots(patch, a, config.insert[a]);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(Str() << "direction " << a << ": " << e.what());
      }
    }
  }
  return patch;
}

HierarchicalSpace bodySpace(const BodyConfig& config) {
  const NurbsPatch patch = refinedPatch(config);
  if (config.global_reference) {
    return HierarchicalSpace(globalReferencePatch(patch, config.hierarchy), HierarchyOptions{});
  }
  return HierarchicalSpace(patch, config.hierarchy);
}

}  // namespace ffriga

namespace ffriga {

std::vector<std::vector<int>> tiedControlPoints(const HierarchicalSpace& space) {
  // Degeneracies are read from the THB control points (refined control points of the
  // patch): HB control points of one level can coincide without any degeneracy (functions
  // whose only coarse parent in the region is the same). HB and THB share the active set.
  Eigen::MatrixXd thb;
  if (!space.truncated()) {
    HierarchyOptions o = space.options();
    o.truncated = true;
    thb = HierarchicalSpace(space.basePatch(), o).controlPoints();
  }
  const Eigen::MatrixXd& P = space.truncated() ? space.controlPoints() : thb;
  const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
  std::vector<std::vector<int>> groups;
  for (const auto& g : coincidentPoints(P, 1e-12 * size)) {
    std::map<int, std::vector<int>> byLevel;
    for (int k : g) byLevel[space.functionLevel(k)].push_back(k);
    for (auto& entry : byLevel)
      if (entry.second.size() >= 2) groups.push_back(std::move(entry.second));
  }
  return groups;
}

DofCount countDofs(const HierarchicalSpace& space, ModelKind model) {
  const std::vector<std::vector<int>> groups = tiedControlPoints(space);
  const Eigen::MatrixXd& P = space.controlPoints();
  const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
  DofCount n;
  n.groups = static_cast<int>(groups.size());
  std::vector<char> tiedAway(P.rows(), 0);
  for (const auto& g : groups) {
    n.tied += static_cast<int>(g.size()) - 1;
    for (std::size_t i = 1; i < g.size(); ++i) tiedAway[g[i]] = 1;
  }
  if (model == ModelKind::kAxisymmetric) {
    for (int k = 0; k < P.rows(); ++k) n.on_axis += !tiedAway[k] && P(k, 0) <= 1e-12 * size;
  }
  n.ndof = space.spaceDim() * (space.numFunctions() - n.tied) - n.on_axis;
  return n;
}

}  // namespace ffriga
