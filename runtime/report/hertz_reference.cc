#include "runtime/report/hertz_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/mechanics/hertz_ellipse.h"
#include "runtime/contact/obstacle_contact.h"

namespace ffriga {

namespace {

// A designed explicit patch: its contact point's surface radius (spherical), or its
// principal curvatures (elliptical) from the SID (preproc/design/impact_design.h; /design).
bool designedPatch(const FlexibleBodySid& sid) {
  return sid.geometry.type == "nurbs" && sid.design.present &&
         (sid.design.surface_radius > 0.0 || sid.design.principal_direction.size() == 3);
}

// A body's surface at its contact point as Hertz sees it: principal curvatures k1 <= k2
// (1/m) and the direction of k1 (inertial components at t = 0; zero where k1 = k2).
struct PrincipalCurvatures {
  double k1 = 0.0, k2 = 0.0;
  Eigen::Vector3d d1 = Eigen::Vector3d::Zero();
  bool spherical() const { return d1.isZero(); }
};

// A sphere's Hertz data from its SID (material and exact geometry, SID format 3), or a
// designed patch's at its contact point (an elliptical one: radius the mean curvature's,
// used only through its curvatures). A frozen body (a SID body without elastic
// coordinates: a rigid NURBS target) is infinitely stiff.
std::optional<HertzSphere> sphereOf(const BodyModel& body) {
  const FlexibleBodySid& sid = body.sid();
  const std::string& type = sid.geometry.type;
  if (type != "half_disk" && type != "sphere" && !designedPatch(sid)) return std::nullopt;
  HertzSphere s;
  s.radius = sid.geometry.radius;
  if (designedPatch(sid))
    s.radius =
        sid.design.surface_radius > 0.0
            ? sid.design.surface_radius
            : 2.0 / (sid.design.principal_curvatures(0) + sid.design.principal_curvatures(1));
  s.youngs_modulus = body.nq() > 0 ? sid.material.youngs_modulus
                                   : std::numeric_limits<double>::infinity();
  s.poisson_ratio = sid.material.poisson_ratio;
  s.mass = sid.mass;
  return s;
}

// Body b's principal curvatures at its contact point: a sphere's (or a spherical designed
// patch's) 1 / R twice, an elliptical designed patch's from its SID, turned by the body's
// initial rotation.
PrincipalCurvatures curvaturesOf(const Scene& scene, int b, const HertzSphere& s) {
  const FlexibleBodySid& sid = scene.system->body(b).sid();
  if (!designedPatch(sid) || sid.design.principal_direction.size() != 3)
    return {1.0 / s.radius, 1.0 / s.radius, Eigen::Vector3d::Zero()};
  return {sid.design.principal_curvatures(0), sid.design.principal_curvatures(1),
          scene.initial_rotation[b] * Eigen::Vector3d(sid.design.principal_direction)};
}

// A rigid obstacle as Hertz sees it: infinitely stiff and heavy; a plane also infinitely
// large (IEEE infinities make E*, R* and m* those of the body alone).
HertzSphere rigidPartner(const RigidObstacle& o) {
  const double inf = std::numeric_limits<double>::infinity();
  return HertzSphere{inf, 0.0, o.shape() == RigidObstacle::Shape::kSphere ? o.radius() : inf, inf};
}

// A sphere body against an obstacle: the approach speed along the normal at the nearest
// point when the sphere's surface first touches, under gravity alone (v_n^2 + 2 g_n d with
// d the initial clearance; a body that never gets there has none), and gravity presses it
// on during the contact: the steady load m g_n of hertzImpact (the obstacle does not fall
// with it, unlike a partner body). A solid sphere on a cylinder makes Hertz's elliptical
// contact (relative curvatures 1 / (2 r) along the axis, (1 / r + 1 / R_c) / 2 across).
std::optional<HertzReference> obstacleReference(const Scene& scene, const ObstacleContact& c) {
  const bool cylinder = c.obstacle().shape() == RigidObstacle::Shape::kCylinder;
  const BodyModel& body = scene.system->body(c.bodyA());
  if (cylinder && body.sid().space_dim != 3) return std::nullopt;  // a coaxial ring
  if (designedPatch(body.sid())) return std::nullopt;              // no centre
  const auto sa = sphereOf(body);
  if (!sa) return std::nullopt;
  const Eigen::Vector3d& r = scene.initial_position[c.bodyA()];
  const Eigen::Vector3d& v = scene.initial_velocity[c.bodyA()];
  const ObstaclePoint p = c.obstacle().nearest(r);
  if (!p.covered) return std::nullopt;
  const double clearance = std::max(0.0, p.gap - sa->radius);
  const double vn = -v.dot(p.normal), gn = -scene.system->gravity().dot(p.normal);
  const double v2 = vn * vn + 2.0 * gn * clearance;
  if (!(vn > 0.0 || gn > 0.0) || !(v2 > 0.0)) return std::nullopt;
  HertzReference h;
  h.approach_speed = std::sqrt(v2);
  h.sphere_a = *sa;
  h.sphere_b = rigidPartner(c.obstacle());
  const double preload = sa->mass * gn;
  if (cylinder) {
    const double k = 1.0 / sa->radius;
    h.curvatures = relativeCurvatures(k, k, 0.0, 1.0 / c.obstacle().radius(), 1.0);
    h.elliptical = true;
    h.impact =
        ellipticalHertzImpact(h.curvatures, h.sphere_a, h.sphere_b, h.approach_speed, preload);
  } else {
    h.impact = hertzImpact(h.sphere_a, h.sphere_b, h.approach_speed, preload);
    h.curvatures.A = h.curvatures.B = 0.5 / effectiveRadius(h.sphere_a, h.sphere_b);
  }
  return h;
}

// Whether body b is an end of a joint: its effective mass at the contact is the
// mechanism's (a pendulum's I_pivot / d^2, not m) and its approach speed the mechanism's
// motion, neither of which the free-sphere formulas know.
bool jointed(const MultibodySystem& system, int b) {
  for (int j = 0; j < system.numJoints(); ++j)
    if (system.joint(j).end(0).body == b || system.joint(j).end(1).body == b) return true;
  return false;
}

// Whether body b's designed contact point faces along the unit vector n at t = 0 (the
// central impact Hertz describes); a sphere faces every way.
bool facesAlong(const Scene& scene, int b, const Eigen::Vector3d& n) {
  const FlexibleBodySid& sid = scene.system->body(b).sid();
  if (!designedPatch(sid)) return true;
  const Eigen::Vector3d normal =
      scene.initial_rotation[b] * Eigen::Vector3d(sid.design.contact_normal);
  return normal.dot(n) > 1.0 - 1e-9;
}

}  // namespace

std::optional<HertzReference> hertzReference(const Scene& scene, int pair) {
  const SurfaceContact& c = scene.system->contact(pair);
  if (jointed(*scene.system, c.bodyA()) || (c.bodyB() >= 0 && jointed(*scene.system, c.bodyB())))
    return std::nullopt;
  if (const auto* o = dynamic_cast<const ObstacleContact*>(&c)) return obstacleReference(scene, *o);
  const BodyModel& a = scene.system->body(c.bodyA());
  const BodyModel& b = scene.system->body(c.bodyB());
  const auto sa = sphereOf(a);
  const auto sb = sphereOf(b);
  if (!sa || !sb) return std::nullopt;
  const Eigen::Vector3d& ra = scene.initial_position[c.bodyA()];
  const Eigen::Vector3d& rb = scene.initial_position[c.bodyB()];
  const Eigen::Vector3d& va = scene.initial_velocity[c.bodyA()];
  const Eigen::Vector3d& vb = scene.initial_velocity[c.bodyB()];
  if ((rb - ra).norm() == 0.0) return std::nullopt;
  const Eigen::Vector3d n = (rb - ra).normalized();
  if (!facesAlong(scene, c.bodyA(), n) || !facesAlong(scene, c.bodyB(), -n)) return std::nullopt;
  HertzReference h;
  h.approach_speed = -(vb - va).dot(n);
  if (!(h.approach_speed > 0.0)) return std::nullopt;
  h.sphere_a = *sa;
  h.sphere_b = *sb;
  const PrincipalCurvatures ca = curvaturesOf(scene, c.bodyA(), *sa);
  const PrincipalCurvatures cb = curvaturesOf(scene, c.bodyB(), *sb);
  if (ca.spherical() && cb.spherical()) {
    h.impact = hertzImpact(*sa, *sb, h.approach_speed);
    h.curvatures.A = h.curvatures.B = 0.5 / effectiveRadius(*sa, *sb);
    return h;
  }
  const double cos_alpha = ca.spherical() || cb.spherical() ? 1.0 : ca.d1.dot(cb.d1);
  h.curvatures = relativeCurvatures(ca.k1, ca.k2, cb.k1, cb.k2, cos_alpha);
  h.elliptical = true;
  h.impact = ellipticalHertzImpact(h.curvatures, *sa, *sb, h.approach_speed);
  return h;
}

HertzReferences hertzReferences(const Scene& scene) {
  HertzReferences out;
  for (int c = 0; c < scene.system->numContacts(); ++c) out.push_back(hertzReference(scene, c));
  return out;
}

std::vector<std::optional<HertzPartner>> hertzPartners(const Scene& scene,
                                                       const HertzReferences& hertz) {
  const MultibodySystem& sys = *scene.system;
  std::vector<std::optional<HertzPartner>> partners(sys.numBodies());
  for (int c = 0; c < sys.numContacts(); ++c) {
    const auto& h = hertz[c];
    if (!h || h->elliptical) continue;  // the stress lines know the spheres' field only
    const int a = sys.contact(c).bodyA(), b = sys.contact(c).bodyB();
    if (!partners[a]) partners[a] = HertzPartner{h->sphere_a, h->sphere_b};
    if (b >= 0 && !partners[b]) partners[b] = HertzPartner{h->sphere_b, h->sphere_a};
  }
  return partners;
}

}  // namespace ffriga
