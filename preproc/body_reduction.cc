#include "preproc/body_reduction.h"

#include <chrono>
#include <cmath>
#include <set>

#include "common/splines/contact_surface.h"
#include "common/base/error.h"
#include "common/base/version.h"
#include "preproc/geometry/contact_region.h"
#include "preproc/reduction/craig_bampton.h"
#include "preproc/assembly/dof_map.h"
#include "preproc/assembly/elasticity_assembly.h"
#include "preproc/reduction/marker_points.h"
#include "preproc/assembly/rigid_body_modes.h"
#include "preproc/reduction/sid_invariants.h"
#include "preproc/solvers/single_threaded_blas.h"
#include "preproc/assembly/stress_modes.h"
#include "preproc/assembly/visualisation_mesh.h"

namespace ffriga {

namespace {

const double kPi = std::acos(-1.0);

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

// Material and exact geometry for the runtime (stresses, Hertz's reference).
void describeBody(const BodyConfig& config, const Eigen::Vector3d& origin, FlexibleBodySid* sid) {
  sid->material.youngs_modulus = config.material.youngs_modulus;
  sid->material.poisson_ratio = config.material.poisson_ratio;
  sid->material.density = config.material.density;
  sid->geometry.type = config.geometry_type;
  sid->geometry.radius = config.geometry_radius;
  sid->geometry.length = config.geometry_length;
  sid->geometry.centre = -origin;  // the geometries are built around the origin
}

// Visualisation mesh and stress lines with their sampled displacement and stress modes.
void sampleBody(const BodyConfig& config, const HierarchicalSpace& space,
                const Eigen::Vector3d& origin, FlexibleBodySid* sid) {
  const bool axi = config.model == ModelKind::kAxisymmetric;
  IsotropicMaterial material;
  material.youngs_modulus = config.material.youngs_modulus;
  material.poisson_ratio = config.material.poisson_ratio;
  const Eigen::MatrixXd& P = space.controlPoints();
  const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
  const int s = space.spaceDim();
  sid->mesh = visualisationMesh(space, config.visualisation.subdivisions, sid->Phi, material, axi,
                                origin.head(s), size);
  for (const StressLineConfig& lc : config.visualisation.stress_lines) {
    std::vector<ParametricPoint> points;
    for (const auto& xi : lc.parameters) {
      ParametricPoint p;
      p.xi = xi;
      p.element = space.findElement(xi.data());
      points.push_back(p);
    }
    StressLine line;
    line.name = lc.name;
    line.from = lc.from - origin.head(s);
    line.to = lc.to - origin.head(s);
    line.samples = sampleModes(space, points, sid->Phi, material, axi, origin.head(s), size);
    sid->stress_lines.push_back(std::move(line));
  }
}

}  // namespace

FlexibleBodySid preprocessBody(const BodyConfig& config,
                               const std::function<void(const std::string&)>& log,
                               PreprocessSummary* summary) {
  bool interfaceMarkers = false;
  for (const MarkerConfig& m : config.markers) interfaceMarkers = interfaceMarkers || m.interface;
  if (config.reduction.method == "craig_bampton" && !config.contact.present && !interfaceMarkers) {
    throw InputError(Str() << config.source.path << ": the Craig-Bampton reduction (the default "
                           << "of key 'reduction.method') needs an interface: add the key "
                           << "'contact' with face and region, or 'interface: true' on a marker, "
                           << "or choose method: modal");
  }
  const SingleThreadedBlas singleThreadedBlas;  // bitwise reproducible factorisations
  FlexibleBodySid sid;
  StageClock clock(&sid, log);
  const bool axi = config.model == ModelKind::kAxisymmetric;
  sid.name = config.name;
  sid.model = toString(config.model);
  sid.input_yaml = config.source.text;
  sid.input_path = config.source.path;
  for (const YamlOverride& o : config.source.overrides) sid.input_overrides += o.text + "\n";
  sid.created_by = Str() << "igaprep " << kVersion;
  sid.reduction = config.reduction.method;
  sid.frame = config.reduction.frame;

  // Geometry: the (hierarchically) refined space; everything below works on the abstract
  // SplineSpace. The quadrature degrees come from the refined patch (all levels share them).
  const HierarchicalSpace hspace = bodySpace(config);
  const NurbsPatch& patch = hspace.basePatch();
  const SplineSpace& space = hspace;
  const int s = space.spaceDim();
  const int d = space.paramDim();
  sid.space_dim = s;
  sid.nlvl = config.global_reference ? 1 : hspace.numLevels();
  sid.n_elements = space.numElements();
  const DofMap dofs(space, axi, tiedControlPoints(hspace));
  sid.ndof = dofs.numDofs();
  summary->ndof = dofs.numDofs();
  summary->num_control_points = space.numFunctions();
  summary->tied_points = dofs.numTiedPoints();
  summary->fixed_dofs = dofs.numFixedDofs();
  clock.done("geometry", Str() << space.numElements() << " elements, " << space.numFunctions()
                               << " control points, " << dofs.numDofs() << " DOFs");

  // Assembly.
  ElasticityModel model;
  model.axisymmetric = axi;
  model.youngs_modulus = config.material.youngs_modulus;
  model.poisson_ratio = config.material.poisson_ratio;
  model.density = config.material.density;
  for (int a = 0; a < d; ++a) model.gauss_points[a] = patch.degree(a) + 1;
  const ElasticSystem sys = assembleElasticity(space, dofs, model);
  clock.done("assembly", Str() << "K: " << sys.K.nonZeros() << " stored entries (upper)");

  // Interface.
  ReductionOptions ro;
  ro.method =
      config.reduction.method == "modal" ? ReductionMethod::kModal : ReductionMethod::kCraigBampton;
  ro.frame = config.reduction.frame == "tangent" ? FrameKind::kTangent : FrameKind::kBuckens;
  ro.normal_modes = config.reduction.normal_modes;
  ro.rigid_modes = rigidBodyModes(space, dofs, axi);
  ContactRegion region;
  if (config.contact.present) {
    region.direction = config.contact.direction;
    region.upper = config.contact.upper;
    region.bounds = config.contact.bounds;
  }
  int gaussFace = 0;  // face markers: degree + 2 Gauss points per direction
  for (int a = 0; a < d; ++a) gaussFace = std::max(gaussFace, patch.degree(a) + 2);
  if (ro.method == ReductionMethod::kCraigBampton) {
    std::vector<int> cps;
    if (config.contact.present) cps = interfaceControlPoints(space, region);
    // Interface markers: every control point whose function does not vanish at the marker,
    // so that a joint's load there lies in the span of the constraint modes.
    for (const MarkerConfig& m : config.markers) {
      if (!m.interface) continue;
      const Marker mk = m.face ? evaluateFaceMarker(space, m.name, m.face_direction, m.face_upper,
                                                    gaussFace, Eigen::MatrixXd(0, 0))
                               : evaluateMarker(space, m.name, m.parameters);
      for (std::size_t j = 0; j < mk.functions.size(); ++j)
        if (mk.values(static_cast<int>(j)) != 0.0) cps.push_back(mk.functions[j]);
    }
    std::set<int> nodes;
    ro.interface.assign(dofs.numDofs(), false);
    for (int k : cps) {
      nodes.insert(dofs.node(k));
      for (int c = 0; c < s; ++c) {
        if (dofs.dof(k, c) >= 0) ro.interface[dofs.dof(k, c)] = true;
      }
    }
    for (bool b : ro.interface) summary->interface_dofs += b;
    summary->interface_control_points = static_cast<int>(nodes.size());
    if (cps.empty()) {
      throw InputError(Str() << config.source.path << ": contact.region selects no control "
                             << "point on face " << faceName(region.direction, region.upper)
                             << " and no marker has interface: true: the interface is empty");
    }
  }
  sid.n_interface_control_points = summary->interface_control_points;
  std::vector<double> frameXi;
  for (const MarkerConfig& m : config.markers) {
    if (m.name == config.reduction.frame_marker) frameXi = m.parameters;
  }
  if (ro.frame == FrameKind::kTangent) {
    ro.frame_conditions = tangentFrameConditions(space, dofs, frameXi, axi);
  }
  ReducedModel red;
  try {
    red = reduceBody(sys.K, sys.M, ro);
  } catch (const InputError& e) {
    throw InputError(Str() << config.source.path << ": " << e.what());
  } catch (const ComputeError& e) {
    throw ComputeError(Str() << config.source.path << ": " << e.what());
  }
  for (const auto& [step, t] : red.timings) {
    if (log) log(Str() << "  reduction step " << step << ": " << t << " s");
  }
  if (log && red.factor_nonzeros > 0.0) {
    log(Str() << "  factor of K_ii: " << red.factor_nonzeros << " entries ("
              << red.factor_nonzeros * 8.0 / (1024.0 * 1024.0 * 1024.0) << " GiB), "
              << red.factor_flops << " flops");
  }
  summary->factor_rcond = red.factor_rcond;
  summary->arpack_iterations = red.arpack_iterations;
  sid.normal_modes = red.normal_modes;
  sid.constraint_modes = red.constraint_modes;
  sid.rigid_modes_dropped = red.rigid_dropped;
  const int nq = static_cast<int>(red.omega2.size());
  if (nq > 0 && red.omega2(0) <= 0.0) {
    throw ComputeError(Str() << "reduction: the lowest reduced eigenvalue is " << red.omega2(0)
                             << " (rad/s)^2; a rigid-body direction was not removed");
  }
  clock.done("reduction", Str() << config.reduction.method << ", " << red.normal_modes
                                << " normal + " << red.constraint_modes << " constraint modes, "
                                << red.rigid_dropped << " rigid directions dropped, nq = " << nq);

  // Invariants, in the body frame.
  std::array<int, 3> massPoints{};
  for (int a = 0; a < d; ++a) massPoints[a] = patch.degree(a) + 3;
  const MassProperties mp = massProperties(space, model.density, axi, massPoints);
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  if (ro.frame == FrameKind::kBuckens) {
    origin = mp.centreOfMass();
    if (axi) origin(0) = origin(2) = 0.0;  // on the axis by symmetry
  } else {
    const Marker fm = evaluateMarker(space, config.reduction.frame_marker, frameXi);
    origin.head(s) = fm.position;
    if (axi) origin(0) = 0.0;  // the frame of a body of revolution stays on its axis
  }
  sid.frame_origin = origin;
  const MassProperties body = mp.shifted(origin);
  sid.mass = body.mass;
  sid.first_moment = body.first_moment;
  sid.inertia = body.inertia;
  sid.control_points = space.controlPoints();
  for (int k = 0; k < sid.control_points.rows(); ++k)
    sid.control_points.row(k) -= origin.head(s).transpose();
  sid.weights = space.weights();
  sid.Phi = dofs.expand(red.Phi);
  computeElasticInvariants(sys.Ms, sid.control_points, sid.Phi, axi, &sid);
  sid.frequencies_hz = red.omega2.cwiseSqrt() / (2.0 * kPi);
  sid.Me = Eigen::MatrixXd::Identity(nq, nq);
  sid.Ke = red.omega2.asDiagonal();
  sid.damping_ratio.resize(nq);
  sid.De = Eigen::MatrixXd::Zero(nq, nq);
  const double f1 = nq > 0 ? sid.frequencies_hz.minCoeff() : 0.0;
  for (int i = 0; i < nq; ++i) {
    sid.damping_ratio(i) = config.reduction.dampingRatio(sid.frequencies_hz(i), f1);
    sid.De(i, i) = 2.0 * sid.damping_ratio(i) * std::sqrt(red.omega2(i));
  }
  clock.done("invariants", Str() << "mass " << sid.mass << " kg");

  // Contact surface and markers.
  if (config.contact.present) {
    ParamBox box;
    for (std::size_t a = 0; a < region.bounds.size(); ++a) {
      box.lower[a] = region.bounds[a][0];
      box.upper[a] = region.bounds[a][1];
    }
    ContactSurface cs;
    try {
      cs = extractContactSurface(hspace, region.direction, region.upper ? 1 : 0, box,
                                 config.contact.name);
    } catch (const std::invalid_argument& e) {
      throw InputError(Str() << config.source.path << ": contact surface: " << e.what());
    }
    sid.surfaces.push_back(std::move(cs));
  }
  for (const MarkerConfig& m : config.markers) {
    if (m.face) {
      Marker mk =
          evaluateFaceMarker(space, m.name, m.face_direction, m.face_upper, gaussFace, sid.Phi);
      mk.position -= origin.head(s);
      sid.markers.push_back(std::move(mk));
      continue;
    }
    Marker mk = evaluateMarker(space, m.name, m.parameters);
    mk.position -= origin.head(s);
    if (s == 3) {
      try {
        mk.Psi = markerRotationModes(space, m.name, m.parameters, sid.Phi);
      } catch (const InputError& e) {
        throw InputError(Str() << config.source.path << ": " << e.what());
      }
    }
    sid.markers.push_back(std::move(mk));
  }
  clock.done("surface", Str() << sid.surfaces.size() << " contact surface(s), "
                              << sid.markers.size() << " marker(s)");

  describeBody(config, origin, &sid);
  sampleBody(config, hspace, origin, &sid);
  clock.done("visualisation",
             Str() << sid.mesh.samples.points.rows() << " mesh points, " << sid.mesh.cells.rows()
                   << " cells, " << sid.stress_lines.size() << " stress line(s)");
  return sid;
}

}  // namespace ffriga
