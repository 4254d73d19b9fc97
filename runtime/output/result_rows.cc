#include "runtime/output/result_rows.h"

#include <algorithm>

namespace ffriga {

namespace {

// The group of one joint or force element under `parent`: its kind (attribute `kindKey`:
// joints say "type", force elements "kind", schemas/result_format.md) and its two ends.
h5::Handle connectionGroup(ResultFile& file, hid_t parent, const ConnectionLayout& e,
                           const char* kindKey) {
  const h5::Context c = file.context();
  h5::Handle g = file.group(parent, e.name);
  h5::writeAttribute(c, g.id(), kindKey, e.kind);
  h5::writeAttribute(c, g.id(), "end_a", e.end_a);
  h5::writeAttribute(c, g.id(), "end_b", e.end_b);
  return g;
}

}  // namespace

ResultRows::ResultRows(ResultFile& file, const OutputLayout& layout) : file_(file) {
  time_ = &file_.series(file_.id(), "time", 0, "s", "output times");
  createBodies(layout);
  createContacts(layout);
  createEnergies();
  createJoints(layout);
  createForceElements(layout);
}

void ResultRows::createBodies(const OutputLayout& layout) {
  const h5::Context c = file_.context();
  h5::Handle bodies = file_.group(file_.id(), "bodies");
  for (const BodyLayout& body : layout.bodies) {
    h5::Handle g = file_.group(bodies.id(), body.name);
    h5::writeAttribute(c, g.id(), "model", std::string(toString(body.sid->model)));
    h5::writeAttribute(c, g.id(), "sid_name", body.sid->name);
    // Quasi-static coordinates (runtime/bodies/quasi_static_modes.h): their count and
    // cutoff (Hz, 0 if none), and those above it that joints keep dynamic; their qdot
    // columns are zero.
    h5::writeAttribute(c, g.id(), "quasi_static_modes", body.quasi_static_modes);
    h5::writeAttribute(c, g.id(), "quasi_static_cutoff_hz", body.quasi_static_cutoff_hz);
    h5::writeAttribute(c, g.id(), "quasi_static_cutoff_unit", std::string("Hz"));
    h5::writeAttribute(c, g.id(), "quasi_static_held_by_joints", body.quasi_static_held_by_joints);
    BodySeries s;
    s.position = &file_.series(g.id(), "position", 3, "m", "reference point r_R, inertial");
    s.orientation = &file_.series(g.id(), "orientation", 4, "1",
                                  "unit quaternion (p0, p1, p2, p3), body to inertial");
    s.velocity = &file_.series(g.id(), "velocity", 3, "m/s", "velocity of r_R, body components");
    s.angular_velocity = &file_.series(g.id(), "angular_velocity", 3, "rad/s",
                                       "angular velocity, body components");
    const int nq = std::max(body.nq, 1);
    s.q = &file_.series(g.id(), "q", nq, "kg^(1/2) m", "elastic coordinates (mass-normalised modes)");
    s.qdot = &file_.series(g.id(), "qdot", nq, "kg^(1/2) m/s", "elastic velocities");
    bodies_.push_back(s);
  }
}

namespace {

// A pair's description (attributes and the obstacle's data), written once when the file is
// created (a restart appends rows to what is there: writing the obstacle's datasets again
// failed, and every restart of a run with an obstacle with it).
void writeContactDescription(const h5::Context& c, hid_t g, const ConnectionLayout& pair) {
  h5::writeAttribute(c, g, "body_a", pair.end_a);
  h5::writeAttribute(c, g, "body_b", pair.end_b);
  h5::writeAttribute(c, g, "region_a", pair.region_a);
  if (!pair.region_b.empty()) h5::writeAttribute(c, g, "region_b", pair.region_b);
  h5::writeAttribute(c, g, "penalty_factor", pair.penalty_factor);
  h5::writeAttribute(c, g, "penalty_factor_unit", std::string("N/m^3"));
  if (pair.friction_coefficient > 0.0) {
    h5::writeAttribute(c, g, "friction_coefficient", pair.friction_coefficient);
    h5::writeAttribute(c, g, "friction_law",
                       std::string(pair.stick_relaxation_time > 0.0 ? "anchored" : "regularised"));
    if (pair.stick_relaxation_time > 0.0)
      h5::writeAttribute(c, g, "stick_relaxation_time_s", pair.stick_relaxation_time);
    else
      h5::writeAttribute(c, g, "slip_velocity_m_s", pair.slip_velocity);
  }
  if (!pair.obstacle_shape.empty()) {  // body_b is a rigid obstacle fixed in space
    h5::writeAttribute(c, g, "obstacle_shape", pair.obstacle_shape);
    h5::writeAttribute(c, g, "obstacle_radius_m", pair.obstacle_radius);
    h5::writeVector(c, g, "obstacle_point", pair.obstacle_point, "m");
    if (pair.obstacle_shape == "plane")
      h5::writeVector(c, g, "obstacle_normal", pair.obstacle_normal, "1");
    if (pair.obstacle_shape == "cylinder")
      h5::writeVector(c, g, "obstacle_axis", pair.obstacle_normal, "1");
  }
}

}  // namespace

void ResultRows::createContacts(const OutputLayout& layout) {
  const h5::Context c = file_.context();
  h5::Handle contacts = file_.group(file_.id(), "contacts");
  for (const ConnectionLayout& pair : layout.contacts) {
    h5::Handle g = file_.group(contacts.id(), pair.name);
    if (!file_.appending()) writeContactDescription(c, g.id(), pair);
    ContactSeries s;
    s.normal_force = &file_.series(g.id(), "normal_force", 0, "N",
                                   "magnitude of the resultant normal contact force on "
                                   "body_a (axisymmetric: over the whole ring; with "
                                   "friction, force less tangential_force)");
    s.force = &file_.series(g.id(), "force", 3, "N", "resultant contact force on body_a, inertial");
    s.max_penetration = &file_.series(g.id(), "max_penetration", 0, "m", "largest -g_n");
    s.active_points = &file_.series(g.id(), "active_points", 0, "1",
                                    "collocation points in contact (both roles)", true);
    s.projection_failures = &file_.series(g.id(), "projection_failures", 0, "1",
                                          "closest-point searches that did not converge", true);
    if (pair.friction_coefficient > 0.0) {
      s.tangential_force = &file_.series(g.id(), "tangential_force", 3, "N",
                                         "friction: the tangential part of force, inertial");
      s.sticking_points = &file_.series(g.id(), "sticking_points", 0, "1",
                                        "active points slipping slower than slip_velocity", true);
      s.slipping_points = &file_.series(g.id(), "slipping_points", 0, "1",
                                        "active points slipping at slip_velocity or faster", true);
    }
    contacts_.push_back(s);
  }
}

void ResultRows::createEnergies() {
  h5::Handle energy = file_.group(file_.id(), "energy");
  kinetic_ = &file_.series(energy.id(), "kinetic", 0, "J", "kinetic energy, all bodies");
  elastic_ = &file_.series(energy.id(), "elastic", 0, "J", "elastic energy 1/2 q^T Ke q, all bodies");
  contact_ = &file_.series(energy.id(), "contact", 0, "J", "penalty energy, all contact pairs");
  gravity_ = &file_.series(energy.id(), "gravity", 0, "J", "potential energy of gravity");
  force_energy_ = &file_.series(energy.id(), "force_elements", 0, "J",
                                "potential energy of the force elements (springs, Hertz contact)");
  dissipated_ = &file_.series(energy.id(), "dissipated", 0, "J",
                              "energy taken out by modal damping, dampers and friction since "
                              "t = 0");
}

void ResultRows::createJoints(const OutputLayout& layout) {
  if (layout.joints.empty()) return;
  h5::Handle joints = file_.group(file_.id(), "joints");
  for (const ConnectionLayout& joint : layout.joints) {
    const h5::Handle g = connectionGroup(file_, joints.id(), joint, "type");
    JointSeries s;
    s.force = &file_.series(g.id(), "force", 3, "N",
                            "reaction force of the joint on end b's body, inertial");
    s.moment = &file_.series(g.id(), "moment", 3, "N m",
                             "reaction moment of the joint on end b's body about its marker "
                             "point, inertial");
    s.violation = &file_.series(g.id(), "violation", 0, "m or 1",
                                "largest |g| of the joint's position-level equations");
    s.quasi_static_offset =
        &file_.series(g.id(), "quasi_static_offset", 0, "m",
                      "largest displacement of the joint's marker points by their bodies' "
                      "quasi-static coordinates, which the joint does not hold");
    joints_.push_back(s);
  }
}

void ResultRows::createForceElements(const OutputLayout& layout) {
  if (layout.force_elements.empty()) return;
  h5::Handle forces = file_.group(file_.id(), "force_elements");
  for (const ConnectionLayout& e : layout.force_elements) {
    const h5::Handle g = connectionGroup(file_, forces.id(), e, "kind");
    ForceElementSeries s;
    s.length = &file_.series(g.id(), "length", 0, "m", "distance between the two points");
    s.rate = &file_.series(g.id(), "rate", 0, "m/s", "rate of change of the length");
    s.tension = &file_.series(g.id(), "tension", 0, "N",
                              "force along the line, > 0 pulling the ends together (Hertz "
                              "contact: minus the contact force)");
    s.energy = &file_.series(g.id(), "energy", 0, "J", "potential energy");
    force_elements_.push_back(s);
  }
}

void ResultRows::write(const OutputSample& sample) {
  time_->append(&sample.time);
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const BodySample& body = sample.bodies[b];
    bodies_[b].position->append(body.position.data());
    bodies_[b].orientation->append(body.orientation.data());
    bodies_[b].velocity->append(body.velocity.data());
    bodies_[b].angular_velocity->append(body.angular_velocity.data());
    bodies_[b].q->append(body.q.data());
    bodies_[b].qdot->append(body.qdot.data());
  }
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    const ContactSample& pair = sample.contacts[c];
    contacts_[c].normal_force->append(&pair.normal_force);
    contacts_[c].force->append(pair.force.data());
    contacts_[c].max_penetration->append(&pair.max_penetration);
    contacts_[c].active_points->append(&pair.active_points);
    contacts_[c].projection_failures->append(&pair.projection_failures);
    if (contacts_[c].tangential_force) {
      contacts_[c].tangential_force->append(pair.tangential_force.data());
      contacts_[c].sticking_points->append(&pair.sticking_points);
      contacts_[c].slipping_points->append(&pair.slipping_points);
    }
  }
  kinetic_->append(&sample.energy.kinetic);
  elastic_->append(&sample.energy.elastic);
  contact_->append(&sample.energy.contact);
  gravity_->append(&sample.energy.gravity);
  force_energy_->append(&sample.energy.force_elements);
  dissipated_->append(&sample.energy.dissipated);
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    joints_[j].force->append(sample.joints[j].force.data());
    joints_[j].moment->append(sample.joints[j].moment.data());
    joints_[j].violation->append(&sample.joints[j].violation);
    joints_[j].quasi_static_offset->append(&sample.joints[j].quasi_static_offset);
  }
  for (std::size_t f = 0; f < force_elements_.size(); ++f) {
    const ForceElementSample& e = sample.force_elements[f];
    force_elements_[f].length->append(&e.length);
    force_elements_[f].rate->append(&e.rate);
    force_elements_[f].tension->append(&e.tension);
    force_elements_[f].energy->append(&e.energy);
  }
}

}  // namespace ffriga
