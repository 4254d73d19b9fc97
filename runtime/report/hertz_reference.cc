#include "runtime/report/hertz_reference.h"

namespace ffriga {

namespace {

// A sphere's Hertz data from its SID (material and exact geometry, SID format 3).
std::optional<HertzSphere> sphereOf(const FlexibleBodySid& sid) {
  const std::string& type = sid.geometry.type;
  if (type != "half_disk" && type != "sphere") return std::nullopt;
  HertzSphere s;
  s.radius = sid.geometry.radius;
  s.youngs_modulus = sid.material.youngs_modulus;
  s.poisson_ratio = sid.material.poisson_ratio;
  s.mass = sid.mass;
  return s;
}

}  // namespace

std::optional<HertzReference> hertzReference(const Scene& scene, int pair) {
  const ContactPair& c = scene.system->contact(pair);
  const BodyModel& a = scene.system->body(c.bodyA());
  const BodyModel& b = scene.system->body(c.bodyB());
  const auto sa = sphereOf(a.sid());
  const auto sb = sphereOf(b.sid());
  if (!sa || !sb) return std::nullopt;
  const Eigen::Vector3d& ra = scene.initial_position[c.bodyA()];
  const Eigen::Vector3d& rb = scene.initial_position[c.bodyB()];
  const Eigen::Vector3d& va = scene.initial_velocity[c.bodyA()];
  const Eigen::Vector3d& vb = scene.initial_velocity[c.bodyB()];
  if ((rb - ra).norm() == 0.0) return std::nullopt;
  const Eigen::Vector3d n = (rb - ra).normalized();
  HertzReference h;
  h.approach_speed = -(vb - va).dot(n);
  if (!(h.approach_speed > 0.0)) return std::nullopt;
  h.impact = hertzImpact(*sa, *sb, h.approach_speed);
  h.sphere_a = *sa;
  h.sphere_b = *sb;
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
    if (!h) continue;
    const int a = sys.contact(c).bodyA(), b = sys.contact(c).bodyB();
    if (!partners[a]) partners[a] = HertzPartner{h->sphere_a, h->sphere_b};
    if (!partners[b]) partners[b] = HertzPartner{h->sphere_b, h->sphere_a};
  }
  return partners;
}

}  // namespace ffriga
