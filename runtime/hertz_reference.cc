#include "runtime/hertz_reference.h"

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

Eigen::Vector3d vectorOf(const YAML::Node& node) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  if (node && node.IsSequence()) {
    for (std::size_t i = 0; i < node.size() && i < 3; ++i) v(i) = node[i].as<double>();
  }
  return v;
}

}  // namespace

std::optional<HertzReference> hertzReference(const Scene& scene, int pair) {
  const ContactPair& c = scene.system->contact(pair);
  const BodyModel& a = scene.system->body(c.bodyA());
  const BodyModel& b = scene.system->body(c.bodyB());
  const auto sa = sphereOf(a.sid());
  const auto sb = sphereOf(b.sid());
  if (!sa || !sb) return std::nullopt;
  Eigen::Vector3d ra, rb, va, vb;
  int found = 0;
  for (const auto& body : scene.doc.root["bodies"]) {
    const std::string name = body["name"].as<std::string>();
    if (name == a.name()) {
      ra = vectorOf(body["position"]);
      va = vectorOf(body["velocity"]);
      ++found;
    }
    if (name == b.name()) {
      rb = vectorOf(body["position"]);
      vb = vectorOf(body["velocity"]);
      ++found;
    }
  }
  if (found != 2 || (rb - ra).norm() == 0.0) return std::nullopt;
  const Eigen::Vector3d n = (rb - ra).normalized();
  HertzReference h;
  h.approach_speed = -(vb - va).dot(n);
  if (!(h.approach_speed > 0.0)) return std::nullopt;
  h.impact = hertzImpact(*sa, *sb, h.approach_speed);
  return h;
}

}  // namespace ffriga
