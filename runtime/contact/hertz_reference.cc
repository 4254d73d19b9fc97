#include "runtime/contact/hertz_reference.h"

#include <yaml-cpp/yaml.h>

namespace ffriga {

namespace {

std::optional<HertzSphere> sphereOf(const FlexibleBodySid& sid) {
  try {
    const YAML::Node body = YAML::Load(sid.input_yaml);
    const std::string type = body["geometry"]["type"].as<std::string>();
    if (type != "half_disk" && type != "sphere") return std::nullopt;
    HertzSphere s;
    s.radius = body["geometry"]["radius"].as<double>();
    s.youngs_modulus = body["material"]["youngs_modulus"].as<double>();
    s.poisson_ratio = body["material"]["poisson_ratio"].as<double>();
    s.mass = sid.mass;
    return s;
  } catch (const YAML::Exception&) {
    return std::nullopt;  // not a body file we can read as a sphere: no reference
  }
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
  return h;
}

}  // namespace ffriga
