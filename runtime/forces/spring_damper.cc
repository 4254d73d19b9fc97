#include "runtime/forces/spring_damper.h"

namespace ffriga {

SpringDamper::SpringDamper(std::string name, MarkerEnd a, MarkerEnd b, double stiffness,
                           double damping, double free_length)
    : LineForce(std::move(name), std::move(a), std::move(b)),
      k_(stiffness),
      c_(damping),
      l0_(free_length) {}

}  // namespace ffriga
