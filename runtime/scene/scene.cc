#include "runtime/scene/scene.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "common/input/json_schema.h"
#include "common/input/schemas.h"
#include "common/input/yaml_overrides.h"
#include "runtime/bodies/axisymmetric_body.h"
#include "runtime/bodies/quasi_static_rule.h"
#include "runtime/bodies/floating_body.h"
#include "runtime/bodies/rigid_body.h"
#include "runtime/bodies/rotation.h"
#include "runtime/scene/scene_multibody.h"

namespace ffriga {

namespace fs = std::filesystem;

namespace {

Eigen::VectorXd vectorOr(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                         const Eigen::VectorXd& fallback) {
  if (!node) return fallback;
  Eigen::VectorXd v(node.size());
  for (std::size_t i = 0; i < node.size(); ++i)
    v(i) = getDouble(doc, node[i], Str() << key << "[" << i << "]");
  return v;
}

double doubleOr(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                double fallback) {
  return node ? getDouble(doc, node, key) : fallback;
}

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

Scene loadScene(const std::string& path, const std::vector<std::string>& sid_paths,
                const SidLoader& load_sid, const std::vector<std::string>& sets) {
  YamlDocument doc = loadYamlFile(path);
  applyOverrides(doc, sets);
  return buildScene(std::move(doc), sid_paths, load_sid);
}

namespace {

// 2. Names: unique body names ("ground" reserved), contact pairs of known, distinct bodies.
std::map<std::string, int> checkNames(const YamlDocument& doc) {
  const YAML::Node bodies = doc.root["bodies"];
  std::map<std::string, int> index;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const std::string key = Str() << "bodies[" << b << "].name";
    const std::string name = getString(doc, bodies[b]["name"], key);
    if (name == "ground")
      throw inputError(doc, bodies[b]["name"], key, "'ground' is reserved for the inertial frame");
    if (!index.emplace(name, static_cast<int>(b)).second)
      throw inputError(doc, bodies[b]["name"], key,
                       Str() << "body name '" << name << "' is used twice");
    const bool sid = bool(bodies[b]["sid"]), rigid = bool(bodies[b]["rigid"]);
    if (sid == rigid)
      throw inputError(doc, bodies[b], Str() << "bodies[" << b << "]",
                       "expected either 'sid' (a body from igaprep) or 'rigid' (mass and inertia)");
    for (const char* key : {"frozen", "q", "qdot", "damping", "surface", "quasi_static"})
      if (rigid && bodies[b][key])
        throw inputError(doc, bodies[b][key], Str() << "bodies[" << b << "]." << key,
                         Str() << "'" << key << "' is for SID bodies, not rigid ones");
  }
  const YAML::Node contacts = doc.root["contacts"];
  for (std::size_t c = 0; contacts && c < contacts.size(); ++c) {
    const YAML::Node pair = contacts[c]["bodies"];
    for (int i = 0; i < 2; ++i) {
      const std::string key = Str() << "contacts[" << c << "].bodies[" << i << "]";
      const std::string name = getString(doc, pair[i], key);
      if (!index.count(name)) {
        std::string known;
        for (const auto& kv : index) known += (known.empty() ? "" : ", ") + kv.first;
        throw inputError(doc, pair[i], key,
                         Str() << "expected the name of a body of this scene (" << known
                               << "), found '" << name << "'");
      }
    }
    if (getString(doc, pair[0], "") == getString(doc, pair[1], ""))
      throw inputError(doc, pair, Str() << "contacts[" << c << "].bodies",
                       "expected two different bodies");
  }
  return index;
}

Eigen::Matrix3d matrix3(const YamlDocument& doc, const YAML::Node& node, const std::string& key) {
  Eigen::Matrix3d M;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      M(i, j) = getDouble(doc, node[i][j], Str() << key << "[" << i << "][" << j << "]");
  return M;
}

// 3-4. The body data: SID files (all resolved before any is read, so a missing file is
// reported at once), frozen SIDs, rigid bodies defined in the scene.
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
      p.centre_of_mass =
          vectorOr(doc, R["centre_of_mass"], k + ".rigid.centre_of_mass", Eigen::Vector3d::Zero());
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
      const bool frozen = B["frozen"] && B["frozen"].as<bool>();
      const std::string shareKey = (frozen ? "frozen:" : "elastic:") + files[b];
      if (auto it = loaded.find(shareKey); it != loaded.end()) {
        sids.push_back(it->second);
        continue;
      }
      auto sid = std::make_shared<FlexibleBodySid>(load_sid(files[b], content));
      if (frozen) {
        if (sid->model == "axisymmetric")
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
  // Joints impose acceleration-level constraints that assume every coordinate has inertia
  // (multibody_system.h): quasi-static coordinates are not combined with them (yet).
  const YAML::Node joints = doc.root["joints"];
  if (joints && joints.size() > 0) {
    if (Q && rule.kind != QuasiStaticRule::Kind::kNone)
      throw inputError(doc, Q, k + ".quasi_static",
                       "quasi-static coordinates are not available in scenes with joints: give "
                       "'quasi_static: false' and damp the high modes (body file 'damping')");
    return;
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

// Bodies must not start inside each other: a penetration beyond the pair's tolerance
// (ContactPair::penetrationTolerance) is bad input, with the depth in the message. Two
// spheres placed 5 mm into each other once ran to `completed` with zero force: their
// contact surfaces' boxes were apart, so no point was ever evaluated.
void checkInitialPenetration(const YamlDocument& doc, const MultibodySystem& sys,
                             const Eigen::VectorXd& y0) {
  for (int c = 0; c < sys.numContacts(); ++c) {
    const ContactPair& pair = sys.contact(c);
    const Penetration p = sys.deepestPenetration(y0.data(), c);
    const double tol = pair.penetrationTolerance();
    if (p.depth <= tol) continue;
    const std::string k = Str() << "contacts[" << c << "]";
    throw inputError(doc, doc.root["contacts"][c], k,
                     Str() << "bodies '" << sys.body(pair.bodyA()).name() << "' and '"
                           << sys.body(pair.bodyB()).name() << "' start " << p.depth
                           << " m into each other (a point of '"
                           << sys.body(p.contact_body).name() << "' at (" << p.point.transpose()
                           << ") m); at most " << tol
                           << " m is accepted (key penetration_tolerance): move them apart");
  }
}

// The number of output rows end_time / output_interval must be a count the run can reach:
// at most kMaxOutputRows (an int), and consecutive output times distinct in double precision.
// (An interval of 1e-300 s once made the row count overflow: the run stopped after one step
// and reported `completed`.)
void checkOutputRows(const YamlDocument& doc) {
  constexpr double kMaxOutputRows = 2147483647.0;
  const YAML::Node I = doc.root["integrator"];
  const double end = getDouble(doc, I["end_time"], "integrator.end_time");
  const double dt = getDouble(doc, I["output_interval"], "integrator.output_interval");
  const double rows = std::ceil(end / dt);
  if (!(rows <= kMaxOutputRows) || !(dt >= 1e-12 * end)) {
    throw inputError(doc, I["output_interval"], "integrator.output_interval",
                     Str() << dt << " s over end_time " << end << " s gives " << rows
                           << " output rows; at most " << static_cast<long>(kMaxOutputRows)
                           << " rows, with an interval of at least 1e-12 of end_time");
  }
}

// outputs.visualisation: frames of every SID body; each SID must carry a visualisation mesh
// (igaprep's body file key visualisation.subdivisions > 0). Scene-defined rigid bodies have
// no shape and are not drawn.
void parseVisualisationOutput(const YamlDocument& doc, const YAML::Node& V, Scene& scene) {
  if (!V) return;
  VisualisationSettings& v = scene.visualisation;
  v.enabled = true;
  v.interval = getDouble(doc, V["interval"], "outputs.visualisation.interval");
  v.magnification = doubleOr(doc, V["magnification"], "outputs.visualisation.magnification", 1.0);
  if (V["revolve"]) {
    v.revolve = getInt(doc, V["revolve"], "outputs.visualisation.revolve");
    if (v.revolve == 1 || v.revolve == 2)
      throw inputError(doc, V["revolve"], "outputs.visualisation.revolve",
                       "expected 0 (the meridian section) or at least 3 segments");
  }
  const MultibodySystem& sys = *scene.system;
  for (int b = 0; b < sys.numBodies(); ++b) {
    if (scene.sid_files[b].empty() || !sys.body(b).sid().mesh.empty()) continue;
    throw inputError(doc, V, "outputs.visualisation",
                     Str() << "body '" << sys.body(b).name() << "': its SID file "
                           << scene.sid_files[b] << " has no visualisation mesh (rebuild it with "
                           << "igaprep and visualisation.subdivisions >= 1 in the body file)");
  }
}

}  // namespace

Scene buildScene(YamlDocument document, const std::vector<std::string>& sid_paths,
                 const SidLoader& load_sid) {
  Scene scene;
  scene.doc = std::move(document);
  const YamlDocument& doc = scene.doc;
  static const JsonSchema schema(kSceneSchema, "scene.schema.json");
  schema.validate(doc);
  const YAML::Node root = doc.root;
  scene.name =
      root["name"] ? getString(doc, root["name"], "name") : fs::path(doc.path).stem().string();
  const std::map<std::string, int> index = checkNames(doc);
  checkOutputRows(doc);
  const YAML::Node bodies = root["bodies"];
  const std::vector<std::shared_ptr<FlexibleBodySid>> sids =
      loadBodyData(doc, sid_paths, load_sid, scene.sid_files);

  // 5. Bodies and their initial state.
  const Eigen::Vector3d gravity =
      vectorOr(doc, root["gravity"], "gravity", Eigen::Vector3d::Zero());
  const bool axisymmetric = sids[0]->model == "axisymmetric";
  scene.system = std::make_unique<MultibodySystem>();
  MultibodySystem& sys = *scene.system;
  sys.setGravity(gravity);
  if (axisymmetric && (gravity(0) != 0.0 || gravity(2) != 0.0))
    throw inputError(doc, root["gravity"], "gravity",
                     "an axisymmetric scene allows gravity along its axis (y) only");
  std::vector<InitialPose> init;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const YAML::Node B = bodies[b];
    const std::string k = Str() << "bodies[" << b << "]";
    const std::string name = getString(doc, B["name"], k + ".name");
    const FlexibleBodySid& sid = *sids[b];
    if ((sid.model == "axisymmetric") != axisymmetric) {
      const YAML::Node at = B["sid"] ? B["sid"] : B["rigid"];
      throw inputError(doc, at, k + (B["sid"] ? ".sid" : ".rigid"),
                       Str() << "axisymmetric bodies cannot share a scene with other kinds; '"
                             << name << "' is '" << sid.model << "', the first body '"
                             << sids[0]->model << "'");
    }
    InitialPose in;
    in.r = vectorOr(doc, B["position"], k + ".position", Eigen::Vector3d::Zero());
    Eigen::Vector4d p =
        vectorOr(doc, B["orientation"], k + ".orientation", Eigen::Vector4d(1, 0, 0, 0));
    if (!(p.norm() > 0.0))
      throw inputError(doc, B["orientation"], k + ".orientation", "expected a non-zero quaternion");
    p.normalize();
    in.A = rotationMatrix(p.data());
    in.v = vectorOr(doc, B["velocity"], k + ".velocity", Eigen::Vector3d::Zero());
    in.w = vectorOr(doc, B["angular_velocity"], k + ".angular_velocity", Eigen::Vector3d::Zero());
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
    std::unique_ptr<BodyModel> model;
    if (axisymmetric) {
      // The axis must stay the inertial y axis: A e_y = +-e_y, no lateral offset or motion.
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
      model = std::make_unique<AxisymmetricBody>(name, sids[b], sign > 0 ? 1.0 : -1.0);
    } else {
      model = std::make_unique<FloatingBody3d>(name, sids[b]);
    }
    // Damping overrides.
    if (const YAML::Node d = B["damping"]) {
      if (d["modal_damping_ratio"] && d["scale"])
        throw inputError(doc, d, k + ".damping",
                         "give either modal_damping_ratio or scale, not both");
      if (d["modal_damping_ratio"]) {
        const double zeta =
            getDouble(doc, d["modal_damping_ratio"], k + ".damping.modal_damping_ratio");
        const Eigen::VectorXd omega = sid.Ke.diagonal().cwiseMax(0.0).cwiseSqrt();
        model->setDamping(Eigen::MatrixXd((2.0 * zeta * omega).asDiagonal()));
      } else if (d["scale"]) {
        model->setDamping(getDouble(doc, d["scale"], k + ".damping.scale") * sid.De);
      }
    }
    applyQuasiStaticRule(doc, B, k, *model, in.qd);
    for (std::string& w : modeBandWarnings(model->name(), model->stiffnessDiagonal(),
                                           model->dampingDiagonal(), model->quasiStatic()))
      scene.warnings.push_back(std::move(w));
    sys.addBody(std::move(model));
    init.push_back(in);
  }

  // Contact pairs.
  const YAML::Node contacts = root["contacts"];
  for (std::size_t c = 0; contacts && c < contacts.size(); ++c) {
    const YAML::Node C = contacts[c];
    const std::string k = Str() << "contacts[" << c << "]";
    const int ia = index.at(getString(doc, C["bodies"][0], "")),
              ib = index.at(getString(doc, C["bodies"][1], ""));
    int surf[2] = {0, 0};
    for (int i = 0; i < 2; ++i) {
      const int bi = i == 0 ? ia : ib;
      const FlexibleBodySid& sid = *sids[bi];
      const YAML::Node sname = bodies[bi]["surface"];
      if (sid.surfaces.empty())
        throw inputError(
            doc, C["bodies"][i], k + ".bodies[" + std::to_string(i) + "]",
            Str() << "body '" << sys.body(bi).name() << "' has no contact surface in its SID");
      if (sname) {
        const std::string want = getString(doc, sname, "surface");
        surf[i] = -1;
        for (std::size_t s = 0; s < sid.surfaces.size(); ++s)
          if (sid.surfaces[s].name == want) surf[i] = static_cast<int>(s);
        if (surf[i] < 0)
          throw inputError(doc, sname, Str() << "bodies[" << bi << "].surface",
                           Str() << "the SID has no contact surface named '" << want << "'");
      }
    }
    ContactOptions o;
    o.penalty = getDouble(doc, C["penalty_factor"], k + ".penalty_factor");
    if (!(o.penalty > 0.0))  // also checked by the schema; kept for direct callers
      throw inputError(doc, C["penalty_factor"], k + ".penalty_factor",
                       Str() << "expected a number > 0 N/m^3, found " << o.penalty);
    if (C["both_roles"]) o.both_roles = C["both_roles"].as<bool>();
    o.search_margin = doubleOr(doc, C["search_margin"], k + ".search_margin", -1.0);
    o.penetration_tolerance =
        doubleOr(doc, C["penetration_tolerance"], k + ".penetration_tolerance", -1.0);
    const std::string name = C["name"] ? getString(doc, C["name"], k + ".name")
                                       : sys.body(ia).name() + "-" + sys.body(ib).name();
    sys.addContact(std::make_unique<ContactPair>(name, ia, sys.body(ia), surf[0], ib, sys.body(ib),
                                                 surf[1], o));
  }

  // Initial state and tolerances.
  const YAML::Node I = root["integrator"];
  SimulationSettings& s = scene.settings;
  s.end_time = getDouble(doc, I["end_time"], "integrator.end_time");
  s.output_interval = getDouble(doc, I["output_interval"], "integrator.output_interval");
  s.integrator.rtol = doubleOr(doc, I["rtol"], "integrator.rtol", 1e-6);
  const double aPos = doubleOr(doc, I["atol_position"], "integrator.atol_position", 1e-12);
  const double aVel = doubleOr(doc, I["atol_velocity"], "integrator.atol_velocity", 1e-8);
  const double aRot = doubleOr(doc, I["atol_rotation"], "integrator.atol_rotation", 1e-10);
  const double aAng =
      doubleOr(doc, I["atol_angular_velocity"], "integrator.atol_angular_velocity", 1e-6);
  s.integrator.max_step = doubleOr(doc, I["max_step"], "integrator.max_step", 0.0);
  s.integrator.initial_step = doubleOr(doc, I["initial_step"], "integrator.initial_step", 0.0);
  s.integrator.max_order = I["max_order"] ? getInt(doc, I["max_order"], "integrator.max_order")
                                          : IntegratorOptions().max_order;
  // YAML spelling of LinearSolverKind (the schema restricts the values to these).
  static const std::pair<const char*, LinearSolverKind> kSolvers[] = {
      {"structured", LinearSolverKind::kAuto}, {"dense", LinearSolverKind::kEigenDense}};
  if (I["linear_solver"]) {
    const std::string v = getString(doc, I["linear_solver"], "integrator.linear_solver");
    for (const auto& [name, kind] : kSolvers)
      if (v == name) s.integrator.linear_solver = kind;
  }
  // 6. Joints, force elements, sensors; initial joint angles.
  const BodyMarkers markers = collectMarkers(doc, sys);
  const std::vector<double> angles = addJoints(doc, index, markers, init, sys);
  addForceElements(doc, index, markers, init, sys);
  addSensors(doc, index, markers, sys);
  applyInitialAngles(doc, sys, angles, init);

  scene.y0.resize(sys.size());
  s.integrator.atol.resize(sys.size());
  for (int b = 0; b < sys.numBodies(); ++b) {
    const BodyModel& body = sys.body(b);
    const InitialPose& in = init[b];
    scene.initial_position.push_back(in.r);
    scene.initial_velocity.push_back(in.v);
    double* sp = scene.y0.data() + sys.positionOffset(b);
    double* sv = scene.y0.data() + sys.velocityOffset(b);
    double* ap = s.integrator.atol.data() + sys.positionOffset(b);
    double* av = s.integrator.atol.data() + sys.velocityOffset(b);
    const int nr = body.numRigidPositions(), nv = body.numRigidVelocities();
    const double sq = std::sqrt(body.sid().mass);
    if (axisymmetric) {
      sp[0] = in.r(1);
      sv[0] = in.v(1);  // the state of an axisymmetric body is the inertial V_y
      ap[0] = aPos;
      av[0] = aVel;
    } else {
      // State velocities in body components (Eq. 1).
      const Eigen::Vector3d vb = in.A.transpose() * in.v, wb = in.A.transpose() * in.w;
      const Eigen::Quaterniond quat(in.A);
      const double p[4] = {quat.w(), quat.x(), quat.y(), quat.z()};
      for (int i = 0; i < 3; ++i) {
        sp[i] = in.r(i), sv[i] = vb(i), sv[3 + i] = wb(i);
        ap[i] = aPos, av[i] = aVel, av[3 + i] = aAng;
      }
      for (int i = 0; i < 4; ++i) sp[3 + i] = p[i], ap[3 + i] = aRot;
    }
    // Elastic coordinates: atol * sqrt(m) in q units (kg^(1/2) m), except for quasi-static
    // coordinates, whose tolerances are displacements of the body's points (m): coordinate
    // j gets atol / max |Phi_j| (Phi_j in m per unit q_j). A quasi-static coordinate moves
    // the contact surface directly, with no inertia to filter its error, and a local
    // interface mode moves it by 1e4-1e6 m per unit q (sphere2d_h3; a global mode by ~10):
    // with the q-unit tolerance the local modes could move the surface by nanometres, a
    // tenth of the penetration, and jittered at that level from step to step. The dynamic
    // coordinates keep the q-unit tolerance: the displacement tolerance gives them the
    // same force peak (-0.05 % from Hertz on sphere2d_h3, damped) at 7 times the steps.
    const QuasiStaticModes& qs = body.quasiStatic();
    for (int j = 0; j < body.nq(); ++j) {
      sp[nr + j] = in.q(j), sv[nv + j] = in.qd(j);
      ap[nr + j] = aPos * sq, av[nv + j] = aVel * sq;
    }
    for (int s = 0; s < qs.size(); ++s) {
      const double phi = qs.reach(s);
      if (phi > 0.0) ap[nr + qs.index[s]] = aPos / phi, av[nv + qs.index[s]] = aVel / phi;
    }
  }
  checkInitialConstraints(doc, sys, scene.y0);
  checkInitialPenetration(doc, sys, scene.y0);
  if (root["outputs"]) parseVisualisationOutput(doc, root["outputs"]["visualisation"], scene);
  if (root["static_preload"] && root["static_preload"].as<bool>()) {
    scene.static_preload = true;
    scene.preload = staticPreload(sys, scene.y0);
  }
  if (const YAML::Node O = root["outputs"]) {
    if (O["flush_rows"]) scene.flush_rows = getInt(doc, O["flush_rows"], "outputs.flush_rows");
    scene.flush_interval = doubleOr(doc, O["flush_interval"], "outputs.flush_interval", 2.0);
    s.progress_interval = doubleOr(doc, O["progress_interval"], "outputs.progress_interval", 1.0);
    s.contact_output_interval =
        doubleOr(doc, O["contact_output_interval"], "outputs.contact_output_interval", 0.0);
  }
  return scene;
}

}  // namespace ffriga
