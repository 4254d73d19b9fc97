#include "runtime/scene/scene.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "common/input/json_schema.h"
#include "common/input/schemas.h"
#include "common/input/yaml_overrides.h"
#include "common/mechanics/hertz.h"
#include "common/mechanics/hertz_ellipse.h"
#include "runtime/bodies/quasi_static_rule.h"
#include "runtime/contact/contact_pair.h"
#include "runtime/contact/obstacle_contact.h"
#include "runtime/scene/initial_state.h"
#include "runtime/scene/scene_multibody.h"
#include "runtime/scene/scene_obstacles.h"
#include "runtime/scene/scene_values.h"

namespace ffriga {

namespace fs = std::filesystem;

namespace {

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

// The scene builder's phases, in the order of the checks of scene.h.
class SceneBuilder {
 public:
  SceneBuilder(YamlDocument document, const std::vector<std::string>& sid_paths,
               const SidLoader& load_sid)
      : sid_paths_(sid_paths), load_sid_(load_sid) {
    scene_.doc = std::move(document);
  }
  Scene build() {
    validate();
    loadBodies();
    addBodies();
    addContacts();
    readIntegrator();
    addMultibody();
    assembleState();
    readVisualisation();
    preload();
    readOutputs();
    return std::move(scene_);
  }

 private:
  const YamlDocument& doc() const { return scene_.doc; }
  void validate();
  void loadBodies();
  void addBodies();
  void addContacts();
  int contactSurface(std::size_t c, int i, int body) const;
  ContactOptions contactOptions(std::size_t c, int body_a, int body_b) const;
  void readFriction(const YAML::Node& C, const std::string& k, FrictionLaw& friction) const;
  double automaticPenalty(std::size_t c, int body_a, int body_b) const;
  void warnFacingAway();
  void readIntegrator();
  void addMultibody();
  void assembleState();
  void readVisualisation();
  void preload();
  void readOutputs();

  const std::vector<std::string>& sid_paths_;
  const SidLoader& load_sid_;
  Scene scene_;
  std::map<std::string, int> index_;  // body index by name
  std::vector<std::shared_ptr<FlexibleBodySid>> sids_;
  std::vector<InitialPose> poses_;
  bool axisymmetric_ = false;
  AbsoluteTolerances atol_;
};

// 1.-2. The schema, the names, the number of output rows.
void SceneBuilder::validate() {
  static const JsonSchema schema(kSceneSchema, "scene.schema.json");
  schema.validate(scene_.doc);
  schema.applyDefaults(scene_.doc);  // every default below is the schema's
  const YAML::Node root = doc().root;
  scene_.name =
      root["name"] ? getString(doc(), root["name"], "name") : fs::path(doc().path).stem().string();
  index_ = checkBodyNames(doc());
  checkOutputRows(doc());
}

// 3.-4. The SIDs and rigid bodies; gravity.
void SceneBuilder::loadBodies() {
  sids_ = loadBodyData(doc(), sid_paths_, load_sid_, scene_.sid_files);
  const YAML::Node root = doc().root;
  const Eigen::Vector3d gravity = vector3(doc(), root["gravity"], "gravity");
  axisymmetric_ = sids_[0]->model == ModelKind::kAxisymmetric;
  scene_.system = std::make_unique<MultibodySystem>();
  scene_.system->setGravity(gravity);
  if (axisymmetric_ && (gravity(0) != 0.0 || gravity(2) != 0.0))
    throw inputError(doc(), root["gravity"], "gravity",
                     "an axisymmetric scene allows gravity along its axis (y) only");
}

// 5. The bodies and their initial pose (all of one kind: axisymmetric or not).
void SceneBuilder::addBodies() {
  const YAML::Node bodies = doc().root["bodies"];
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const YAML::Node B = bodies[b];
    const std::string k = Str() << "bodies[" << b << "]";
    const std::string name = getString(doc(), B["name"], k + ".name");
    const FlexibleBodySid& sid = *sids_[b];
    if ((sid.model == ModelKind::kAxisymmetric) != axisymmetric_) {
      const YAML::Node at = B["sid"] ? B["sid"] : B["rigid"];
      throw inputError(doc(), at, k + (B["sid"] ? ".sid" : ".rigid"),
                       Str() << "axisymmetric bodies cannot share a scene with other kinds; '"
                             << name << "' is '" << toString(sid.model) << "', the first body '"
                             << toString(sids_[0]->model) << "'");
    }
    const InitialPose pose = readInitialPose(doc(), static_cast<int>(b), sid);
    std::unique_ptr<BodyModel> model =
        makeBody(doc(), static_cast<int>(b), sids_[b], axisymmetric_, pose);
    for (std::string& w : modeBandWarnings(model->name(), model->stiffnessDiagonal(),
                                           model->dampingDiagonal(), model->quasiStatic()))
      scene_.warnings.push_back(std::move(w));
    scene_.system->addBody(std::move(model));
    poses_.push_back(pose);
  }
}

// The index of the SID contact surface of pair c's body i: the region its entry names
// (BODY.REGION), else bodies[body].surface, else the SID's only one.
int SceneBuilder::contactSurface(std::size_t c, int i, int body) const {
  const YAML::Node entry = doc().root["contacts"][c]["bodies"][i];
  const std::string k = Str() << "contacts[" << c << "].bodies[" << i << "]";
  const FlexibleBodySid& sid = *sids_[body];
  const std::string& name = scene_.system->body(body).name();
  if (sid.surfaces.empty())
    throw inputError(doc(), entry, k, Str() << "body '" << name << "' has no contact surface in its SID");
  std::string regions;
  for (const ContactSurface& s : sid.surfaces) regions += (regions.empty() ? "" : ", ") + s.name;
  const YAML::Node sname = doc().root["bodies"][body]["surface"];
  std::string want = pairRegionName(getString(doc(), entry, k));
  if (want.empty() && !sname) {
    if (sid.surfaces.size() == 1) return 0;
    throw inputError(doc(), entry, k,
                     Str() << "body '" << name << "' has " << sid.surfaces.size()
                           << " contact regions (" << regions << "): name one, as " << name << "."
                           << sid.surfaces[0].name);
  }
  const bool fromEntry = !want.empty();
  if (!fromEntry) want = getString(doc(), sname, "surface");
  for (std::size_t s = 0; s < sid.surfaces.size(); ++s)
    if (sid.surfaces[s].name == want) return static_cast<int>(s);
  throw inputError(doc(), fromEntry ? entry : sname,
                   fromEntry ? k : std::string(Str() << "bodies[" << body << "].surface"),
                   Str() << "body '" << name << "' has no contact region '" << want
                         << "' (its regions: " << regions << ")");
}

// The contact pairs (Sect. 4): two bodies, or a body and an obstacle.
void SceneBuilder::addContacts() {
  const YAML::Node contacts = doc().root["contacts"];
  MultibodySystem& sys = *scene_.system;
  const std::map<std::string, RigidObstacle> obstacles = readObstacles(doc(), axisymmetric_);
  for (std::size_t c = 0; contacts && c < contacts.size(); ++c) {
    const YAML::Node C = contacts[c];
    const std::string k = Str() << "contacts[" << c << "]";
    const std::string entryA = getString(doc(), C["bodies"][0], ""),
                      entryB = getString(doc(), C["bodies"][1], "");
    const std::string nameA = pairBodyName(entryA), nameB = pairBodyName(entryB);
    const std::string name = C["name"] ? getString(doc(), C["name"], k + ".name")
                                       : entryA + "-" + entryB;
    const auto obstacle = obstacles.find(obstacles.count(nameA) ? nameA : nameB);
    if (obstacle != obstacles.end()) {  // the body is side A whichever order the file gives
      const int i = obstacles.count(nameA) ? 1 : 0;
      if (!pairRegionName(i == 0 ? entryB : entryA).empty())
        throw inputError(doc(), C["bodies"][1 - i], Str() << k << ".bodies[" << 1 - i << "]",
                         Str() << "obstacle '" << obstacle->first << "' has no contact regions "
                               << "(name it without '.')");
      const int body = index_.at(i == 0 ? nameA : nameB);
      const ContactOptions o = contactOptions(c, body, -1);
      sys.addForceElement(std::make_unique<ObstacleContact>(
          name, body, sys.body(body), contactSurface(c, i, body), obstacle->second, o));
      continue;
    }
    const int ia = index_.at(nameA), ib = index_.at(nameB);
    const int surfA = contactSurface(c, 0, ia), surfB = contactSurface(c, 1, ib);
    const ContactOptions o = contactOptions(c, ia, ib);
    sys.addForceElement(std::make_unique<ContactPair>(name, ia, sys.body(ia), surfA, ib, sys.body(ib),
                                                 surfB, o));
  }
}

// penalty_factor: auto (scene.schema.json, schemas/body_design.md): the penetration at the
// designed impact's force peak is this fraction of Hertz's approach, c_p = p0 / (eps delta)
// = 2 E* / (pi eps a) with p0 = 2 E* a / (pi R*) and delta = a^2 / R*. Measured on the
// paper's Sect. 5 impact designed (a = 0.168 mm): the force peak at eps = 0.002 is 0.013 %
// below that at 0.001 and 0.023 % below that at 0.00025.
constexpr double kAutoPenaltyPenetration = 0.002;

// The default slip velocity of friction's regularisation (schemas/contact_friction.md): a
// sticking point creeps at most at about this speed, which over a contact of 100 us moves
// it 0.1 nm, against tangential displacements of tens of nanometres and more in the
// impacts this tool is for (mu times Hertz's approach of micrometres).
constexpr double kDefaultSlipVelocity = 1e-6;

// The default relaxation time of anchored friction's slip (schemas/contact_friction.md,
// "Stick anchors"). A slipping point's force is Coulomb's whatever eta is; its anchor
// trails it by eta |v_slip| beyond the slip limit mu |g_n| (c_t = c_p: 1 to 10 nm at the
// peak of a steel impact at penalty 1e17 N/m^3) and it sticks again about eta after its
// slip stops. 1e-9 s: a trail of 0.03 nm at 0.03 m/s of slip; smaller values make the
// anchors' rows stiffer than the steps (gamma / eta >> 1), and CVODE's Newton iteration
// fails wherever a point changed between stick and slip since the last Jacobian: on the
// 20-degree oblique impact 1e-11 s took 63,420 steps with 60,112 convergence failures
// (435 s), 1e-9 s 6,692 steps (19 s), the rebound angle 0.1 % apart.
constexpr double kDefaultStickRelaxation = 1e-9;

// Pair c's c_p for penalty_factor: auto, from the bodies' materials and designed contact
// radii (body_b < 0: a rigid obstacle, infinitely stiff).
double SceneBuilder::automaticPenalty(std::size_t c, int body_a, int body_b) const {
  const MultibodySystem& sys = *scene_.system;
  const double inf = std::numeric_limits<double>::infinity();
  double radius = inf;
  HertzSphere sides[2] = {{inf, 0.0, inf, inf}, {inf, 0.0, inf, inf}};  // rigid unless flexible
  std::string names;
  for (int i = 0; i < 2; ++i) {
    const int b = i == 0 ? body_a : body_b;
    if (b < 0) continue;
    const FlexibleBodySid& sid = sys.body(b).sid();
    names += (names.empty() ? "'" : " nor '") + sys.body(b).name() + "'";
    if (sid.nq() > 0) {
      sides[i].youngs_modulus = sid.material.youngs_modulus;
      sides[i].poisson_ratio = sid.material.poisson_ratio;
    }
    if (sid.design.present)  // an ellipse counts as its approach length (hertz_ellipse.h)
      radius = std::min(radius, ellipseApproachLength(sid.design.contact_radius,
                                                      sid.design.contact_minor_radius));
  }
  const YAML::Node node = doc().root["contacts"][c]["penalty_factor"];
  const std::string key = Str() << "contacts[" << c << "].penalty_factor";
  if (!std::isfinite(radius)) {
    throw inputError(doc(), node, key,
                     Str() << "'auto' needs a designed body in the pair (a SID with /design, "
                           << "from a body file with 'design'); neither " << names
                           << " is: give c_p in N/m^3");
  }
  const double modulus = effectiveModulus(sides[0], sides[1]);
  if (!std::isfinite(modulus))
    throw inputError(doc(), node, key, "'auto' needs a flexible body in the pair");
  return 2.0 * modulus / (M_PI * kAutoPenaltyPenetration * radius);
}

// Pair c's penalty and search settings (body_b < 0: an obstacle).
ContactOptions SceneBuilder::contactOptions(std::size_t c, int body_a, int body_b) const {
  const YAML::Node C = doc().root["contacts"][c];
  const std::string k = Str() << "contacts[" << c << "]";
  ContactOptions o;
  o.penalty = C["penalty_factor"].IsScalar() && C["penalty_factor"].Scalar() == "auto"
                  ? automaticPenalty(c, body_a, body_b)
                  : getDouble(doc(), C["penalty_factor"], k + ".penalty_factor");
  if (!(o.penalty > 0.0))  // also checked by the schema; kept for direct callers
    throw inputError(doc(), C["penalty_factor"], k + ".penalty_factor",
                     Str() << "expected a number > 0 N/m^3, found " << o.penalty);
  o.both_roles = getBool(doc(), C["both_roles"], k + ".both_roles");
  o.search_margin = doubleOr(doc(), C["search_margin"], k + ".search_margin", -1.0);
  o.penetration_tolerance =
      doubleOr(doc(), C["penetration_tolerance"], k + ".penetration_tolerance", -1.0);
  o.edge_reach = doubleOr(doc(), C["edge_reach"], k + ".edge_reach", -1.0);
  readFriction(C, k, o.friction);
  if (o.friction.anchored && body_b >= 0)
    throw inputError(doc(), C["friction_law"], k + ".friction_law",
                     "'anchored' friction is implemented between a body and an obstacle only "
                     "so far: use 'regularised' between two bodies");
  return o;
}

// Pair c's Coulomb friction (runtime/contact/coulomb_friction.h): a coefficient >= 0 (0 or
// absent: frictionless) and the regularisation's slip velocity (m/s, default
// kDefaultSlipVelocity).
void SceneBuilder::readFriction(const YAML::Node& C, const std::string& k,
                                FrictionLaw& friction) const {
  friction.coefficient =
      doubleOr(doc(), C["friction_coefficient"], k + ".friction_coefficient", 0.0);
  if (!(friction.coefficient >= 0.0) || !std::isfinite(friction.coefficient))
    throw inputError(doc(), C["friction_coefficient"], k + ".friction_coefficient",
                     Str() << "expected a finite number >= 0, found " << friction.coefficient);
  friction.slip_velocity =
      doubleOr(doc(), C["slip_velocity"], k + ".slip_velocity", kDefaultSlipVelocity);
  if (!(friction.slip_velocity > 0.0) || !std::isfinite(friction.slip_velocity))
    throw inputError(doc(), C["slip_velocity"], k + ".slip_velocity",
                     Str() << "expected a finite number > 0 m/s, found " << friction.slip_velocity);
  friction.anchored =
      C["friction_law"] && getString(doc(), C["friction_law"], k + ".friction_law") == "anchored";
  friction.relaxation_time = doubleOr(doc(), C["stick_relaxation_time"],
                                      k + ".stick_relaxation_time", kDefaultStickRelaxation);
  if (!(friction.relaxation_time > 0.0) || !std::isfinite(friction.relaxation_time))
    throw inputError(doc(), C["stick_relaxation_time"], k + ".stick_relaxation_time",
                     Str() << "expected a finite number > 0 s, found " << friction.relaxation_time);
}

// The time span, the output interval and the integrator's tolerances and limits.
void SceneBuilder::readIntegrator() {
  const YAML::Node I = doc().root["integrator"];
  SimulationConfig& s = scene_.settings;
  s.end_time = getDouble(doc(), I["end_time"], "integrator.end_time");
  s.output_interval = getDouble(doc(), I["output_interval"], "integrator.output_interval");
  s.integrator.rtol = getDouble(doc(), I["rtol"], "integrator.rtol");
  atol_.position = getDouble(doc(), I["atol_position"], "integrator.atol_position");
  atol_.velocity = getDouble(doc(), I["atol_velocity"], "integrator.atol_velocity");
  atol_.rotation = getDouble(doc(), I["atol_rotation"], "integrator.atol_rotation");
  atol_.angular_velocity =
      getDouble(doc(), I["atol_angular_velocity"], "integrator.atol_angular_velocity");
  s.integrator.max_step = doubleOr(doc(), I["max_step"], "integrator.max_step", 0.0);
  s.integrator.initial_step = doubleOr(doc(), I["initial_step"], "integrator.initial_step", 0.0);
  s.integrator.max_order = getInt(doc(), I["max_order"], "integrator.max_order");
  // YAML spelling of LinearSolverKind (the schema restricts the values to these).
  s.integrator.linear_solver =
      getKind<LinearSolverKind>(doc(), I["linear_solver"], "integrator.linear_solver");
}

// 6. Joints, force elements, sensors; initial joint angles.
void SceneBuilder::addMultibody() {
  MultibodySystem& sys = *scene_.system;
  const BodyMarkers markers = collectMarkers(doc(), sys);
  const std::vector<double> angles = addJoints(doc(), index_, markers, poses_, sys);
  addForceElements(doc(), index_, markers, poses_, sys);
  addSensors(doc(), index_, markers, sys);
  applyInitialAngles(doc(), sys, angles, poses_);
}

// The initial state and tolerances; the joints satisfied, no body inside another.
void SceneBuilder::assembleState() {
  MultibodySystem& sys = *scene_.system;
  for (const InitialPose& pose : poses_) {
    scene_.initial_position.push_back(pose.r);
    scene_.initial_rotation.push_back(pose.A);
    scene_.initial_velocity.push_back(pose.v);
  }
  assembleInitialState(sys, poses_, axisymmetric_, atol_, scene_.settings.integrator.rtol,
                       scene_.y0, scene_.settings.integrator.atol);
  checkInitialConstraints(doc(), sys, scene_.y0);
  checkInitialPenetration(doc(), sys, scene_.y0);
  warnFacingAway();
}

// A warning for each obstacle pair whose contact surface faces away from its obstacle at
// t = 0 (the body falls through it unless it turns): the surface's outward normal at its
// centre against the obstacle's normal at the nearest point.
void SceneBuilder::warnFacingAway() {
  const MultibodySystem& sys = *scene_.system;
  for (int c = 0; c < sys.numContacts(); ++c) {
    const auto* pair = dynamic_cast<const ObstacleContact*>(&sys.contact(c));
    if (!pair) continue;
    const int a = pair->bodyA();
    Eigen::Vector3d x, n;
    pair->surfaceCentre(sys.body(a).pose(scene_.y0.data() + sys.positionOffset(a)), x, n);
    const ObstaclePoint p = pair->obstacle().nearest(x);
    if (n.dot(p.normal) <= 0.0) continue;
    scene_.warnings.push_back(
        Str() << "contact '" << pair->name() << "': the contact surface of body '"
              << sys.body(a).name() << "' faces away from obstacle '" << pair->obstacleName()
              << "' at t = 0 (outward normal (" << n.transpose() << ") at its centre, the "
              << "obstacle's (" << p.normal.transpose() << ")): they touch only if the body "
              << "turns (bodies[" << a << "].orientation turns it)");
  }
}

// outputs.visualisation: frames of every SID body; each SID must carry a visualisation mesh
// (igaprep's body file key visualisation.subdivisions > 0). Scene-defined rigid bodies have
// no shape and are not drawn.
void SceneBuilder::readVisualisation() {
  const YAML::Node O = doc().root["outputs"];
  if (!O || !O["visualisation"]) return;
  const YAML::Node V = O["visualisation"];
  VisualisationFramesConfig& v = scene_.visualisation;
  v.enabled = true;
  v.interval = getDouble(doc(), V["interval"], "outputs.visualisation.interval");
  v.magnification = getDouble(doc(), V["magnification"], "outputs.visualisation.magnification");
  v.revolve = getInt(doc(), V["revolve"], "outputs.visualisation.revolve");
  if (v.revolve == 1 || v.revolve == 2)
    throw inputError(doc(), V["revolve"], "outputs.visualisation.revolve",
                     "expected 0 (the meridian section) or at least 3 segments");
  const MultibodySystem& sys = *scene_.system;
  for (int b = 0; b < sys.numBodies(); ++b) {
    if (scene_.sid_files[b].empty() || !sys.body(b).sid().mesh.empty()) continue;
    throw inputError(doc(), V, "outputs.visualisation",
                     Str() << "body '" << sys.body(b).name() << "': its SID file "
                           << scene_.sid_files[b] << " has no visualisation mesh (rebuild it with "
                           << "igaprep and visualisation.subdivisions >= 1 in the body file)");
  }
}

// The static preload (runtime/system/static_preload.h) when the scene asks for it.
void SceneBuilder::preload() {
  if (!getBool(doc(), doc().root["static_preload"], "static_preload")) return;
  scene_.static_preload = true;
  scene_.preload = staticPreload(*scene_.system, scene_.y0);
}

// outputs: when the result file is flushed, progress lines, contact rows.
void SceneBuilder::readOutputs() {
  const YAML::Node O = doc().root["outputs"];  // the schema's default {} when absent
  scene_.flush.rows = getInt(doc(), O["flush_rows"], "outputs.flush_rows");
  scene_.flush.interval = getDouble(doc(), O["flush_interval"], "outputs.flush_interval");
  SimulationConfig& s = scene_.settings;
  s.progress_interval = getDouble(doc(), O["progress_interval"], "outputs.progress_interval");
  s.contact_output_interval =
      doubleOr(doc(), O["contact_output_interval"], "outputs.contact_output_interval", 0.0);
}

}  // namespace

Scene loadScene(const std::string& path, const std::vector<std::string>& sid_paths,
                const SidLoader& load_sid, const std::vector<std::string>& sets) {
  YamlDocument doc = loadYamlFile(path);
  applyOverrides(doc, sets);
  return buildScene(std::move(doc), sid_paths, load_sid);
}

Scene buildScene(YamlDocument document, const std::vector<std::string>& sid_paths,
                 const SidLoader& load_sid) {
  return SceneBuilder(std::move(document), sid_paths, load_sid).build();
}

}  // namespace ffriga
