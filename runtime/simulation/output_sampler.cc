#include "runtime/simulation/output_sampler.h"

#include <algorithm>

#include "runtime/bodies/axisymmetric_body.h"
#include "runtime/contact/obstacle_contact.h"

namespace ffriga {

namespace {

// "BODY.MARKER" or "ground".
std::string endName(const MultibodySystem& system, const MarkerEnd& e) {
  return e.body < 0 ? std::string("ground") : system.body(e.body).name() + "." + e.marker.name;
}

// Body b's rows (the result file's terms) and pose at y.
BodySample bodySample(const MultibodySystem& system, int b, const Eigen::VectorXd& y) {
  const BodyModel& body = system.body(b);
  const double* sp = y.data() + system.positionOffset(b);
  const double* sv = y.data() + system.velocityOffset(b);
  BodySample s;
  s.q = Eigen::VectorXd::Zero(std::max(body.nq(), 1));
  s.qdot = s.q;
  if (const auto* ax = dynamic_cast<const AxisymmetricBody*>(&body)) {
    const double sgn = ax->axisSign();
    s.position = Eigen::Vector3d(0.0, sp[0], 0.0);
    s.orientation = sgn > 0 ? Eigen::Vector4d(1, 0, 0, 0) : Eigen::Vector4d(0, 1, 0, 0);
    s.velocity = Eigen::Vector3d(0.0, sgn * sv[0], 0.0);
  } else {
    Eigen::Vector4d pq(sp[3], sp[4], sp[5], sp[6]);
    pq.normalize();
    for (int i = 0; i < 3; ++i)
      s.position(i) = sp[i], s.velocity(i) = sv[i], s.angular_velocity(i) = sv[3 + i];
    s.orientation = pq;
  }
  const int nr = body.numRigidPositions(), nv = body.numRigidVelocities();
  for (int j = 0; j < body.nq(); ++j) s.q(j) = sp[nr + j], s.qdot(j) = sv[nv + j];
  const BodyPose pose = body.pose(sp);
  s.A = pose.A;
  s.origin = pose.origin;
  s.pose_q = pose.q;
  return s;
}

// The pairs' rows and the penalty energy (evaluates the pairs at y).
void sampleContacts(MultibodySystem& system, const Eigen::VectorXd& y, OutputSample& out) {
  std::vector<ContactState> states;
  std::vector<Eigen::VectorXd> h;
  system.contactForces(y.data(), h, &states);
  for (int c = 0; c < system.numContacts(); ++c) {
    const ContactState& st = states[c];
    ContactSample s;
    s.normal_force = st.normal_force;
    s.force = st.force;
    s.max_penetration = st.max_penetration;
    s.active_points = st.active_points;
    s.projection_failures = st.projection_failures;
    s.tangential_force = st.tangential_force;
    s.sticking_points = st.sticking_points;
    s.slipping_points = st.slipping_points;
    out.contacts.push_back(s);
    out.energy.contact += st.energy;
  }
}

// Joints' reactions, force elements' states and their energy, sensors.
void sampleMultibody(MultibodySystem& system, const Eigen::VectorXd& y, OutputSample& out) {
  if (system.numJoints() > 0) {
    for (const JointReaction& r : system.jointReactions(y.data())) {
      JointSample s;
      s.force = r.force, s.moment = r.moment, s.violation = r.violation;
      s.quasi_static_offset = r.quasi_static_offset;
      out.joints.push_back(s);
    }
  }
  const std::vector<LineForceState> f = system.lineForceStates(y.data());
  for (int i = 0; i < system.numLineForces(); ++i) {
    out.force_elements.push_back({f[i].length, f[i].rate, f[i].tension, f[i].energy});
    out.energy.force_elements += f[i].energy;
  }
  for (int i = 0; i < system.numSensors(); ++i) {
    SensorSample s;
    system.sensorState(y.data(), i, s.position, s.velocity);
    out.sensors.push_back(s);
  }
}

}  // namespace

OutputLayout outputLayout(const MultibodySystem& system) {
  OutputLayout layout;
  for (int b = 0; b < system.numBodies(); ++b) {
    const BodyModel& body = system.body(b);
    const QuasiStaticModes& qs = body.quasiStatic();
    layout.bodies.push_back(
        {body.name(), body.sharedSid(), body.nq(), qs.size(), qs.empty() ? 0.0 : qs.cutoff_hz,
         qs.held_by_joints});
  }
  for (int c = 0; c < system.numContacts(); ++c) {
    const SurfaceContact& pair = system.contact(c);
    ConnectionLayout l{pair.name(), "contact", system.contactSideName(c, 0),
                       system.contactSideName(c, 1), pair.options().penalty};
    l.region_a = pair.regionName(0);
    l.region_b = pair.regionName(1);
    l.collocation_role = pair.pressureField().role;
    l.collocation_weight = pair.pressureField().weight;
    l.role_factor = pair.pressureField().factor;
    l.friction_coefficient = pair.options().friction.coefficient;
    l.slip_velocity = pair.options().friction.slip_velocity;
    if (pair.options().friction.anchored)
      l.stick_relaxation_time = pair.options().friction.relaxation_time;
    if (const auto* o = dynamic_cast<const ObstacleContact*>(&pair)) {
      l.obstacle_shape = o->obstacle().shapeName();
      l.obstacle_point = o->obstacle().point();
      l.obstacle_normal = o->obstacle().normal();
      l.obstacle_radius = o->obstacle().radius();
    }
    layout.contacts.push_back(std::move(l));
  }
  for (int j = 0; j < system.numJoints(); ++j) {
    const Joint& joint = system.joint(j);
    layout.joints.push_back({joint.name(), jointTypeName(joint.type()),
                             endName(system, joint.end(0)), endName(system, joint.end(1)), 0.0});
  }
  for (int f = 0; f < system.numLineForces(); ++f) {
    const LineForce& e = system.lineForce(f);
    layout.force_elements.push_back(
        {e.name(), e.kind(), endName(system, e.end(0)), endName(system, e.end(1)), 0.0});
  }
  for (int i = 0; i < system.numSensors(); ++i)
    layout.sensors.push_back({system.sensor(i).name, endName(system, system.sensor(i).end)});
  layout.state_size = system.size();
  return layout;
}

std::vector<BodySample> bodySamples(const MultibodySystem& system, const Eigen::VectorXd& y) {
  std::vector<BodySample> out;
  for (int b = 0; b < system.numBodies(); ++b) out.push_back(bodySample(system, b, y));
  return out;
}

PressureSample pressureSample(const MultibodySystem& system, int c) {
  const ContactPressure& p = system.contact(c).pressureField();
  return {p.position, p.pressure, p.normal, p.traction};
}

OutputSample outputSample(MultibodySystem& system, double t, const Eigen::VectorXd& y) {
  OutputSample out;
  out.time = t;
  out.state = y;
  out.bodies = bodySamples(system, y);
  sampleContacts(system, y, out);
  for (int b = 0; b < system.numBodies(); ++b) {
    const double* sp = y.data() + system.positionOffset(b);
    out.energy.kinetic += system.body(b).kineticEnergy(sp, y.data() + system.velocityOffset(b));
    out.energy.elastic += system.body(b).elasticEnergy(sp);
    out.energy.gravity += system.body(b).gravityEnergy(sp, system.gravity());
  }
  sampleMultibody(system, y, out);
  return out;
}

}  // namespace ffriga
