// What the outputs of a run see of the multibody system: its layout once (the bodies with
// their SIDs, the contact pairs, joints, force elements and sensors, by name) and a sample
// at every output row (the state in the result file's terms, the pairs', joints' and force
// elements' quantities, the energies). The simulation forms both from the system
// (runtime/simulation/output_sampler.h) and hands them to the outputs through one
// interface (runtime/output/output_sink.h); the outputs know nothing of the system.
// Units as in the result file (schemas/result_format.md): SI.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "common/sid/sid.h"

namespace ffriga {

// One body of the system as the outputs name and draw it.
struct BodyLayout {
  std::string name;
  std::shared_ptr<const FlexibleBodySid> sid;  // model, mesh, stress lines, geometry
  int nq = 0;                                  // elastic coordinates (0: rigid or frozen)
  int quasi_static_modes = 0;                  // of them quasi-static
  double quasi_static_cutoff_hz = 0.0;         // Hz, 0 if none
  int quasi_static_held_by_joints = 0;         // above the cutoff, kept dynamic by joints
};

// A contact pair, a joint or a force element between two bodies (or a body and the ground).
struct ConnectionLayout {
  ConnectionLayout(std::string name_, std::string kind_, std::string a, std::string b,
                   double penalty = 0.0)
      : name(std::move(name_)), kind(std::move(kind_)), end_a(std::move(a)), end_b(std::move(b)),
        penalty_factor(penalty) {}
  std::string name;
  std::string kind;  // joint type, force element kind ("contact" for pairs)
  std::string end_a, end_b;  // body names (pairs) or BODY.MARKER / ground (joints, forces)
  std::string region_a, region_b;  // contact pairs: the bodies' contact regions ("": none)
  double penalty_factor = 0.0;  // contact pairs: c_p, N/m^3
  // Contact pairs with friction (runtime/contact/coulomb_friction.h): mu > 0 and eps (m/s).
  double friction_coefficient = 0.0, slip_velocity = 0.0;
  double stick_relaxation_time = 0.0;  // s; > 0: friction_law anchored (stick anchors)
  // A pair with a rigid obstacle (end_b): its shape ("plane", "sphere"; empty for two
  // bodies), point (plane: p, sphere: centre; m, inertial), normal (plane) and radius (m;
  // plane: 0 where infinite).
  std::string obstacle_shape;
  Eigen::Vector3d obstacle_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d obstacle_normal = Eigen::Vector3d::Zero();
  double obstacle_radius = 0.0;
  // Contact pairs: the role of each collocation point (0: body A's points against B, 1: B's
  // against A), its collocation weight w_i (m^2) and the roles' factor (1/2 where both roles
  // are averaged, else 1): the rows of the pair's PressureSample
  // (runtime/contact/contact_pressure.h).
  std::vector<int> collocation_role;
  Eigen::VectorXd collocation_weight;
  double role_factor = 1.0;
};

struct SensorLayout {
  std::string name;
  std::string marker;  // BODY.MARKER
};

struct OutputLayout {
  std::vector<BodyLayout> bodies;
  std::vector<ConnectionLayout> contacts, joints, force_elements;
  std::vector<SensorLayout> sensors;
  int state_size = 0;  // entries of the state vector y
};

// One body at one moment: the result file's rows (position and velocity of the frame
// origin, orientation, elastic coordinates) and the pose that maps body points into the
// contact space (3D, or the meridian plane of an axisymmetric body): world = origin + A x.
struct BodySample {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();          // m, inertial
  Eigen::Vector4d orientation = Eigen::Vector4d(1, 0, 0, 0);   // unit quaternion
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // m/s, body components
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, body components
  Eigen::VectorXd q, qdot;  // max(nq, 1) entries (a zero for rigid bodies)
  Eigen::MatrixXd A;        // d x d, body -> world
  Eigen::VectorXd origin;   // d, m
  Eigen::VectorXd pose_q;   // nq: the pose's elastic coordinates (empty if none)
};

struct ContactSample {
  double normal_force = 0.0;                        // N, on the pair's first body
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, inertial
  double max_penetration = 0.0;                     // m
  double active_points = 0.0;                       // count
  double projection_failures = 0.0;                 // count
  // With friction: the tangential part of `force` (N, inertial), the active points that
  // stick and slip (counts).
  Eigen::Vector3d tangential_force = Eigen::Vector3d::Zero();
  double sticking_points = 0.0, slipping_points = 0.0;
};

// A contact pair's pressure field at one state (runtime/contact/contact_pressure.h), one row
// per collocation point as ConnectionLayout::collocation_role.
struct PressureSample {
  Eigen::MatrixXd position;  // n x 3, m, inertial (axisymmetric: x the radius, y the axis)
  Eigen::VectorXd pressure;  // n, Pa: c_p max(0, -g_n)
  Eigen::MatrixXd normal;    // n x 3, the target's unit outward normal (0 where no pressure)
  Eigen::MatrixXd traction;  // n x 3, Pa: tangential (friction) traction, 0 without friction
};

struct JointSample {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // N, on end b's body, inertial
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // N m, about end b's marker point
  double violation = 0.0;                            // m or 1
  double quasi_static_offset = 0.0;                  // m (JointReaction)
};

struct ForceElementSample {
  double length = 0.0, rate = 0.0, tension = 0.0, energy = 0.0;  // m, m/s, N, J
};

struct SensorSample {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m, inertial
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s, inertial
};

struct EnergySample {
  double kinetic = 0.0, elastic = 0.0, contact = 0.0, gravity = 0.0, force_elements = 0.0;  // J
  // J, the energy modal damping and dampers took out since t = 0 (the time integral of
  // MultibodySystem::dissipationPower, accumulated by the time loop).
  double dissipated = 0.0;
};

struct OutputSample {
  double time = 0.0;  // s
  Eigen::VectorXd state;  // the full state vector y (the restart record keeps it)
  std::vector<BodySample> bodies;
  std::vector<ContactSample> contacts;
  std::vector<JointSample> joints;
  std::vector<ForceElementSample> force_elements;
  std::vector<SensorSample> sensors;
  EnergySample energy;
};

}  // namespace ffriga
