#include "runtime/output/result_writer.h"

#include "common/base/error.h"
#include "runtime/bodies/axisymmetric_body.h"

namespace ffriga {

using h5::Handle;

namespace {
// Checked HDF5 call of the result file (common/sid/hdf5_io.h: ComputeError naming the file).
hid_t check(hid_t status, const std::string& what, const std::string& file) {
  return h5::Context{file}.check(status, what);
}
}  // namespace

ResultWriter::ResultWriter(const std::string& path, const MultibodySystem& system,
                           const std::string& created_by, const std::string& scene_yaml,
                           int flush_rows, double flush_interval, const RestartRecord* resume)
    : path_(path),
      flush_rows_(flush_rows),
      flush_interval_(flush_interval),
      last_flush_(std::chrono::steady_clock::now()) {
  h5::silenceErrors();
  appending_ = resume != nullptr;
  const hid_t f = appending_ ? H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)
                             : H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) {
    throw InputError(Str() << path << ": cannot " << (appending_ ? "open" : "create")
                           << " the result file");
  }
  file_ = Handle(f, H5Fclose);
  if (!appending_) {
    setAttribute("format", std::string(kResultFormat));
    setAttribute("format_version", static_cast<long>(kResultFormatVersion));
    setAttribute("scene_yaml", scene_yaml);
  }
  setAttribute("created_by", created_by);
  setAttribute("status", std::string("running"));
  time_ = &create(f, "time", 0, "s", "output times");
  Handle bodies = group(f, "bodies");
  for (int b = 0; b < system.numBodies(); ++b) {
    const BodyModel& body = system.body(b);
    Handle g = group(bodies.id(), body.name());
    h5::writeAttribute(h5::Context{path_}, g.id(), "model", body.sid().model);
    h5::writeAttribute(h5::Context{path_}, g.id(), "sid_name", body.sid().name);
    // Quasi-static coordinates (runtime/bodies/quasi_static_modes.h): their count and
    // cutoff (Hz, 0 if none); their qdot columns are zero.
    const QuasiStaticModes& qs = body.quasiStatic();
    h5::writeAttribute(h5::Context{path_}, g.id(), "quasi_static_modes", qs.size());
    h5::writeAttribute(h5::Context{path_}, g.id(), "quasi_static_cutoff_hz",
                       qs.empty() ? 0.0 : qs.cutoff_hz);
    h5::writeAttribute(h5::Context{path_}, g.id(), "quasi_static_cutoff_unit", std::string("Hz"));
    BodySeries s;
    s.position = &create(g.id(), "position", 3, "m", "reference point r_R, inertial");
    s.orientation = &create(g.id(), "orientation", 4, "1",
                            "unit quaternion (p0, p1, p2, p3), body to inertial");
    s.velocity = &create(g.id(), "velocity", 3, "m/s", "velocity of r_R, body components");
    s.angular_velocity =
        &create(g.id(), "angular_velocity", 3, "rad/s", "angular velocity, body components");
    const int nq = std::max(body.nq(), 1);
    s.q = &create(g.id(), "q", nq, "kg^(1/2) m", "elastic coordinates (mass-normalised modes)");
    s.qdot = &create(g.id(), "qdot", nq, "kg^(1/2) m/s", "elastic velocities");
    bodies_.push_back(s);
  }
  Handle contacts = group(f, "contacts");
  for (int c = 0; c < system.numContacts(); ++c) {
    const ContactPair& pair = system.contact(c);
    Handle g = group(contacts.id(), pair.name());
    h5::writeAttribute(h5::Context{path_}, g.id(), "body_a", system.body(pair.bodyA()).name());
    h5::writeAttribute(h5::Context{path_}, g.id(), "body_b", system.body(pair.bodyB()).name());
    h5::writeAttribute(h5::Context{path_}, g.id(), "penalty_factor", pair.options().penalty);
    h5::writeAttribute(h5::Context{path_}, g.id(), "penalty_factor_unit", std::string("N/m^3"));
    ContactSeries s;
    s.normal_force = &create(g.id(), "normal_force", 0, "N",
                             "magnitude of the resultant contact force on body_a "
                             "(axisymmetric: over the whole ring)");
    s.force = &create(g.id(), "force", 3, "N", "resultant contact force on body_a, inertial");
    s.max_penetration = &create(g.id(), "max_penetration", 0, "m", "largest -g_n");
    s.active_points = &create(g.id(), "active_points", 0, "1",
                              "collocation points in contact (both roles)", true);
    s.projection_failures = &create(g.id(), "projection_failures", 0, "1",
                                    "closest-point searches that did not converge", true);
    contacts_.push_back(s);
  }
  Handle energy = group(f, "energy");
  kinetic_ = &create(energy.id(), "kinetic", 0, "J", "kinetic energy, all bodies");
  elastic_ = &create(energy.id(), "elastic", 0, "J", "elastic energy 1/2 q^T Ke q, all bodies");
  contact_ = &create(energy.id(), "contact", 0, "J", "penalty energy, all contact pairs");
  gravity_ = &create(energy.id(), "gravity", 0, "J", "potential energy of gravity");
  force_elements_ = &create(energy.id(), "force_elements", 0, "J",
                            "potential energy of the force elements (springs, Hertz contact)");
  createMultibodySeries(system);
  // The restart record: the state at the last row on disk, rewritten at every flush.
  const int n = system.size();
  if (appending_) {
    restart_ = h5::openGroup(h5::Context{path_}, f, "restart");
    restart_state_ = Handle(check(H5Dopen2(restart_.id(), "state", H5P_DEFAULT), "H5Dopen2 'state'",
                                  path_),
                            H5Dclose);
    // Rows after the record's (written after its last flush, if any) are dropped.
    rows_ = written_ = resume->rows;
    restart_time_ = resume->time;
    for (auto& series : series_) {
      const hsize_t dims[2] = {static_cast<hsize_t>(rows_), static_cast<hsize_t>(std::max(series->cols, 1))};
      check(H5Dset_extent(series->dataset.id(), dims), "H5Dset_extent", path_);
    }
  } else {
    restart_ = group(f, "restart");
    const hsize_t dims[1] = {static_cast<hsize_t>(n)};
    Handle space(check(H5Screate_simple(1, dims, nullptr), "H5Screate_simple", path_), H5Sclose);
    restart_state_ = Handle(check(H5Dcreate2(restart_.id(), "state", H5T_NATIVE_DOUBLE, space.id(),
                                             H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                  "H5Dcreate2 'state'", path_),
                            H5Dclose);
    h5::writeAttribute(h5::Context{path_}, restart_state_.id(), "unit", std::string("SI"));
    h5::writeAttribute(h5::Context{path_}, restart_state_.id(), "description",
                       std::string("full state vector y at the last row on disk (the layout of "
                                   "MultibodySystem: positions, then velocities)"));
    h5::writeAttribute(h5::Context{path_}, restart_.id(), "rows", 0.0);
  }
  flush();
}

void ResultWriter::writeRestartRecord() {
  if (!resume_pending_) return;
  const h5::Context c{path_};
  check(H5Dwrite(restart_state_.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                 resume_state_.data()),
        "H5Dwrite 'restart/state'", path_);
  h5::writeAttribute(c, restart_.id(), "time_s", resume_time_);
  for (const auto& [name, value] : resume_figures_)
    h5::writeAttribute(c, restart_.id(), "figure_" + name, value);
  h5::writeAttribute(c, restart_.id(), "rows", static_cast<double>(rows_));
  resume_pending_ = false;
}

void ResultWriter::createMultibodySeries(const MultibodySystem& system) {
  const h5::Context c{path_};
  auto endName = [&](const MarkerEnd& e) {
    return e.body < 0 ? std::string("ground") : system.body(e.body).name() + "." + e.marker.name;
  };
  if (system.numJoints() > 0) {
    Handle joints = group(file_.id(), "joints");
    for (int j = 0; j < system.numJoints(); ++j) {
      const Joint& joint = system.joint(j);
      Handle g = group(joints.id(), joint.name());
      h5::writeAttribute(c, g.id(), "type", std::string(jointTypeName(joint.type())));
      h5::writeAttribute(c, g.id(), "end_a", endName(joint.end(0)));
      h5::writeAttribute(c, g.id(), "end_b", endName(joint.end(1)));
      JointSeries s;
      s.force =
          &create(g.id(), "force", 3, "N", "reaction force of the joint on end b's body, inertial");
      s.moment = &create(g.id(), "moment", 3, "N m",
                         "reaction moment of the joint on end b's body about its marker point, "
                         "inertial");
      s.violation = &create(g.id(), "violation", 0, "m or 1",
                            "largest |g| of the joint's position-level equations");
      joints_.push_back(s);
    }
  }
  if (system.numLineForces() > 0) {
    Handle forces = group(file_.id(), "force_elements");
    for (int f = 0; f < system.numLineForces(); ++f) {
      const LineForce& e = system.lineForce(f);
      Handle g = group(forces.id(), e.name());
      h5::writeAttribute(c, g.id(), "kind", std::string(e.kind()));
      h5::writeAttribute(c, g.id(), "end_a", endName(e.end(0)));
      h5::writeAttribute(c, g.id(), "end_b", endName(e.end(1)));
      LineForceSeries s;
      s.length = &create(g.id(), "length", 0, "m", "distance between the two points");
      s.rate = &create(g.id(), "rate", 0, "m/s", "rate of change of the length");
      s.tension = &create(g.id(), "tension", 0, "N",
                          "force along the line, > 0 pulling the ends together (Hertz "
                          "contact: minus the contact force)");
      s.energy = &create(g.id(), "energy", 0, "J", "potential energy");
      line_forces_.push_back(s);
    }
  }
  if (system.numSensors() > 0) {
    Handle sensors = group(file_.id(), "sensors");
    for (int i = 0; i < system.numSensors(); ++i) {
      Handle g = group(sensors.id(), system.sensor(i).name);
      h5::writeAttribute(c, g.id(), "marker", endName(system.sensor(i).end));
      SensorSeries s;
      s.position = &create(g.id(), "position", 3, "m", "marker position, inertial");
      s.velocity = &create(g.id(), "velocity", 3, "m/s", "marker velocity, inertial");
      sensors_.push_back(s);
    }
  }
}

void ResultWriter::appendMultibodyRows(const Eigen::VectorXd& y, MultibodySystem& system) {
  if (system.numJoints() > 0) {
    const std::vector<JointReaction> r = system.jointReactions(y.data());
    for (int j = 0; j < system.numJoints(); ++j) {
      appendRow(*joints_[j].force, r[j].force.data());
      appendRow(*joints_[j].moment, r[j].moment.data());
      appendRow(*joints_[j].violation, &r[j].violation);
    }
  }
  const std::vector<LineForceState> f = system.lineForceStates(y.data());
  double energy = 0.0;
  for (int i = 0; i < system.numLineForces(); ++i) {
    appendRow(*line_forces_[i].length, &f[i].length);
    appendRow(*line_forces_[i].rate, &f[i].rate);
    appendRow(*line_forces_[i].tension, &f[i].tension);
    appendRow(*line_forces_[i].energy, &f[i].energy);
    energy += f[i].energy;
  }
  appendRow(*force_elements_, &energy);
  for (int i = 0; i < system.numSensors(); ++i) {
    Eigen::Vector3d x, v;
    system.sensorState(y.data(), i, x, v);
    appendRow(*sensors_[i].position, x.data());
    appendRow(*sensors_[i].velocity, v.data());
  }
}

ResultWriter::~ResultWriter() {
  try {
    close();
  } catch (...) {
    // Destructors must not throw; close() explicitly to see errors.
  }
}

Handle ResultWriter::group(hid_t parent, const std::string& name) {
  if (appending_) return h5::openGroup(h5::Context{path_}, parent, name);
  return Handle(check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                      "H5Gcreate2 '" + name + "'", path_),
                H5Gclose);
}

ResultWriter::Series& ResultWriter::create(hid_t parent, const std::string& name, int cols,
                                           const std::string& unit, const std::string& description,
                                           bool integer) {
  auto s = std::make_unique<Series>();
  s->cols = cols;
  s->integer = integer;
  if (appending_) {  // a restart: the dataset exists and must have this shape
    s->dataset = Handle(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose);
    int found = -1;
    if (s->dataset.id() >= 0) {
      Handle space(H5Dget_space(s->dataset.id()), H5Sclose);
      hsize_t dims[2] = {0, 0};
      const int rank = H5Sget_simple_extent_dims(space.id(), dims, nullptr);
      found = rank == 1 ? 0 : rank == 2 ? static_cast<int>(dims[1]) : -2;
    }
    if (found != cols) {
      throw InputError(Str() << path_ << ": dataset '" << name << "' "
                             << (found == -1 ? "is missing" : "has another shape")
                             << ": the file was not written by this scene");
    }
    series_.push_back(std::move(s));
    return *series_.back();
  }
  const int rank = cols == 0 ? 1 : 2;
  const hsize_t dims[2] = {0, static_cast<hsize_t>(cols)};
  const hsize_t maxdims[2] = {H5S_UNLIMITED, static_cast<hsize_t>(cols)};
  const hsize_t chunk[2] = {256, static_cast<hsize_t>(std::max(cols, 1))};
  Handle space(check(H5Screate_simple(rank, dims, maxdims), "H5Screate_simple", path_), H5Sclose);
  Handle plist(check(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate", path_), H5Pclose);
  check(H5Pset_chunk(plist.id(), rank, chunk), "H5Pset_chunk", path_);
  const hid_t type = integer ? H5T_NATIVE_LONG : H5T_NATIVE_DOUBLE;
  s->dataset = Handle(check(H5Dcreate2(parent, name.c_str(), type, space.id(), H5P_DEFAULT,
                                       plist.id(), H5P_DEFAULT),
                            "H5Dcreate2 '" + name + "'", path_),
                      H5Dclose);
  h5::writeAttribute(h5::Context{path_}, s->dataset.id(), "unit", unit);
  h5::writeAttribute(h5::Context{path_}, s->dataset.id(), "description", description);
  series_.push_back(std::move(s));
  return *series_.back();
}

void ResultWriter::appendRow(Series& s, const double* row) {
  s.pending.insert(s.pending.end(), row, row + std::max(s.cols, 1));
}

void ResultWriter::writePending(Series& s) {
  const hsize_t n = static_cast<hsize_t>(std::max(s.cols, 1));
  const hsize_t count0 = s.pending.size() / n;
  if (count0 == 0) return;
  const int rank = s.cols == 0 ? 1 : 2;
  const hsize_t newDims[2] = {static_cast<hsize_t>(written_) + count0, n};
  check(H5Dset_extent(s.dataset.id(), newDims), "H5Dset_extent", path_);
  Handle fspace(check(H5Dget_space(s.dataset.id()), "H5Dget_space", path_), H5Sclose);
  const hsize_t start[2] = {static_cast<hsize_t>(written_), 0};
  const hsize_t count[2] = {count0, n};
  check(H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, start, nullptr, count, nullptr),
        "H5Sselect_hyperslab", path_);
  Handle mspace(check(H5Screate_simple(rank, count, nullptr), "H5Screate_simple", path_), H5Sclose);
  if (s.integer) {
    std::vector<long> v(s.pending.begin(), s.pending.end());
    check(
        H5Dwrite(s.dataset.id(), H5T_NATIVE_LONG, mspace.id(), fspace.id(), H5P_DEFAULT, v.data()),
        "H5Dwrite", path_);
  } else {
    check(H5Dwrite(s.dataset.id(), H5T_NATIVE_DOUBLE, mspace.id(), fspace.id(), H5P_DEFAULT,
                   s.pending.data()),
          "H5Dwrite", path_);
  }
  s.pending.clear();
}

void ResultWriter::append(double t, const Eigen::VectorXd& y, MultibodySystem& system) {
  FFRIGA_CHECK(file_.id() >= 0, "result file " << path_ << " is closed");
  appendRow(*time_, &t);
  for (int b = 0; b < system.numBodies(); ++b) {
    const BodyModel& body = system.body(b);
    const double* sp = y.data() + system.positionOffset(b);
    const double* sv = y.data() + system.velocityOffset(b);
    const BodySeries& s = bodies_[b];
    double r[3], p[4], v[3], w[3] = {0, 0, 0};
    Eigen::VectorXd q = Eigen::VectorXd::Zero(std::max(body.nq(), 1)), qd = q;
    if (const auto* ax = dynamic_cast<const AxisymmetricBody*>(&body)) {
      const double sgn = ax->axisSign();
      r[0] = 0.0, r[1] = sp[0], r[2] = 0.0;
      p[0] = sgn > 0 ? 1.0 : 0.0, p[1] = sgn > 0 ? 0.0 : 1.0, p[2] = 0.0, p[3] = 0.0;
      v[0] = 0.0, v[1] = sgn * sv[0], v[2] = 0.0;
    } else {
      Eigen::Vector4d pq(sp[3], sp[4], sp[5], sp[6]);
      pq.normalize();
      for (int i = 0; i < 3; ++i) r[i] = sp[i], v[i] = sv[i], w[i] = sv[3 + i];
      for (int i = 0; i < 4; ++i) p[i] = pq(i);
    }
    const int nr = body.numRigidPositions(), nv = body.numRigidVelocities();
    for (int j = 0; j < body.nq(); ++j) q(j) = sp[nr + j], qd(j) = sv[nv + j];
    appendRow(*s.position, r);
    appendRow(*s.orientation, p);
    appendRow(*s.velocity, v);
    appendRow(*s.angular_velocity, w);
    appendRow(*s.q, q.data());
    appendRow(*s.qdot, qd.data());
  }
  std::vector<ContactState> states;
  std::vector<Eigen::VectorXd> h;
  system.contactForces(y.data(), h, &states);
  double contactEnergy = 0.0;
  for (int c = 0; c < system.numContacts(); ++c) {
    const ContactState& st = states[c];
    const ContactSeries& s = contacts_[c];
    appendRow(*s.normal_force, &st.normal_force);
    appendRow(*s.force, st.force.data());
    appendRow(*s.max_penetration, &st.max_penetration);
    const double active = st.active_points, failures = st.projection_failures;
    appendRow(*s.active_points, &active);
    appendRow(*s.projection_failures, &failures);
    contactEnergy += st.energy;
  }
  SystemEnergies e;
  for (int b = 0; b < system.numBodies(); ++b) {
    const double* sp = y.data() + system.positionOffset(b);
    e.kinetic += system.body(b).kineticEnergy(sp, y.data() + system.velocityOffset(b));
    e.elastic += system.body(b).elasticEnergy(sp);
    e.gravity += system.body(b).gravityEnergy(sp, system.gravity());
  }
  appendRow(*kinetic_, &e.kinetic);
  appendRow(*elastic_, &e.elastic);
  appendRow(*contact_, &contactEnergy);
  appendRow(*gravity_, &e.gravity);
  appendMultibodyRows(y, system);
  if (frames_ && frames_->due(t)) frames_->append(t, y, system);
  ++rows_;
  resume_time_ = t;
  resume_state_ = y;
  resume_pending_ = true;
  if (rows_ % flush_rows_ == 0)
    flush();
  else
    flushIfDue();
}

void ResultWriter::enableFrames(const VisualisationSettings& settings,
                                const MultibodySystem& system) {
  frames_ = std::make_unique<FrameWriter>(path_, file_.id(), system, settings, restart_time_);
}

void ResultWriter::enablePeakStressLines(const MultibodySystem& system,
                                         std::vector<std::optional<HertzPartner>> partners) {
  peak_ = std::make_unique<PeakStressLines>(system, std::move(partners));
  if (peak_->empty()) peak_.reset();
}

void ResultWriter::recordPeak(double t, double force, const Eigen::VectorXd& y,
                              const MultibodySystem& system) {
  if (peak_) peak_->record(t, force, y, system);
}

void ResultWriter::flushIfDue() {
  if (rows_ == written_) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_flush_).count() >= flush_interval_) flush();
}

void ResultWriter::flush() {
  if (file_.id() < 0) return;
  for (auto& series : series_) writePending(*series);
  written_ = rows_;
  if (frames_) frames_->flush();
  if (peak_) peak_->write(h5::Context{path_}, file_.id());
  writeRestartRecord();
  check(H5Fflush(file_.id(), H5F_SCOPE_GLOBAL), "H5Fflush", path_);
  if (frames_) frames_->writeXdmf();  // refers only to frames now on disk
  last_flush_ = std::chrono::steady_clock::now();
}

void ResultWriter::setAttribute(const std::string& name, const std::string& value) {
  h5::writeAttribute(h5::Context{path_}, file_.id(), name, value);
}
void ResultWriter::setAttribute(const std::string& name, double value) {
  h5::writeAttribute(h5::Context{path_}, file_.id(), name, value);
}
void ResultWriter::setAttribute(const std::string& name, long value) {
  h5::writeAttribute(h5::Context{path_}, file_.id(), name, value);
}

void ResultWriter::setObjectAttribute(const std::string& object, const std::string& name,
                                      double value) {
  const h5::Context c{path_};
  Handle o(c.check(H5Oopen(file_.id(), object.c_str(), H5P_DEFAULT), "open " + object), H5Oclose);
  h5::writeAttribute(c, o.id(), name, value);
}
void ResultWriter::setObjectAttribute(const std::string& object, const std::string& name,
                                      const std::string& value) {
  const h5::Context c{path_};
  Handle o(c.check(H5Oopen(file_.id(), object.c_str(), H5P_DEFAULT), "open " + object), H5Oclose);
  h5::writeAttribute(c, o.id(), name, value);
}

void ResultWriter::close() {
  if (file_.id() < 0) return;
  // The record again with the run's final figures: a flush by wall time right after the
  // last row wrote the figures of the step before, and whether one happened depends on the
  // machine's speed (same input, same bits).
  if (rows_ > 0) resume_pending_ = true;
  flush();
  series_.clear();
  if (frames_) frames_written_ = frames_->frames();
  frames_.reset();  // its datasets before the file
  if (peak_) peaks_ = peak_->peaks();
  peak_.reset();
  file_.reset();
}

}  // namespace ffriga
