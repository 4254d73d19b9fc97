#include "runtime/scene/scene_bodies.h"

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <utility>

#include "runtime/bodies/axisymmetric_body.h"
#include "runtime/bodies/floating_body.h"
#include "runtime/bodies/quasi_static_rule.h"
#include "runtime/bodies/rigid_body.h"
#include "runtime/bodies/rotation.h"
#include "runtime/scene/scene_values.h"

namespace ffriga {

namespace fs = std::filesystem;

namespace {

// A SID file named in the scene: a relative name resolves against the scene file's folder,
// then against each --sid-path folder in turn; the first existing file is used.
std::string resolveSid(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                       const std::vector<std::string>& sid_paths) {
  const std::string name = getString(doc, node, key);
  std::vector<fs::path> tried;
  const fs::path p(name);
  if (p.is_absolute()) {
    tried.push_back(p);
  } else {
    tried.push_back(fs::path(doc.path).parent_path() / p);
    for (const std::string& dir : sid_paths) tried.push_back(fs::path(dir) / p);
  }
  for (const fs::path& candidate : tried) {
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate.string();
  }
  std::string list;
  for (const fs::path& candidate : tried) list += (list.empty() ? "" : ", ") + candidate.string();
  throw inputError(doc, node, key,
                   Str() << "SID file '" << name << "' not found (tried " << list
                         << "; add a folder with --sid-path)");
}

}  // namespace

namespace {

// The obstacles' names: unique among bodies and obstacles, not 'ground'.
std::set<std::string> checkObstacleNames(const YamlDocument& doc,
                                         const std::map<std::string, int>& bodies) {
  std::set<std::string> names;
  const YAML::Node obstacles = doc.root["obstacles"];
  for (std::size_t o = 0; obstacles && o < obstacles.size(); ++o) {
    const std::string key = Str() << "obstacles[" << o << "].name";
    const std::string name = getString(doc, obstacles[o]["name"], key);
    if (name == "ground")
      throw inputError(doc, obstacles[o]["name"], key,
                       "'ground' is reserved for the inertial frame (name the plane 'floor')");
    if (name.find('.') != std::string::npos)
      throw inputError(doc, obstacles[o]["name"], key,
                       "an obstacle name cannot contain '.' (a contact pair's BODY.REGION)");
    if (bodies.count(name) || !names.insert(name).second)
      throw inputError(doc, obstacles[o]["name"], key,
                       Str() << "name '" << name << "' is used twice (bodies and obstacles "
                             << "share their names)");
  }
  return names;
}

}  // namespace

std::string pairBodyName(const std::string& entry) { return entry.substr(0, entry.find('.')); }

std::string pairRegionName(const std::string& entry) {
  const std::size_t dot = entry.find('.');
  return dot == std::string::npos ? std::string() : entry.substr(dot + 1);
}

std::map<std::string, int> checkBodyNames(const YamlDocument& doc) {
  const YAML::Node bodies = doc.root["bodies"];
  std::map<std::string, int> index;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::string key = Str() << "bodies[" << b << "].name";
    const std::string name = getString(doc, bodies[b]["name"], key);
    if (name == "ground")
      throw inputError(doc, bodies[b]["name"], key, "'ground' is reserved for the inertial frame");
    if (name.find('.') != std::string::npos)
      throw inputError(doc, bodies[b]["name"], key,
                       "a body name cannot contain '.' (BODY.REGION and BODY.MARKER name its parts)");
    if (!index.emplace(name, static_cast<int>(b)).second)
      throw inputError(doc, bodies[b]["name"], key,
                       Str() << "body name '" << name << "' is used twice");
    const bool sid = bool(bodies[b]["sid"]), rigid = bool(bodies[b]["rigid"]);
    if (sid == rigid)
      throw inputError(doc, bodies[b], Str() << "bodies[" << b << "]",
                       "expected either 'sid' (a body from igaprep) or 'rigid' (mass and inertia)");
    for (const char* key : {"frozen", "q", "qdot", "damping", "surface", "quasi_static"})
      if (rigid && isGiven(doc, bodies[b][key]))
        throw inputError(doc, bodies[b][key], Str() << "bodies[" << b << "]." << key,
                         Str() << "'" << key << "' is for SID bodies, not rigid ones");
  }
  const std::set<std::string> obstacles = checkObstacleNames(doc, index);
  const YAML::Node contacts = doc.root["contacts"];
  for (std::size_t c = 0; contacts && c < contacts.size(); ++c) {
    const YAML::Node pair = contacts[c]["bodies"];
    int bodies = 0;
    for (int i = 0; i < 2; ++i) {
      const std::string key = Str() << "contacts[" << c << "].bodies[" << i << "]";
      const std::string name = pairBodyName(getString(doc, pair[i], key));
      bodies += index.count(name) ? 1 : 0;
      if (!index.count(name) && !obstacles.count(name)) {
        std::string known;
        for (const auto& kv : index) known += (known.empty() ? "" : ", ") + kv.first;
        for (const auto& o : obstacles) known += ", obstacle " + o;
        throw inputError(doc, pair[i], key,
                         Str() << "expected the name of a body or obstacle of this scene ("
                               << known << "), found '" << name << "'");
      }
    }
    if (pairBodyName(getString(doc, pair[0], "")) == pairBodyName(getString(doc, pair[1], "")))
      throw inputError(doc, pair, Str() << "contacts[" << c << "].bodies",
                       "expected two different bodies");
    if (bodies == 0)
      throw inputError(doc, pair, Str() << "contacts[" << c << "].bodies",
                       "expected at least one body: two obstacles are fixed and never meet");
  }
  return index;
}

std::vector<std::shared_ptr<FlexibleBodySid>> loadBodyData(
    const YamlDocument& doc, const std::vector<std::string>& sid_paths, const SidLoader& load_sid,
    std::vector<std::string>& files) {
  const YAML::Node bodies = doc.root["bodies"];
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::string key = Str() << "bodies[" << b << "].sid";
    files.push_back(bodies[b]["sid"] ? resolveSid(doc, bodies[b]["sid"], key, sid_paths) : "");
  }
  std::vector<std::shared_ptr<FlexibleBodySid>> sids;
  std::map<std::string, std::shared_ptr<FlexibleBodySid>> loaded;
  // Only visualisation frames need the mesh's sampled modes.
  const YAML::Node outputs = doc.root["outputs"];
  const SidContent content =
      outputs && outputs["visualisation"] ? SidContent::kAll : SidContent::kWithoutMesh;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const YAML::Node B = bodies[b];
    const std::string k = Str() << "bodies[" << b << "]";
    if (B["rigid"]) {
      const YAML::Node R = B["rigid"];
      RigidBodyProperties p;
      p.mass = getDouble(doc, R["mass"], k + ".rigid.mass");
      p.centre_of_mass = vector3(doc, R["centre_of_mass"], k + ".rigid.centre_of_mass");
      p.inertia = matrix3(doc, R["inertia"], k + ".rigid.inertia");
      try {
        sids.push_back(std::make_shared<FlexibleBodySid>(
            rigidBodySid(getString(doc, B["name"], k + ".name"), p)));
      } catch (const InputError& e) {
        throw inputError(doc, R["inertia"], k + ".rigid.inertia", e.what());
      }
      continue;
    }
    const std::string key = k + ".sid";
    try {
      // Bodies of one SID file share its data (read once; the runtime never changes it).
      const bool frozen = getBool(doc, B["frozen"], k + ".frozen");
      const std::string shareKey = (frozen ? "frozen:" : "elastic:") + files[b];
      if (auto it = loaded.find(shareKey); it != loaded.end()) {
        sids.push_back(it->second);
        continue;
      }
      auto sid = std::make_shared<FlexibleBodySid>(load_sid(files[b], content));
      if (frozen) {
        if (sid->model == ModelKind::kAxisymmetric)
          throw InputError("an axisymmetric body cannot be frozen (it would lose its axis)");
        sid = std::make_shared<FlexibleBodySid>(frozenSid(*sid));
      }
      sids.push_back(sid);
      loaded[shareKey] = sid;
    } catch (const InputError& e) {
      throw inputError(doc, B["sid"], key, e.what());
    }
  }
  return sids;
}

namespace {

// The body's quasi-static coordinates (runtime/bodies/quasi_static_rule.h): the scene's
// `quasi_static` key, else the rule's default. Their initial velocities must be zero.
void applyQuasiStaticRule(const YamlDocument& doc, const YAML::Node& B, const std::string& k,
                          BodyModel& model, const Eigen::VectorXd& qdot) {
  if (model.nq() == 0) return;
  QuasiStaticRule rule;
  const YAML::Node Q = B["quasi_static"];
  if (Q && Q.IsScalar()) {
    rule.kind = QuasiStaticRule::Kind::kNone;  // `false` (the schema admits no other scalar)
  } else if (Q) {
    if (Q["above_hz"] && Q["above_first_elastic"])
      throw inputError(doc, Q, k + ".quasi_static", "give either above_hz or above_first_elastic, not both");
    if (Q["above_hz"]) {
      rule.kind = QuasiStaticRule::Kind::kAboveHz;
      rule.value = getDouble(doc, Q["above_hz"], k + ".quasi_static.above_hz");
    } else if (Q["above_first_elastic"]) {
      rule.kind = QuasiStaticRule::Kind::kAboveFirstElastic;
      rule.value = getDouble(doc, Q["above_first_elastic"], k + ".quasi_static.above_first_elastic");
    }
  }
  const double cutoff = quasiStaticCutoffHz(model.stiffnessDiagonal(), rule);
  if (!std::isfinite(cutoff)) return;
  try {
    model.setQuasiStatic(cutoff);
  } catch (const InputError& e) {
    throw inputError(doc, Q ? Q : B, k + ".quasi_static", e.what());
  }
  for (int i : model.quasiStatic().index)
    if (qdot(i) != 0.0)
      throw inputError(doc, B["qdot"], k + ".qdot",
                       Str() << "qdot[" << i << "] = " << qdot(i) << " belongs to a quasi-static "
                             << "coordinate (no velocity of its own): expected 0");
}

// The scene's damping override (bodies[b].damping): a modal damping ratio for every mode or
// a factor on the SID's De.
void applyDamping(const YamlDocument& doc, const YAML::Node& d, const std::string& k,
                  const FlexibleBodySid& sid, BodyModel& model) {
  if (!d) return;
  if (d["modal_damping_ratio"] && d["scale"])
    throw inputError(doc, d, k + ".damping", "give either modal_damping_ratio or scale, not both");
  if (d["modal_damping_ratio"]) {
    const double zeta = getDouble(doc, d["modal_damping_ratio"], k + ".damping.modal_damping_ratio");
    const Eigen::VectorXd omega = sid.Ke.diagonal().cwiseMax(0.0).cwiseSqrt();
    model.setDamping(Eigen::MatrixXd((2.0 * zeta * omega).asDiagonal()));
  } else if (d["scale"]) {
    model.setDamping(getDouble(doc, d["scale"], k + ".damping.scale") * sid.De);
  }
}

// An axisymmetric body's axis must stay the inertial y axis: A e_y = +-e_y, no lateral
// offset or motion. Returns the axis' sign.
double axisymmetricAxisSign(const YamlDocument& doc, const YAML::Node& B, const std::string& k,
                            const InitialPose& in) {
  const double sign = in.A(1, 1);
  if (std::abs(std::abs(sign) - 1.0) > 1e-12)
    throw inputError(doc, B["orientation"], k + ".orientation",
                     "an axisymmetric body's axis must lie along the inertial y axis "
                     "([1,0,0,0] or [0,1,0,0])");
  if (in.r(0) != 0.0 || in.r(2) != 0.0)
    throw inputError(doc, B["position"], k + ".position",
                     "an axisymmetric body must sit on the y axis: expected [0, Y, 0]");
  if (in.v(0) != 0.0 || in.v(2) != 0.0)
    throw inputError(doc, B["velocity"], k + ".velocity",
                     "an axisymmetric body moves along y only: expected [0, V, 0]");
  if (in.w.norm() != 0.0)
    throw inputError(doc, B["angular_velocity"], k + ".angular_velocity",
                     "an axisymmetric body does not rotate: expected [0, 0, 0]");
  return sign > 0 ? 1.0 : -1.0;
}

}  // namespace

InitialPose readInitialPose(const YamlDocument& doc, int b, const FlexibleBodySid& sid) {
  const YAML::Node B = doc.root["bodies"][b];
  const std::string k = Str() << "bodies[" << b << "]";
  InitialPose in;
  in.r = vector3(doc, B["position"], k + ".position");
  Eigen::Vector4d p = numbers(doc, B["orientation"], k + ".orientation");
  if (!(p.norm() > 0.0))
    throw inputError(doc, B["orientation"], k + ".orientation", "expected a non-zero quaternion");
  p.normalize();
  in.A = rotationMatrix(p.data());
  in.v = vector3(doc, B["velocity"], k + ".velocity");
  in.w = vector3(doc, B["angular_velocity"], k + ".angular_velocity");
  const int nq = sid.nq();
  in.q = vectorOr(doc, B["q"], k + ".q", Eigen::VectorXd::Zero(nq));
  in.qd = vectorOr(doc, B["qdot"], k + ".qdot", Eigen::VectorXd::Zero(nq));
  if (in.q.size() != nq)
    throw inputError(
        doc, B["q"], k + ".q",
        Str() << "expected " << nq << " values (nq of the SID), found " << in.q.size());
  if (in.qd.size() != nq)
    throw inputError(
        doc, B["qdot"], k + ".qdot",
        Str() << "expected " << nq << " values (nq of the SID), found " << in.qd.size());
  return in;
}

std::unique_ptr<BodyModel> makeBody(const YamlDocument& doc, int b,
                                    std::shared_ptr<const FlexibleBodySid> sid, bool axisymmetric,
                                    const InitialPose& pose) {
  const YAML::Node B = doc.root["bodies"][b];
  const std::string k = Str() << "bodies[" << b << "]";
  const std::string name = getString(doc, B["name"], k + ".name");
  std::unique_ptr<BodyModel> model;
  if (axisymmetric)
    model = std::make_unique<AxisymmetricBody>(name, sid, axisymmetricAxisSign(doc, B, k, pose));
  else
    model = std::make_unique<FloatingBody3d>(name, sid);
  applyDamping(doc, B["damping"], k, *sid, *model);
  applyQuasiStaticRule(doc, B, k, *model, pose.qd);
  return model;
}

}  // namespace ffriga
