#include "preproc/input/body_config.h"

#include <utility>

#include "common/base/spelling.h"
#include "common/input/json_schema.h"
#include "common/input/schemas.h"
#include "common/input/yaml_overrides.h"
#include "preproc/geometry/contact_region.h"
#include "preproc/input/body_checks.h"

namespace ffriga {

namespace {

// YAML spelling of GeometryKind (the schema restricts geometry.type to these).
const Spelling<GeometryKind> kGeometryKinds[] = {{"half_disk", GeometryKind::kHalfDisk},
                                                 {"sphere", GeometryKind::kSphere},
                                                 {"rod", GeometryKind::kRod},
                                                 {"nurbs", GeometryKind::kNurbs}};

}  // namespace

bool parseKind(std::string_view text, GeometryKind* kind) {
  return parseSpelling(kGeometryKinds, text, kind);
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

void parseInsert(const YamlDocument& doc, const YAML::Node& node, int d, BodyConfig& c) {
  c.refinement.insert.assign(d, {});
  if (!node || node.IsNull()) return;
  if (static_cast<int>(node.size()) != d) {
    throw inputError(doc, node, "refinement.insert",
                     Str() << "expected one knot list per parametric direction (" << d
                           << "), found " << node.size());
  }
  for (int a = 0; a < d; ++a) {
    for (std::size_t i = 0; i < node[a].size(); ++i) {
      c.refinement.insert[a].push_back(getDouble(doc, node[a][i], Str() << "refinement.insert[" << a << "]"));
    }
  }
}

void parseReduction(const YamlDocument& doc, const YAML::Node& node, bool hasContact,
                    const std::vector<MarkerConfig>& markers, ReductionConfig* r) {
  if (node) {
    r->method = getKind<ReductionMethod>(doc, node["method"], "reduction.method");
    r->normal_modes = getInt(doc, node["normal_modes"], "reduction.normal_modes");
    r->frame = getKind<FrameKind>(doc, node["frame"], "reduction.frame");
    for (const char* key : {"interface_modes", "pressure_patches"}) {
      if (node[key] && r->method != ReductionMethod::kCraigBampton) {
        throw inputError(doc, node[key], Str() << "reduction." << key,
                         "reduces a Craig-Bampton interface, but the method is modal");
      }
    }
    if (node["interface_modes"])
      r->interface_modes = getInt(doc, node["interface_modes"], "reduction.interface_modes");
    if (const YAML::Node pp = node["pressure_patches"]) {
      PressurePatchConfig& c = r->pressure_patches;
      c.given = true;
      if (pp["radius"])
        c.radius = getDouble(doc, pp["radius"], "reduction.pressure_patches.radius");
      c.radii = getInt(doc, pp["radii"], "reduction.pressure_patches.radii");  // schema defaults
      c.degree = getInt(doc, pp["degree"], "reduction.pressure_patches.degree");
      c.tangential = getBool(doc, pp["tangential"], "reduction.pressure_patches.tangential");
      for (std::size_t i = 0; pp["centre"] && i < pp["centre"].size(); ++i) {
        c.centre.push_back(getDouble(doc, pp["centre"][i],
                                     Str() << "reduction.pressure_patches.centre[" << i << "]"));
      }
    }
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
  if (node && r->method == ReductionMethod::kCraigBampton && !hasContact && !interfaceMarker) {
    throw inputError(doc, where, "reduction.method",
                     "craig_bampton needs an interface: a contact region (key 'contact' or "
                     "'contacts') or a marker with 'interface: true'");
  }
  if (r->method == ReductionMethod::kModal && r->normal_modes < 1) {
    throw inputError(doc, node["normal_modes"], "reduction.normal_modes",
                     "the modal method needs at least one normal mode, found 0");
  }
  if (r->frame == FrameKind::kTangent) {
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

// One box of hierarchy.boxes (at `key`): one interval per parametric direction.
ParamBox readHierarchyBox(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                          int d) {
  if (static_cast<int>(node.size()) != d) {
    throw inputError(doc, node, key,
                     Str() << "expected one [lo, hi] interval per parametric direction (" << d
                           << "), found " << node.size());
  }
  ParamBox box;
  for (int a = 0; a < d; ++a) {
    const std::string k = Str() << key << "[" << a << "]";
    box.lower[a] = getDouble(doc, node[a][0], k);
    box.upper[a] = getDouble(doc, node[a][1], k);
  }
  return box;
}

// Reads hierarchy.*: the levels and each level's boxes (one, or a list), one interval per
// direction (their number and the level grids of the refined patch are checked by
// checkBodyConfig).
void readHierarchy(const YamlDocument& doc, const YAML::Node& h, int d, BodyConfig& c) {
  if (!h) return;
  c.hierarchy.levels = getInt(doc, h["levels"], "hierarchy.levels");
  if (h["truncated"]) c.hierarchy.truncated = h["truncated"].as<bool>();
  if (h["as_global_reference"]) c.global_reference = h["as_global_reference"].as<bool>();
  const YAML::Node boxes = h["boxes"];
  const int nb = boxes ? static_cast<int>(boxes.size()) : 0;
  for (int b = 0; b < nb; ++b) {
    const int members = listOfBoxes(boxes[b]) ? static_cast<int>(boxes[b].size()) : 1;
    LevelBoxes level;
    for (int k = 0; k < members; ++k)
      level.push_back(
          readHierarchyBox(doc, hierarchyBoxNode(boxes[b], k), hierarchyBoxKey(boxes[b], b, k), d));
    c.hierarchy.boxes.push_back(level);
  }
}

// Reads one contact region (at `key`): the face (one of the patch's) and one [lo, hi] per
// direction along it.
ContactConfig readContact(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                          int item, int d) {
  ContactConfig c;
  c.key = key;
  c.item = item;
  c.name = getString(doc, node["name"], key + ".name");  // `contact`: the schema's default
  const std::string face = getString(doc, node["face"], key + ".face");
  parseFaceName(face, &c.direction, &c.upper);  // the schema's enum has checked the name
  if (c.direction >= d) {
    throw inputError(doc, node["face"], key + ".face",
                     Str() << "face '" << face << "' does not exist on a patch with " << d
                           << " parametric directions");
  }
  const YAML::Node region = node["region"];
  if (static_cast<int>(region.size()) != d - 1) {
    throw inputError(doc, region, key + ".region",
                     Str() << "expected one [lo, hi] pair per parametric direction along the "
                           << "face (" << d - 1 << "), found " << region.size());
  }
  for (int s = 0; s < d - 1; ++s) {
    const std::string k = Str() << key << ".region[" << s << "]";
    c.bounds.push_back({getDouble(doc, region[s][0], k), getDouble(doc, region[s][1], k)});
  }
  c.gauss = getString(doc, node["collocation"], key + ".collocation") == "gauss";
  return c;
}

// Reads `contact` (the short form: one region) or `contacts` (named regions, file order),
// not both; each region's name once (it names the SID's /contact_surfaces group).
std::vector<ContactConfig> readContacts(const YamlDocument& doc, int d) {
  const YAML::Node one = doc.root["contact"];
  const YAML::Node list = doc.root["contacts"];
  if (one && list) {
    throw inputError(doc, list, "contacts",
                     "give either 'contact' (one region) or 'contacts' (a list of named "
                     "regions), not both");
  }
  std::vector<ContactConfig> out;
  if (one) out.push_back(readContact(doc, one, "contact", -1, d));
  for (std::size_t i = 0; list && i < list.size(); ++i) {
    const std::string key = Str() << "contacts[" << i << "]";
    ContactConfig c = readContact(doc, list[i], key, static_cast<int>(i), d);
    for (const ContactConfig& other : out) {
      if (other.name == c.name) {
        throw inputError(doc, list[i]["name"], key + ".name",
                         Str() << "name '" << c.name << "' is used twice (also " << other.key
                               << ".name): each names a contact surface of the SID file");
      }
    }
    out.push_back(std::move(c));
  }
  return out;
}

// Reads one marker: a point (parameters, one per direction) or a face (3D bodies).
MarkerConfig readMarker(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                        int d) {
  MarkerConfig m;
  m.name = getString(doc, node["name"], key + ".name");
  m.interface = getBool(doc, node["interface"], key + ".interface");
  if (bool(node["parameters"]) == bool(node["face"]))
    throw inputError(doc, node, key,
                     "expected either 'parameters' (a point) or 'face' (a boundary face)");
  if (node["face"]) {
    const std::string face = getString(doc, node["face"], key + ".face");
    parseFaceName(face, &m.face_direction, &m.face_upper);  // the schema's enum checked it
    if (d != 3 || m.face_direction >= d)
      throw inputError(doc, node["face"], key + ".face", "face markers are for 3D (solid) bodies");
    m.face = true;
    return m;
  }
  const YAML::Node p = node["parameters"];
  if (static_cast<int>(p.size()) != d) {
    throw inputError(doc, p, key + ".parameters",
                     Str() << "expected " << d << " parametric coordinates, found " << p.size());
  }
  for (int a = 0; a < d; ++a) m.parameters.push_back(getDouble(doc, p[a], key + ".parameters"));
  return m;
}

void readMarkers(const YamlDocument& doc, const YAML::Node& node, int d,
                 std::vector<MarkerConfig>* markers) {
  for (std::size_t i = 0; node && i < node.size(); ++i) {
    const std::string key = Str() << "markers[" << i << "]";
    const std::string name = getString(doc, node[i]["name"], key + ".name");
    for (const auto& other : *markers) {
      if (other.name == name) {
        throw inputError(doc, node[i]["name"], key + ".name",
                         "marker name '" + name + "' is used twice");
      }
    }
    markers->push_back(readMarker(doc, node[i], key, d));
  }
}

// Reads `geometry`: the kind with its sizes, or the explicit patch.
void readGeometry(const YamlDocument& doc, const YAML::Node& g, GeometryConfig& geometry) {
  geometry.kind = getKind<GeometryKind>(doc, g["type"], "geometry.type");
  if (geometry.kind != GeometryKind::kNurbs)
    geometry.radius = getDouble(doc, g["radius"], "geometry.radius");
  if (geometry.kind == GeometryKind::kRod)
    geometry.length = getDouble(doc, g["length"], "geometry.length");
  if (geometry.kind != GeometryKind::kNurbs) return;
  try {
    geometry.patch = explicitNurbs(doc, g);
  } catch (const std::invalid_argument& e) {
    throw inputError(doc, g, "geometry", e.what());
  }
}

// The model against the geometry's dimensions: an axisymmetric model is a 2D section in
// x >= 0 (x the radius), a solid a 3D volume.
void checkModel(const YamlDocument& doc, const BodyConfig& c) {
  const int d = c.geometry.paramDim();
  const bool nurbs = c.geometry.kind == GeometryKind::kNurbs;
  const int s = nurbs ? c.geometry.patch.spaceDim() : d;
  const bool axi = c.model == ModelKind::kAxisymmetric;
  if ((axi && (d != 2 || s != 2)) || (!axi && (d != 3 || s != 3))) {
    throw inputError(doc, doc.root["model"], "model",
                     Str() << "model '" << toString(c.model) << "' needs "
                           << (axi ? "a 2D surface patch with 2D control points"
                                   : "a 3D volume patch with 3D control points")
                           << ", the geometry has " << d << " parametric directions and " << s
                           << " coordinates");
  }
  if (!axi || !nurbs) return;
  const NurbsPatch& patch = c.geometry.patch;
  for (int k = 0; k < patch.numControlPoints(); ++k) {
    if (patch.points()(k, 0) < 0.0) {
      throw inputError(doc, doc.root["geometry"], "geometry",
                       Str() << "an axisymmetric section must lie in x >= 0 (x is the radius); "
                             << "control point " << k << " has x = " << patch.points()(k, 0));
    }
  }
}

// Reads the request of a `design` block: the impact (partner and speed) or the contact
// radius, and the accuracy level (default by model, impact_design.h).
DesignRequest readDesignRequest(const YamlDocument& doc, const YAML::Node& node, bool section) {
  const YAML::Node impact = node["impact"];
  if (bool(impact) == bool(node["contact_radius"])) {
    throw inputError(doc, node, "design",
                     "give either 'impact' (what hits the body) or 'contact_radius' (the "
                     "largest contact radius to resolve)");
  }
  DesignRequest q;
  q.elements_per_contact_radius =
      node["elements_per_contact_radius"]
          ? getDouble(doc, node["elements_per_contact_radius"],
                      "design.elements_per_contact_radius")
          : (section ? kDefaultElementsPerContactRadius : kDefaultElementsPerContactRadiusSolid);
  q.from_impact = bool(impact);
  if (!q.from_impact) {
    q.contact_radius = getDouble(doc, node["contact_radius"], "design.contact_radius");
    return q;
  }
  q.approach_speed = getDouble(doc, impact["approach_speed"], "design.impact.approach_speed");
  const YAML::Node partner = impact["partner"];
  if (!partner.IsMap()) {
    q.partner = getString(doc, partner, "design.impact.partner") == "plane"
                    ? DesignRequest::Partner::kPlane
                    : DesignRequest::Partner::kSame;
    return q;
  }
  const std::string key = "design.impact.partner";
  q.partner = DesignRequest::Partner::kSphere;
  q.partner_sphere.radius = getDouble(doc, partner["radius"], key + ".radius");
  q.partner_sphere.youngs_modulus =
      getDouble(doc, partner["youngs_modulus"], key + ".youngs_modulus");
  q.partner_sphere.poisson_ratio = getDouble(doc, partner["poisson_ratio"], key + ".poisson_ratio");
  q.partner_sphere.mass =
      sphereMass(q.partner_sphere.radius, getDouble(doc, partner["density"], key + ".density"));
  return q;
}

// The contact point of an explicit patch: design.contact_point.face and .parameters (one
// knot coordinate per direction along the face).
ImpactDesign readPatchDesign(const YamlDocument& doc, const YAML::Node& point, const BodyConfig& c,
                             const DesignRequest& q) {
  const std::string key = "design.contact_point";
  if (!point || !point["face"] || !point["parameters"] || point["direction"]) {
    throw inputError(doc, point ? point : doc.root["design"], point ? key : "design",
                     "an explicit NURBS patch's contact point is a 'face' and its "
                     "'parameters' (knot coordinates along the face)");
  }
  const int d = c.geometry.paramDim();
  int direction = 0;
  bool upper = false;
  parseFaceName(getString(doc, point["face"], key + ".face"), &direction, &upper);
  if (direction >= d)
    throw inputError(doc, point["face"], key + ".face",
                     Str() << "the patch has " << d << " directions");
  const YAML::Node p = point["parameters"];
  if (static_cast<int>(p.size()) != d - 1) {
    throw inputError(
        doc, p, key + ".parameters",
        Str() << "expected " << d - 1 << " knot coordinate(s) along the face, found " << p.size());
  }
  std::vector<double> parameters;
  for (int a = 0; a < d - 1; ++a) parameters.push_back(getDouble(doc, p[a], key + ".parameters"));
  return designPatchImpact(c.geometry.patch, c.model == ModelKind::kAxisymmetric, c.material,
                           direction, upper, parameters, q);
}

// The contact point of a built-in sphere: design.contact_point.direction from the centre
// (the half-disk: its pole, +y, the only point of an axisymmetric impact).
Eigen::Vector3d readContactDirection(const YamlDocument& doc, const YAML::Node& point,
                                     bool halfDisk) {
  const std::string key = "design.contact_point";
  if (point["face"] || point["parameters"] || !point["direction"]) {
    throw inputError(doc, point, key,
                     "a built-in geometry's contact point is a 'direction' from its centre; "
                     "'face' and 'parameters' are for explicit NURBS patches");
  }
  const YAML::Node dir = point["direction"];
  const int dims = halfDisk ? 2 : 3;
  if (static_cast<int>(dir.size()) != dims) {
    throw inputError(doc, dir, key + ".direction",
                     Str() << "expected " << dims << " components, found " << dir.size());
  }
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int a = 0; a < dims; ++a) v(a) = getDouble(doc, dir[a], key + ".direction");
  if (!(v.norm() > 0.0))
    throw inputError(doc, dir, key + ".direction",
                     "the direction is zero: it points at no point of the surface");
  if (halfDisk && !(v(0) == 0.0 && v(1) > 0.0)) {
    throw inputError(doc, dir, key + ".direction",
                     "an axisymmetric impact happens on the axis: the half-disk's contact point "
                     "is its pole, direction [0, 1] (turn the body in the scene for another)");
  }
  return v.normalized();
}

// Reads `design` (preproc/design/impact_design.h) and derives the model from it: the
// refinement, the hierarchy and the contact region, which the file must then not give. A
// sphere's contact direction turns its geometry (c.geometry.contact_direction).
std::optional<ImpactDesign> readDesign(const YamlDocument& doc, BodyConfig& c) {
  const YAML::Node node = doc.root["design"];
  if (!node) return std::nullopt;
  for (const char* key : {"refinement", "hierarchy", "contact", "contacts"}) {
    if (doc.root[key]) {
      throw inputError(doc, doc.root[key], key,
                       Str() << "a designed body (key 'design') derives '" << key
                             << "'; give either the design or the hand-made model, not both");
    }
  }
  const GeometryKind kind = c.geometry.kind;
  if (kind == GeometryKind::kRod) {
    throw inputError(doc, node, "design",
                     "the design rule covers spheres and explicit NURBS patches with a convex "
                     "contact point; give refinement, hierarchy and contact by hand for 'rod'");
  }
  const bool section = c.geometry.paramDim() == 2;
  const DesignRequest q = readDesignRequest(doc, node, section);
  const YAML::Node point = node["contact_point"];
  try {
    if (kind == GeometryKind::kNurbs) return readPatchDesign(doc, point, c, q);
    const bool halfDisk = kind == GeometryKind::kHalfDisk;
    if (point) c.geometry.contact_direction = readContactDirection(doc, point, halfDisk);
    const double r = c.geometry.radius, m = sphereMass(r, c.material.density);
    return halfDisk ? designHalfDiskImpact(r, c.material, m, q)
                    : designSphereImpact(r, c.material, m, q, c.geometry.contact_direction);
  } catch (const std::invalid_argument& e) {
    throw inputError(doc, point ? point : node, point ? "design.contact_point" : "design",
                     e.what());
  }
}

// The designed model into the config: what the hand-made keys would have given.
void applyDesign(const ImpactDesign& d, BodyConfig& c) {
  c.refinement = d.refinement;
  c.hierarchy.levels = d.hierarchy.levels;
  c.hierarchy.boxes = d.hierarchy.boxes;
  ContactConfig contact;
  contact.key = "design";
  contact.designed = true;
  contact.direction = d.face_direction;
  contact.upper = d.face_upper;
  contact.bounds = d.region;
  c.contacts = {contact};
}

// The designed stress line 'axis', unless the file names one so.
void addDesignedStressLine(const ImpactDesign& d, VisualisationConfig& v) {
  for (const StressLineConfig& line : v.stress_lines)
    if (line.name == "axis") return;
  StressLineConfig line;
  line.name = "axis";
  line.from = d.stress_from;
  line.to = d.stress_to;
  line.points = d.stress_points;
  v.stress_lines.push_back(line);
}

// What a designed body gets where its file is silent: the stress line 'axis' and the
// normal modes (impact_design.h): from an impact, every fixed-interface mode below
// kModeCutoffPeriods / T; from a contact radius, kDefaultNormalModesSolid for a solid (the
// schema's 10 for a section).
void addDesignedDefaults(const YamlDocument& doc, BodyConfig& c) {
  addDesignedStressLine(*c.design, c.visualisation);
  const YAML::Node& root = doc.root;  // const: looking up creates no entries
  const bool modesGiven = root["reduction"] && isGiven(doc, root["reduction"]["normal_modes"]);
  if (modesGiven || c.reduction.method != ReductionMethod::kCraigBampton) return;
  const bool solid = c.model == ModelKind::kSolid;
  if (solid) c.reduction.normal_modes = kDefaultNormalModesSolid;  // the first guess
  if (c.design->hertz) {
    c.reduction.mode_cutoff_hz = kModeCutoffPeriods / c.design->hertz->duration;
    c.design->mode_cutoff_hz = c.reduction.mode_cutoff_hz;
    c.design->reasons.push_back(Str() << "normal modes: every fixed-interface mode below "
                                      << kModeCutoffPeriods << " / T = "
                                      << c.reduction.mode_cutoff_hz
                                      << " Hz (faster ones respond quasi-statically: the "
                                      << "constraint modes carry them)");
  } else if (solid) {
    c.design->reasons.push_back(Str() << "normal modes: " << kDefaultNormalModesSolid
                                      << " (a 3D solid has many below the quasi-static cutoff)");
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

BodyConfig readBodyConfig(YamlDocument doc) {
  static const JsonSchema schema(kBodySchema, "body.schema.json");
  schema.validate(doc);
  schema.applyDefaults(doc);  // the keys below with a schema default are always present
  BodyConfig c;
  const YAML::Node& root = doc.root;
  c.name = getString(doc, root["name"], "name");
  c.model = getKind<ModelKind>(doc, root["model"], "model");
  const YAML::Node m = root["material"];
  c.material.youngs_modulus = getDouble(doc, m["youngs_modulus"], "material.youngs_modulus");
  c.material.poisson_ratio = getDouble(doc, m["poisson_ratio"], "material.poisson_ratio");
  c.material.density = getDouble(doc, m["density"], "material.density");
  readGeometry(doc, root["geometry"], c.geometry);
  checkModel(doc, c);
  const int d = c.geometry.paramDim();
  const YAML::Node r = root["refinement"];
  c.refinement.elevate_degree =
      perDirection(doc, r ? r["elevate_degree"] : YAML::Node(), "refinement.elevate_degree", d);
  c.refinement.insert_knots =
      perDirection(doc, r ? r["insert_knots"] : YAML::Node(), "refinement.insert_knots", d);
  parseInsert(doc, r ? r["insert"] : YAML::Node(), d, c);
  readHierarchy(doc, root["hierarchy"], d, c);
  c.contacts = readContacts(doc, d);
  c.design = readDesign(doc, c);
  if (c.design) applyDesign(*c.design, c);
  readMarkers(doc, root["markers"], d, &c.markers);
  parseReduction(doc, root["reduction"], !c.contacts.empty(), c.markers, &c.reduction);
  c.visualisation = readVisualisation(doc, root["visualisation"], d);
  if (c.design) addDesignedDefaults(doc, c);
  c.source = std::move(doc);
  return c;
}

BodyConfig parseBodyConfig(YamlDocument doc, double memory_limit_bytes) {
  BodyConfig c = readBodyConfig(std::move(doc));
  checkBodyConfig(c, memory_limit_bytes);
  return c;
}

BodyConfig loadBodyConfig(const std::string& path, double memory_limit_bytes,
                          const std::vector<std::string>& sets) {
  YamlDocument doc = loadYamlFile(path);
  applyOverrides(doc, sets);
  return parseBodyConfig(std::move(doc), memory_limit_bytes);
}

const char* toString(GeometryKind geometry) { return spell(kGeometryKinds, geometry); }

YAML::Node contactNode(const YamlDocument& doc, const ContactConfig& contact) {
  const YAML::Node& root = doc.root;  // const: looking up creates no entries
  if (contact.designed) return root["design"];
  return contact.item < 0 ? root["contact"] : root["contacts"][contact.item];
}

NurbsPatch refinedPatch(const BodyConfig& config) {
  return ffriga::refinedPatch(exactPatch(config.geometry), config.refinement);
}

HierarchicalSpace bodySpace(const BodyConfig& config) {
  return ffriga::bodySpace(refinedPatch(config), config.hierarchy, config.global_reference);
}

// Whether a level's entry of hierarchy.boxes is a list of boxes (its first item's first item
// is an interval) rather than one box (a list of intervals).
bool listOfBoxes(const YAML::Node& level) {
  return level.IsSequence() && level.size() > 0 && level[0].IsSequence() && level[0].size() > 0 &&
         level[0][0].IsSequence();
}

YAML::Node hierarchyBoxNode(const YAML::Node& level, int member) {
  return listOfBoxes(level) ? level[member] : level;
}

std::string hierarchyBoxKey(const YAML::Node& level, int b, int member) {
  Str key;
  key << "hierarchy.boxes[" << b << "]";
  if (listOfBoxes(level)) key << "[" << member << "]";
  return key;
}

}  // namespace ffriga
