#include "runtime/forces/force_element.h"

namespace ffriga {

const std::vector<StiffnessTerm>& ForceElement::stiffnessTerms() const {
  static const std::vector<StiffnessTerm> kNone;
  return kNone;
}

}  // namespace ffriga
