// The volume of a body given as one patch, by Gauss-Legendre quadrature, p + 2 points per
// direction on each eighth of an element (exact for polynomial patches; the rational half-
// disk of paper Eq. 19 as one element: within 1e-9 of 4/3 pi r^3):
//   solid           V = int |det dx/dxi| dxi
//   axisymmetric    V = 2 pi int x |det dx/dxi| dxi   (x the radius, the section in x >= 0)
// The body's mass is its density times V (the design's Hertz impact needs it before any
// assembly). m^3.
#pragma once

#include "common/splines/nurbs_patch.h"

namespace ffriga {

double patchVolume(const NurbsPatch& patch, bool axisymmetric);

}  // namespace ffriga
