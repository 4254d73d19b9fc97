// Von Mises equivalent stress of Cartesian stress components (xx, yy, zz, xy, yz, xz), Pa:
//   sqrt(1/2 ((sxx - syy)^2 + (syy - szz)^2 + (szz - sxx)^2) + 3 (sxy^2 + syz^2 + sxz^2)).
// The component order is the one of the SID's stress modes (common/sid/sid.h, SampledModes).
#pragma once

#include <cmath>

namespace ffriga {

inline double vonMises(const double* s) {
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

}  // namespace ffriga
