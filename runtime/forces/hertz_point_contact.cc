#include "runtime/forces/hertz_point_contact.h"

#include <cmath>

namespace ffriga {

HertzPointContact::HertzPointContact(std::string name, MarkerEnd a, MarkerEnd b,
                                     const HertzSphere& sa, const HertzSphere& sb)
    : LineForce(std::move(name), std::move(a), std::move(b)),
      K_(hertzStiffness(sa, sb)),
      radii_(sa.radius + sb.radius) {}

double HertzPointContact::tension(double l, double) const {
  const double delta = radii_ - l;
  return delta > 0.0 ? -K_ * delta * std::sqrt(delta) : 0.0;
}

double HertzPointContact::energy(double l) const {
  const double delta = radii_ - l;
  return delta > 0.0 ? 0.4 * K_ * delta * delta * std::sqrt(delta) : 0.0;
}

}  // namespace ffriga
