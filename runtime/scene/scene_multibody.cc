#include "runtime/scene/scene_multibody.h"

#include <cmath>
#include <set>

#include "runtime/bodies/marker_kinematics.h"
#include "runtime/bodies/rotation.h"
#include "runtime/scene/scene_values.h"
#include "runtime/forces/hertz_point_contact.h"
#include "runtime/forces/spring_damper.h"

namespace ffriga {

namespace {

// Orthonormal joint axes with e3 along `axis`: e1 the inertial axis least aligned with it,
// made orthogonal (deterministic, so results do not depend on anything but the input).
Eigen::Matrix3d axesAlong(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d e3 = axis.normalized();
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(e3(i)) < std::abs(e3(k))) k = i;
  Eigen::Vector3d e1 = Eigen::Vector3d::Unit(k) - e3(k) * e3;
  e1.normalize();
  Eigen::Matrix3d E;
  E << e1, e3.cross(e1), e3;
  return E;
}

// Reads one end {body, marker | position} of a joint or force element.
// A sensor (`axisymmetric_ok`) may sit on an axisymmetric body; joints and force elements
// may not.
MarkerEnd readEnd(const YamlDocument& doc, const YAML::Node& node, const std::string& key,
                  const std::map<std::string, int>& index, const BodyMarkers& markers,
                  const MultibodySystem& sys, const Eigen::Vector3d* groundDefault,
                  bool axisymmetric_ok = false) {
  MarkerEnd e;
  const std::string body = getString(doc, node["body"], key + ".body");
  if (body == "ground") {
    if (node["marker"])
      throw inputError(doc, node["marker"], key + ".marker",
                       "the ground has no markers: give 'position'");
    e.body = -1;
    const Eigen::Vector3d x = node["position"] ? vector3(doc, node["position"], key + ".position")
                              : groundDefault  ? *groundDefault
                                               : Eigen::Vector3d::Zero();
    e.marker = fixedMarker("ground", x);
    return e;
  }
  const auto it = index.find(body);
  if (it == index.end()) {
    std::string known = "ground";
    for (const auto& kv : index) known += ", " + kv.first;
    throw inputError(doc, node["body"], key + ".body",
                     Str() << "expected 'ground' or the name of a body of this scene (" << known
                           << "), found '" << body << "'");
  }
  e.body = it->second;
  e.model = dynamic_cast<const FloatingBody3d*>(&sys.body(e.body));
  if (!e.model && !axisymmetric_ok)
    throw inputError(doc, node["body"], key + ".body",
                     Str() << "body '" << body << "' is axisymmetric: joints and force elements "
                           << "need 3D or rigid bodies");
  if (node["position"])
    throw inputError(doc, node["position"], key + ".position",
                     "a body's end is one of its markers: give 'marker', not 'position'");
  if (!node["marker"])
    throw inputError(doc, node, key,
                     Str() << "expected 'marker' (a marker of body '" << body << "')");
  const std::string name = getString(doc, node["marker"], key + ".marker");
  const auto& own = markers[e.body];
  const auto m = own.find(name);
  if (m == own.end()) {
    std::string known;
    for (const auto& kv : own) known += (known.empty() ? "" : ", ") + kv.first;
    throw inputError(doc, node["marker"], key + ".marker",
                     Str() << "body '" << body << "' has no marker '" << name
                           << "' (it has: " << (known.empty() ? "none" : known) << ")");
  }
  e.marker = m->second;
  return e;
}

// Initial inertial position of an end's marker point (undeformed q as given).
Eigen::Vector3d endPosition(const MarkerEnd& e, const std::vector<InitialPose>& pose) {
  if (e.body < 0) return e.marker.x0;
  const InitialPose& p = pose[e.body];
  Eigen::Vector3d x = e.marker.x0;
  if (e.marker.Phi.cols() > 0) x += e.marker.Phi * p.q;
  return p.r + p.A * x;
}

// The name (unique among `names`, default PREFIX_i) and the two ends of a joint or force
// element N: end b a body's marker, end a a marker or the ground (default point: end b's),
// on two different bodies.
struct Connection {
  std::string name;
  MarkerEnd a, b;
};

Connection readConnection(const YamlDocument& doc, const YAML::Node& N, const std::string& k,
                          const std::string& prefix, std::size_t i, std::set<std::string>& names,
                          const std::map<std::string, int>& index, const BodyMarkers& markers,
                          const MultibodySystem& sys, const std::vector<InitialPose>& pose) {
  Connection c;
  c.name = N["name"] ? getString(doc, N["name"], k + ".name") : Str() << prefix << "_" << i;
  if (!names.insert(c.name).second)
    throw inputError(doc, N["name"], k + ".name", Str() << "name '" << c.name << "' is used twice");
  c.b = readEnd(doc, N["b"], k + ".b", index, markers, sys, nullptr);
  if (c.b.body < 0)
    throw inputError(doc, N["b"], k + ".b", "end b must be a body; put the ground at end a");
  const Eigen::Vector3d rb = endPosition(c.b, pose);
  c.a = readEnd(doc, N["a"], k + ".a", index, markers, sys, &rb);
  if (c.a.body == c.b.body)
    throw inputError(doc, N["b"], k + ".b",
                     Str() << "a " << prefix << " connects two different bodies; both ends are on '"
                           << sys.body(c.b.body).name() << "'");
  return c;
}

}  // namespace

BodyMarkers collectMarkers(const YamlDocument& doc, const MultibodySystem& sys) {
  BodyMarkers out(sys.numBodies());
  const YAML::Node bodies = doc.root["bodies"];
  for (int b = 0; b < sys.numBodies(); ++b) {
    const BodyModel& body = sys.body(b);
    const std::string k = Str() << "bodies[" << b << "]";
    for (const Marker& m : body.sid().markers)
      out[b].emplace(m.name, markerFromSid(body.sid(), m, body.nq()));
    const YAML::Node list = bodies[b]["markers"];
    for (std::size_t i = 0; list && i < list.size(); ++i) {
      const std::string key = Str() << k << ".markers[" << i << "]";
      if (body.nq() > 0)
        throw inputError(doc, list[i], key,
                         Str() << "body '" << body.name() << "' is flexible: its markers come "
                               << "from its SID (body file 'markers'); scene markers are for "
                               << "rigid and frozen bodies");
      const std::string name = getString(doc, list[i]["name"], key + ".name");
      if (!out[b]
               .emplace(name,
                        fixedMarker(name, vector3(doc, list[i]["position"], key + ".position")))
               .second)
        throw inputError(
            doc, list[i]["name"], key + ".name",
            Str() << "body '" << body.name() << "' already has a marker '" << name << "'");
    }
  }
  return out;
}

std::vector<double> addJoints(const YamlDocument& doc, const std::map<std::string, int>& index,
                              const BodyMarkers& markers, const std::vector<InitialPose>& pose,
                              MultibodySystem& sys) {
  std::vector<double> angles;
  const YAML::Node joints = doc.root["joints"];
  const int first = sys.numJoints();
  std::set<std::string> names;
  for (std::size_t j = 0; joints && j < joints.size(); ++j) {
    const YAML::Node J = joints[j];
    const std::string k = Str() << "joints[" << j << "]";
    Connection c = readConnection(doc, J, k, "joint", j, names, index, markers, sys, pose);
    const std::string& name = c.name;
    const JointType type = getKind<JointType>(doc, J["type"], k + ".type");
    const char* typeName = jointTypeName(type);
    MarkerEnd& a = c.a;
    MarkerEnd& b = c.b;
    // The quasi-static coordinates that carry the markers' flexibility keep their inertia
    // (jointHeldCoordinates, runtime/bodies/body_marker.h; schemas/multibody.md "Joints and
    // quasi-static coordinates").
    for (const MarkerEnd* e : {&a, &b}) {
      if (e->body < 0) continue;
      BodyModel& body = sys.body(e->body);
      body.keepDynamic(jointHeldCoordinates(e->marker, body.stiffnessDiagonal(),
                                            body.quasiStatic().index,
                                            type != JointType::kSpherical));
    }
    const bool needsAxis = type == JointType::kRevolute || type == JointType::kPrismatic;
    if (needsAxis && !J["axis"])
      throw inputError(doc, J, k, Str() << "a " << typeName << " joint needs 'axis'");
    if (!needsAxis && J["axis"])
      throw inputError(doc, J["axis"], k + ".axis",
                       Str() << "a " << typeName << " joint has no axis");
    Eigen::Matrix3d E = Eigen::Matrix3d::Identity();
    if (needsAxis) {
      const Eigen::Vector3d axis = vector3(doc, J["axis"], k + ".axis");
      if (!(axis.norm() > 0.0))
        throw inputError(doc, J["axis"], k + ".axis", "expected a non-zero vector");
      E = axesAlong(axis);
    }
    const bool rotational = type != JointType::kSpherical;
    for (const MarkerEnd* e : {&a, &b}) {
      if (rotational && !e->marker.rotation_modes)
        throw inputError(doc, J[e == &a ? "a" : "b"], k + (e == &a ? ".a" : ".b"),
                         Str() << "a " << typeName << " joint constrains rotations, and marker '"
                               << e->marker.name << "' of flexible body '"
                               << sys.body(e->body).name() << "' has no rotation modes in its SID");
    }
    if (type != JointType::kRevolute && isGiven(doc, J["initial_angle"]))
      throw inputError(doc, J["initial_angle"], k + ".initial_angle",
                       "initial_angle is for revolute joints");
    angles.push_back(getDouble(doc, J["initial_angle"], k + ".initial_angle"));
    const Eigen::Matrix3d Aa = a.body >= 0 ? pose[a.body].A : Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d Ab = pose[b.body].A;
    auto joint = std::make_unique<Joint>(name, type, std::move(a), std::move(b));
    joint->setAxes(E, Aa, Ab);
    sys.addJoint(std::move(joint));
  }
  // Once every joint has held its coordinates, each detaches the rest from its markers.
  for (int j = first; j < sys.numJoints(); ++j)
    for (int i = 0; i < 2; ++i) {
      JointEnd& e = sys.joint(j).end(i);
      if (e.body >= 0) detachQuasiStatic(e, sys.body(e.body).quasiStatic().index);
    }
  return angles;
}

void addForceElements(const YamlDocument& doc, const std::map<std::string, int>& index,
                      const BodyMarkers& markers, const std::vector<InitialPose>& pose,
                      MultibodySystem& sys) {
  const YAML::Node list = doc.root["force_elements"];
  std::set<std::string> names;
  for (std::size_t f = 0; list && f < list.size(); ++f) {
    const YAML::Node F = list[f];
    const std::string k = Str() << "force_elements[" << f << "]";
    Connection c = readConnection(doc, F, k, "force", f, names, index, markers, sys, pose);
    const std::string& name = c.name;
    MarkerEnd& a = c.a;
    MarkerEnd& b = c.b;
    const Eigen::Vector3d rb = endPosition(b, pose);
    const double l0 = (rb - endPosition(a, pose)).norm();
    const std::string type = getString(doc, F["type"], k + ".type");
    auto forbid = [&](const char* key) {
      if (isGiven(doc, F[key]))
        throw inputError(doc, F[key], k + "." + key,
                         Str() << "'" << key << "' is not a key of " << type);
    };
    if (type == "spring_damper") {
      forbid("spheres");
      if (!F["stiffness"]) throw inputError(doc, F, k, "a spring_damper needs 'stiffness' (N/m)");
      const double stiff = getDouble(doc, F["stiffness"], k + ".stiffness");
      const double damp = getDouble(doc, F["damping"], k + ".damping");
      const double free =
          F["free_length"] ? getDouble(doc, F["free_length"], k + ".free_length") : l0;
      sys.addForceElement(
          std::make_unique<SpringDamper>(name, std::move(a), std::move(b), stiff, damp, free));
    } else {  // hertz_contact (schema enum)
      for (const char* key : {"stiffness", "damping", "free_length"}) forbid(key);
      if (!F["spheres"])
        throw inputError(doc, F, k,
                         "a hertz_contact needs 'spheres' (radius and material of each)");
      HertzSphere s[2];
      for (int i = 0; i < 2; ++i) {
        const YAML::Node S = F["spheres"][i];
        const std::string ks = Str() << k << ".spheres[" << i << "]";
        s[i].radius = getDouble(doc, S["radius"], ks + ".radius");
        s[i].youngs_modulus = getDouble(doc, S["youngs_modulus"], ks + ".youngs_modulus");
        s[i].poisson_ratio = getDouble(doc, S["poisson_ratio"], ks + ".poisson_ratio");
        s[i].mass = 1.0;  // not used by the law
      }
      if (!(l0 > 0.0))
        throw inputError(doc, F["b"], k + ".b", "the two sphere centres coincide initially");
      sys.addForceElement(
          std::make_unique<HertzPointContact>(name, std::move(a), std::move(b), s[0], s[1]));
    }
  }
}

void addSensors(const YamlDocument& doc, const std::map<std::string, int>& index,
                const BodyMarkers& markers, MultibodySystem& sys) {
  const YAML::Node list = doc.root["sensors"];
  std::set<std::string> names;
  for (std::size_t i = 0; list && i < list.size(); ++i) {
    const std::string k = Str() << "sensors[" << i << "]";
    const std::string name = getString(doc, list[i]["name"], k + ".name");
    if (!names.insert(name).second)
      throw inputError(doc, list[i]["name"], k + ".name",
                       Str() << "sensor name '" << name << "' is used twice");
    const std::string body = getString(doc, list[i]["body"], k + ".body");
    if (body == "ground")
      throw inputError(doc, list[i]["body"], k + ".body",
                       "a sensor sits on a body, not the ground");
    YAML::Node end;
    end["body"] = list[i]["body"];
    end["marker"] = list[i]["marker"];
    Sensor s{name, readEnd(doc, end, k, index, markers, sys, nullptr, true)};
    sys.addSensor(std::move(s));
  }
}

void applyInitialAngles(const YamlDocument& doc, const MultibodySystem& sys,
                        const std::vector<double>& angles, std::vector<InitialPose>& pose) {
  const int nb = sys.numBodies(), nj = sys.numJoints();
  for (int j = 0; j < nj; ++j) {
    if (angles[j] == 0.0) continue;
    const std::string k = Str() << "joints[" << j << "]";
    const Joint& joint = sys.joint(j);
    const int a = joint.end(0).body, b = joint.end(1).body;
    // End b's side: the bodies reached from b by the other joints, never crossing this one.
    std::vector<bool> side(nb, false);
    std::vector<int> stack{b};
    side[b] = true;
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      for (int i = 0; i < nj; ++i) {
        if (i == j) continue;
        const int e0 = sys.joint(i).end(0).body, e1 = sys.joint(i).end(1).body;
        if (e0 != c && e1 != c) continue;
        const int other = e0 == c ? e1 : e0;
        if (other < 0)
          throw inputError(doc, doc.root["joints"][j]["initial_angle"], k + ".initial_angle",
                           Str() << "the bodies on end b's side of joint '" << joint.name()
                                 << "' are also held by the ground (joint '" << sys.joint(i).name()
                                 << "'): initial angles need a tree");
        if (!side[other]) {
          side[other] = true;
          stack.push_back(other);
        }
      }
    }
    if (a >= 0 && side[a])
      throw inputError(doc, doc.root["joints"][j]["initial_angle"], k + ".initial_angle",
                       Str() << "joint '" << joint.name() << "' closes a loop: initial angles "
                             << "need a tree of joints");
    // Current point and axis of the joint (end a, as assembled so far).
    const MarkerEnd& ea = joint.end(0);
    const Eigen::Vector3d P = endPosition(ea, pose);
    const Eigen::Vector3d axis =
        (a >= 0 ? pose[a].A : Eigen::Matrix3d::Identity()) * ea.axes.col(2);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angles[j], axis.normalized()).toRotationMatrix();
    for (int c = 0; c < nb; ++c) {
      if (!side[c]) continue;
      pose[c].r = P + R * (pose[c].r - P);
      pose[c].A = R * pose[c].A;
      pose[c].v = R * pose[c].v;
      pose[c].w = R * pose[c].w;
    }
  }
}

void checkInitialConstraints(const YamlDocument& doc, MultibodySystem& sys, Eigen::VectorXd& y0) {
  if (sys.numJoints() == 0) return;
  const YAML::Node joints = doc.root["joints"];
  ConstraintRows rows;
  sys.constraintRows(y0.data(), rows);
  // Tolerances: 1e-9 m and 1e-9 rad are far above the round-off of an assembled state
  // (1e-16 relative) and far below anything a user could mean as a real gap.
  constexpr double kPosition = 1e-9, kVelocity = 1e-9;
  const int v0 = sys.velocityOffset(0);
  const Eigen::VectorXd z = y0.tail(y0.size() - v0);
  const Eigen::VectorXd rate = rows.J * z;
  int row = 0;
  for (int j = 0; j < sys.numJoints(); ++j) {
    const int m = sys.joint(j).numEquations();
    const double g = rows.g.segment(row, m).lpNorm<Eigen::Infinity>();
    const double gd = rate.segment(row, m).lpNorm<Eigen::Infinity>();
    const std::string k = Str() << "joints[" << j << "]";
    if (g > kPosition)
      throw inputError(doc, joints[j], k,
                       Str() << "the initial positions violate "
                             << jointTypeName(sys.joint(j).type()) << " joint '"
                             << sys.joint(j).name() << "' by " << g << " (m or rad; tolerance "
                             << kPosition << "): place the bodies "
                             << "so that its markers coincide and its axes align");
    if (gd > kVelocity)
      throw inputError(doc, joints[j], k,
                       Str() << "the initial velocities violate joint '" << sys.joint(j).name()
                             << "' by " << gd << " (m/s or rad/s; tolerance " << kVelocity << ")");
    row += m;
  }
  // Redundancy: joints 0..j together must have independent equations, i.e. a positive
  // definite J M^-1 J^T; scaled to unit diagonal, its smallest eigenvalue measures how
  // independent the rows are (1e-10: far below any real joint set, far above round-off).
  Eigen::MatrixXd X;
  sys.inverseMassTimes(y0.data(), rows.J, X);
  const Eigen::MatrixXd S = rows.J * X;
  row = 0;
  for (int j = 0; j < sys.numJoints(); ++j) {
    row += sys.joint(j).numEquations();
    const Eigen::VectorXd d = S.topLeftCorner(row, row).diagonal().cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd Sn = d.asDiagonal() * S.topLeftCorner(row, row) * d.asDiagonal();
    const double lmin = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Sn).eigenvalues()(0);
    if (!(lmin > 1e-10))
      throw inputError(doc, joints[j], Str() << "joints[" << j << "]",
                       Str() << "joint '" << sys.joint(j).name() << "' over-constrains the system: "
                             << "its equations repeat those of the joints before it (redundant "
                             << "joints; remove it or use a joint with fewer equations)");
  }
  if (!sys.projectState(y0.data()))
    throw InputError("the initial state could not be projected onto the joints' constraints");
}

}  // namespace ffriga
