#include "preproc/body_preprocessor.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <set>

#include "common/base/error.h"
#include "common/base/version.h"
#include "common/splines/contact_surface.h"
#include "preproc/assembly/dof_map.h"
#include "preproc/assembly/elasticity_assembly.h"
#include "preproc/assembly/rigid_body_modes.h"
#include "preproc/assembly/stress_modes.h"
#include "preproc/assembly/visualisation_mesh.h"
#include "preproc/geometry/contact_region.h"
#include "preproc/reduction/craig_bampton.h"
#include "preproc/reduction/marker_points.h"
#include "preproc/reduction/pressure_patches.h"
#include "preproc/reduction/sid_invariants.h"
#include "preproc/solvers/single_threaded_blas.h"

namespace ffriga {

namespace {

const double kPi = std::acos(-1.0);

// The columns of the blocks one after the other (all with the same rows).
Eigen::MatrixXd sideBySide(const std::vector<Eigen::MatrixXd>& blocks) {
  Eigen::Index cols = 0;
  for (const Eigen::MatrixXd& b : blocks) cols += b.cols();
  Eigen::MatrixXd out(blocks.empty() ? 0 : blocks.front().rows(), cols);
  Eigen::Index j = 0;
  for (const Eigen::MatrixXd& b : blocks) {
    out.middleCols(j, b.cols()) = b;
    j += b.cols();
  }
  return out;
}

class StageClock {
 public:
  StageClock(FlexibleBodySid* sid, const std::function<void(const std::string&)>& log)
      : sid_(sid), log_(log), last_(std::chrono::steady_clock::now()) {}
  void done(const std::string& stage, const std::string& detail) {
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    sid_->stage_times_s.emplace_back(stage, dt);
    if (log_) log_(Str() << stage << ": " << detail << " (" << dt << " s)");
  }

 private:
  FlexibleBodySid* sid_;
  std::function<void(const std::string&)> log_;
  std::chrono::steady_clock::time_point last_;
};

// The pipeline of the header comment; run() calls the phases in order.
class BodyPreprocessor {
 public:
  BodyPreprocessor(const BodyConfig& config, const std::function<void(const std::string&)>& log,
                   PreprocessSummary* summary)
      : config_(config), log_(log), summary_(summary), clock_(&sid_, log),
        axi_(config.model == ModelKind::kAxisymmetric) {}
  FlexibleBodySid run();

 private:
  void checkInterfaceExists() const;
  void identify();
  void setupGeometry();
  void assembleSystem();
  std::vector<int> interfacePoints(std::vector<int>* markerPoints) const;
  ContactSurface contactSurface(const ContactConfig& c) const;
  void patchLoads();
  void selectInterface();
  void reduce();
  void computeInvariants();
  void extractSurfaces();
  void sampleVisualisation();

  const BodyConfig& config_;
  const std::function<void(const std::string&)>& log_;
  PreprocessSummary* summary_;
  FlexibleBodySid sid_;
  StageClock clock_;
  const bool axi_;
  std::unique_ptr<HierarchicalSpace> space_;
  std::unique_ptr<DofMap> dofs_;
  ElasticityModel model_;
  ElasticSystem system_;
  ReductionOptions options_;
  int gauss_face_ = 0;           // face markers: degree + 2 Gauss points per direction
  std::vector<double> frame_xi_;  // the tangent frame marker's parameters
  ReducedModel reduced_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();  // of the body frame, geometry coordinates
};

FlexibleBodySid BodyPreprocessor::run() {
  checkInterfaceExists();
  const SingleThreadedBlas singleThreadedBlas;  // bitwise reproducible factorisations
  identify();
  setupGeometry();
  assembleSystem();
  selectInterface();
  patchLoads();
  reduce();
  computeInvariants();
  extractSurfaces();
  sampleVisualisation();
  return std::move(sid_);
}

void BodyPreprocessor::checkInterfaceExists() const {
  bool interfaceMarkers = false;
  for (const MarkerConfig& m : config_.markers) interfaceMarkers = interfaceMarkers || m.interface;
  if (config_.reduction.method == ReductionMethod::kCraigBampton && config_.contacts.empty() &&
      !interfaceMarkers) {
    throw InputError(Str() << config_.source.path << ": the Craig-Bampton reduction (the default "
                           << "of key 'reduction.method') needs an interface: add the key "
                           << "'contact' (or 'contacts') with face and region, or 'interface: "
                           << "true' on a marker, or choose method: modal");
  }
}

// The SID's name, kind and provenance.
void BodyPreprocessor::identify() {
  sid_.name = config_.name;
  sid_.model = config_.model;
  sid_.input_yaml = config_.source.text;
  sid_.input_path = config_.source.path;
  for (const YamlOverride& o : config_.source.overrides) sid_.input_overrides += o.text + "\n";
  sid_.created_by = Str() << "igaprep " << kVersion;
  sid_.reduction = config_.reduction.method;
  sid_.frame = config_.reduction.frame;
}

// The (hierarchically) refined space; everything below works on the abstract SplineSpace.
void BodyPreprocessor::setupGeometry() {
  space_ = std::make_unique<HierarchicalSpace>(bodySpace(config_));
  const SplineSpace& space = *space_;
  sid_.space_dim = space.spaceDim();
  sid_.nlvl = config_.global_reference ? 1 : space_->numLevels();
  sid_.n_elements = space.numElements();
  dofs_ = std::make_unique<DofMap>(space, axi_, tiedControlPoints(*space_));
  sid_.ndof = dofs_->numDofs();
  summary_->ndof = dofs_->numDofs();
  summary_->num_control_points = space.numFunctions();
  summary_->tied_points = dofs_->numTiedPoints();
  summary_->fixed_dofs = dofs_->numFixedDofs();
  clock_.done("geometry", Str() << space.numElements() << " elements, " << space.numFunctions()
                                << " control points, " << dofs_->numDofs() << " DOFs");
}

// K, M and Ms; the quadrature degrees come from the refined patch (all levels share them).
void BodyPreprocessor::assembleSystem() {
  const NurbsPatch& patch = space_->basePatch();
  model_.axisymmetric = axi_;
  model_.material = config_.material;
  for (int a = 0; a < space_->paramDim(); ++a) model_.gauss_points[a] = patch.degree(a) + 1;
  system_ = assembleElasticity(*space_, *dofs_, model_);
  clock_.done("assembly", Str() << "K: " << system_.K.nonZeros() << " stored entries (upper)");
}

// The control points of every contact region (their union; each region must select some)
// and, at interface markers, every control point whose function does not vanish there, so
// that a joint's load lies in the span of the constraint modes; the markers' alone also in
// markerPoints.
std::vector<int> BodyPreprocessor::interfacePoints(std::vector<int>* markerPoints) const {
  const SplineSpace& space = *space_;
  std::vector<int> cps;
  for (const ContactConfig& c : config_.contacts) {
    const std::vector<int> own =
        interfaceControlPoints(space, ContactRegion{c.direction, c.upper, c.bounds});
    if (own.empty()) {
      throw inputError(config_.source, contactNode(config_.source, c)["region"], c.key + ".region",
                       Str() << "the region selects no control point on face "
                             << faceName(c.direction, c.upper) << ": no interface, no surface");
    }
    cps.insert(cps.end(), own.begin(), own.end());
  }
  for (const MarkerConfig& m : config_.markers) {
    if (!m.interface) continue;
    const Marker mk = m.face ? evaluateFaceMarker(space, m.name, m.face_direction, m.face_upper,
                                                  gauss_face_, Eigen::MatrixXd(0, 0))
                             : evaluateMarker(space, m.name, m.parameters);
    for (std::size_t j = 0; j < mk.functions.size(); ++j)
      if (mk.values(static_cast<int>(j)) != 0.0) {
        cps.push_back(mk.functions[j]);
        markerPoints->push_back(mk.functions[j]);
      }
  }
  return cps;  // duplicates (shared by regions and markers) count once below
}

// The reduction's options: method, frame and, for Craig-Bampton, the interface DOFs of
// interfacePoints().
void BodyPreprocessor::selectInterface() {
  const SplineSpace& space = *space_;
  const int s = space.spaceDim();
  options_.method = config_.reduction.method;
  options_.frame = config_.reduction.frame;
  options_.normal_modes = config_.reduction.normal_modes;
  options_.mode_cutoff_hz = config_.reduction.mode_cutoff_hz;
  options_.rigid_modes = rigidBodyModes(space, *dofs_, axi_);
  for (int a = 0; a < space.paramDim(); ++a)
    gauss_face_ = std::max(gauss_face_, space_->basePatch().degree(a) + 2);
  if (options_.method == ReductionMethod::kCraigBampton) {
    std::vector<int> markerPoints;
    const std::vector<int> cps = interfacePoints(&markerPoints);
    std::set<int> nodes;
    options_.interface.assign(dofs_->numDofs(), false);
    options_.interface_retained.assign(dofs_->numDofs(), false);
    for (int k : cps) {
      nodes.insert(dofs_->node(k));
      for (int c = 0; c < s; ++c) {
        if (dofs_->dof(k, c) >= 0) options_.interface[dofs_->dof(k, c)] = true;
      }
    }
    for (int k : markerPoints) {
      for (int c = 0; c < s; ++c) {
        if (dofs_->dof(k, c) >= 0) options_.interface_retained[dofs_->dof(k, c)] = true;
      }
    }
    options_.interface_modes = config_.reduction.interface_modes;
    for (bool b : options_.interface) summary_->interface_dofs += b;
    summary_->interface_control_points = static_cast<int>(nodes.size());
    if (cps.empty()) {
      throw InputError(Str() << config_.source.path << ": no contact region and no marker with "
                             << "interface: true selects a control point: the interface is empty");
    }
  }
  sid_.n_interface_control_points = summary_->interface_control_points;
  for (const MarkerConfig& m : config_.markers) {
    if (m.name == config_.reduction.frame_marker) frame_xi_ = m.parameters;
  }
  if (options_.frame == FrameKind::kTangent)
    options_.frame_conditions = tangentFrameConditions(space, *dofs_, frame_xi_, axi_);
}

// Craig-Bampton or modal reduction (preproc/reduction/craig_bampton.h).
void BodyPreprocessor::reduce() {
  try {
    reduced_ = reduceBody(system_.K, system_.M, options_);
  } catch (const ParameterError& e) {
    throw inputErrorAt(config_.source, e);
  } catch (const InputError& e) {
    throw InputError(Str() << config_.source.path << ": " << e.what());
  } catch (const ComputeError& e) {
    throw ComputeError(Str() << config_.source.path << ": " << e.what());
  }
  for (const auto& [step, t] : reduced_.timings) {
    if (log_) log_(Str() << "  reduction step " << step << ": " << t << " s");
  }
  if (log_ && reduced_.factor_nonzeros > 0.0) {
    log_(Str() << "  factor of K_ii: " << reduced_.factor_nonzeros << " entries ("
               << reduced_.factor_nonzeros * 8.0 / (1024.0 * 1024.0 * 1024.0) << " GiB), "
               << reduced_.factor_flops << " flops");
  }
  summary_->factor_rcond = reduced_.factor_rcond;
  summary_->arpack_iterations = reduced_.arpack_iterations;
  sid_.normal_modes = reduced_.normal_modes;
  sid_.constraint_modes = reduced_.constraint_modes;
  sid_.interface_dofs = reduced_.interface_dofs;
  if (options_.reducesInterface()) {
    sid_.characteristic_modes = reduced_.characteristic_rigid + reduced_.characteristic_elastic;
    sid_.patch_modes = reduced_.patch_modes;
    sid_.interface_compliance_error = reduced_.interface_compliance_error;
    sid_.characteristic_frequencies_hz =
        reduced_.characteristic_omega2.cwiseMax(0.0).cwiseSqrt() / (2.0 * kPi);
    const Eigen::VectorXd& f = sid_.characteristic_frequencies_hz;
    const int kept = sid_.characteristic_modes;
    if (log_ && kept > 0) {
      const std::string dropped =
          kept < f.size() ? std::string(Str() << ", lowest dropped " << f(kept) << " Hz") : "";
      const std::string guard =
          reduced_.interface_compliance_error >= 0.0
              ? std::string(Str() << "; static compliance missed between the patch radii <= "
                                  << reduced_.interface_compliance_error)
              : "";
      const std::string highest =
          reduced_.characteristic_elastic > 0
              ? std::string(Str() << " (highest " << f(kept - 1) << " Hz" << dropped << ")")
              : "";
      log_(Str() << "  interface: " << reduced_.interface_dofs << " DOFs -> "
                 << reduced_.characteristic_rigid << " rigid + " << reduced_.characteristic_elastic
                 << " elastic characteristic modes" << highest << " + " << reduced_.patch_modes
                 << " pressure patch modes + " << reduced_.interface_retained
                 << " retained marker DOFs" << guard);
    }
  }
  sid_.rigid_modes_dropped = reduced_.rigid_dropped;
  const int nq = static_cast<int>(reduced_.omega2.size());
  if (nq > 0 && reduced_.omega2(0) <= 0.0) {
    throw ComputeError(Str() << "reduction: the lowest reduced eigenvalue is " << reduced_.omega2(0)
                             << " (rad/s)^2; a rigid-body direction was not removed");
  }
  clock_.done("reduction", Str() << toString(config_.reduction.method) << ", " << reduced_.normal_modes
                                 << " normal + " << reduced_.constraint_modes << " constraint modes, "
                                 << reduced_.rigid_dropped << " rigid directions dropped, nq = " << nq);
}

// The body frame (Buckens: the centre of mass; tangent: the frame marker), the mass
// properties and elastic invariants in it, Me = E, Ke = diag(omega^2), the damping.
void BodyPreprocessor::computeInvariants() {
  const SplineSpace& space = *space_;
  const int s = space.spaceDim();
  std::array<int, 3> massPoints{};
  for (int a = 0; a < space.paramDim(); ++a) massPoints[a] = space_->basePatch().degree(a) + 3;
  const MassProperties mp = massProperties(space, model_.material.density, axi_, massPoints);
  if (options_.frame == FrameKind::kBuckens) {
    origin_ = mp.centreOfMass();
    if (axi_) origin_(0) = origin_(2) = 0.0;  // on the axis by symmetry
  } else {
    const Marker fm = evaluateMarker(space, config_.reduction.frame_marker, frame_xi_);
    origin_.head(s) = fm.position;
    if (axi_) origin_(0) = 0.0;  // the frame of a body of revolution stays on its axis
  }
  sid_.frame_origin = origin_;
  const MassProperties body = mp.shifted(origin_);
  sid_.mass = body.mass;
  sid_.first_moment = body.first_moment;
  sid_.inertia = body.inertia;
  sid_.control_points = space.controlPoints();
  for (int k = 0; k < sid_.control_points.rows(); ++k)
    sid_.control_points.row(k) -= origin_.head(s).transpose();
  sid_.weights = space.weights();
  sid_.Phi = dofs_->expand(reduced_.Phi);
  computeElasticInvariants(system_.Ms, sid_.control_points, sid_.Phi, axi_, &sid_);
  const int nq = static_cast<int>(reduced_.omega2.size());
  sid_.frequencies_hz = reduced_.omega2.cwiseSqrt() / (2.0 * kPi);
  sid_.Me = Eigen::MatrixXd::Identity(nq, nq);
  sid_.Ke = reduced_.omega2.asDiagonal();
  sid_.damping_ratio.resize(nq);
  sid_.De = Eigen::MatrixXd::Zero(nq, nq);
  const double f1 = nq > 0 ? sid_.frequencies_hz.minCoeff() : 0.0;
  for (int i = 0; i < nq; ++i) {
    sid_.damping_ratio(i) = config_.reduction.dampingRatio(sid_.frequencies_hz(i), f1);
    sid_.De(i, i) = 2.0 * sid_.damping_ratio(i) * std::sqrt(reduced_.omega2(i));
  }
  clock_.done("invariants", Str() << "mass " << sid_.mass << " kg");
}

// The contact surface of region c (common/splines/contact_surface.h).
ContactSurface BodyPreprocessor::contactSurface(const ContactConfig& c) const {
  ParamBox box;
  for (std::size_t a = 0; a < c.bounds.size(); ++a) {
    box.lower[a] = c.bounds[a][0];
    box.upper[a] = c.bounds[a][1];
  }
  try {
    return extractContactSurface(*space_, c.direction, c.upper ? 1 : 0, box, c.name,
                                 c.gauss ? CollocationRule::kGauss : CollocationRule::kBotella);
  } catch (const std::invalid_argument& e) {
    throw InputError(Str() << config_.source.path << ": contact surface '" << c.name << "' (key '"
                           << c.key << "'): " << e.what());
  }
}

// reduction.pressure_patches: the patches' loads on the interface (pressure_patches.h), for
// every contact region around its own centre, side by side, and the accuracy guard's.
void BodyPreprocessor::patchLoads() {
  const PressurePatchConfig& pc = config_.reduction.pressure_patches;
  if (!pc.given) return;
  const YAML::Node node = config_.source.root["reduction"]["pressure_patches"];
  if (!pc.centre.empty() && config_.contacts.size() != 1) {
    throw inputError(config_.source, node["centre"], "reduction.pressure_patches.centre",
                     Str() << "a centre names a point of one contact region, the body has "
                           << config_.contacts.size() << " (without it each region's patches "
                           << "centre on the region)");
  }
  std::vector<int> index(options_.interface.size(), -1);
  for (std::size_t j = 0, b = 0; j < index.size(); ++j)
    if (options_.interface[j]) index[j] = static_cast<int>(b++);
  PressurePatchOptions po;
  // A designed body knows its largest contact radius: 20 % beyond it covers the peak (the
  // penalty's overshoot of Hertz's a is below 1 %) and a faster impact than designed.
  po.radius = pc.radius > 0.0  ? pc.radius
              : config_.design ? 1.2 * config_.design->contact_radius
                               : 0.0;
  if (!(po.radius > 0.0)) {
    throw inputError(config_.source, node, "reduction.pressure_patches.radius",
                     "give the largest patch radius (m): only a designed body (key 'design') "
                     "has a default");
  }
  po.radii = pc.radii;
  po.degree = pc.degree;
  po.tangential = pc.tangential;
  po.centre = pc.centre;
  // The guard: normal Hertz patches halfway between the radii, from a quarter of the largest
  // on (smaller contacts carry less than 1/64 of the peak force, and the finest elements,
  // not the interface, limit how well they are resolved).
  PressurePatchOptions guard = po;
  guard.degree = 0;
  guard.tangential = false;
  guard.radius_offset = 0.5;
  guard.smallest_radius = 0.25 * po.radius;
  std::vector<Eigen::MatrixXd> loads, checks;
  Str centres;
  for (const ContactConfig& c : config_.contacts) {
    try {
      const ContactSurface surface = contactSurface(c);
      const PressurePatchLoads region =
          pressurePatchLoads(*space_, *dofs_, surface, axi_, index, po);
      loads.push_back(region.F);
      centres << " " << c.name << " (" << region.centre.transpose() << ") m";
      checks.push_back(pressurePatchLoads(*space_, *dofs_, surface, axi_, index, guard).F);
    } catch (const InputError& e) {
      throw inputError(config_.source, node, "reduction.pressure_patches",
                       Str() << "region '" << c.name << "': " << e.what());
    }
  }
  options_.interface_loads = sideBySide(loads);
  options_.interface_check_loads = sideBySide(checks);
  clock_.done("pressure patches", Str() << options_.interface_loads.cols() << " loads, radii up to "
                                        << po.radius << " m, around" << centres.str());
}

// One contact surface per region (Bezier-extracted, with its collocation points, named by
// the region, in file order) and the markers, in the body frame.
void BodyPreprocessor::extractSurfaces() {
  const SplineSpace& space = *space_;
  const int s = space.spaceDim();
  for (const ContactConfig& c : config_.contacts) sid_.surfaces.push_back(contactSurface(c));
  for (const MarkerConfig& m : config_.markers) {
    Marker mk = m.face ? evaluateFaceMarker(space, m.name, m.face_direction, m.face_upper,
                                            gauss_face_, sid_.Phi)
                       : evaluateMarker(space, m.name, m.parameters);
    mk.position -= origin_.head(s);
    if (!m.face && s == 3) {
      try {
        mk.Psi = markerRotationModes(space, m.name, m.parameters, sid_.Phi);
      } catch (const InputError& e) {
        throw InputError(Str() << config_.source.path << ": " << e.what());
      }
    }
    sid_.markers.push_back(std::move(mk));
  }
  clock_.done("surface", Str() << sid_.surfaces.size() << " contact surface(s), "
                               << sid_.markers.size() << " marker(s)");
}

// Material and exact geometry for the runtime (stresses, Hertz's reference); the
// visualisation mesh and the stress lines with their sampled displacement and stress modes.
void BodyPreprocessor::sampleVisualisation() {
  sid_.material = config_.material;
  sid_.geometry.type = toString(config_.geometry.kind);
  sid_.geometry.radius = config_.geometry.radius;
  sid_.geometry.length = config_.geometry.length;
  sid_.geometry.centre = -origin_;  // the geometries are built around the origin
  if (config_.design) {
    const ImpactDesign& d = *config_.design;
    sid_.design.present = true;
    sid_.design.contact_radius = d.contact_radius;
    sid_.design.elements_per_contact_radius = d.elements_per_contact_radius;
    sid_.design.finest_element = std::max(d.finest_arc, d.finest_depth);
    sid_.design.approach_speed = d.approach_speed;
    sid_.design.max_pressure = d.max_pressure;
    sid_.design.surface_radius = d.surface_radius;
    sid_.design.contact_minor_radius = d.contact_minor_radius;
    sid_.design.hertz_max_force = d.hertz ? d.hertz->max_force : 0.0;
    sid_.design.hertz_duration = d.hertz ? d.hertz->duration : 0.0;
    sid_.design.mode_cutoff_hz = d.mode_cutoff_hz;
    sid_.design.contact_point = Eigen::Vector3d::Zero();
    sid_.design.contact_normal = Eigen::Vector3d::Zero();
    sid_.design.contact_point.head(d.contact_point.size()) = d.contact_point;
    sid_.design.contact_normal.head(d.contact_normal.size()) = d.contact_normal;
    sid_.design.principal_curvatures =
        Eigen::Vector2d(d.principal_curvatures[0], d.principal_curvatures[1]);
    if (d.principal_direction.size() == 3) sid_.design.principal_direction = d.principal_direction;
  }
  const IsotropicMaterial& material = config_.material;
  const Eigen::MatrixXd& P = space_->controlPoints();
  const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
  const int s = space_->spaceDim();
  sid_.mesh = visualisationMesh(*space_, config_.visualisation.subdivisions, sid_.Phi, material,
                                axi_, origin_.head(s), size);
  for (const StressLineConfig& lc : config_.visualisation.stress_lines) {
    std::vector<ParametricPoint> points;
    for (const auto& xi : lc.parameters) {
      ParametricPoint p;
      p.xi = xi;
      p.element = space_->findElement(xi.data());
      points.push_back(p);
    }
    StressLine line;
    line.name = lc.name;
    line.from = lc.from - origin_.head(s);
    line.to = lc.to - origin_.head(s);
    line.samples = sampleModes(*space_, points, sid_.Phi, material, axi_, origin_.head(s), size);
    sid_.stress_lines.push_back(std::move(line));
  }
  clock_.done("visualisation",
              Str() << sid_.mesh.samples.points.rows() << " mesh points, " << sid_.mesh.cells.rows()
                    << " cells, " << sid_.stress_lines.size() << " stress line(s)");
}

}  // namespace

FlexibleBodySid preprocessBody(const BodyConfig& config,
                               const std::function<void(const std::string&)>& log,
                               PreprocessSummary* summary) {
  return BodyPreprocessor(config, log, summary).run();
}

}  // namespace ffriga
