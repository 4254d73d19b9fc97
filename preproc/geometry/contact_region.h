// The contact region of a body: a box on one boundary face (3D) or edge (2D) of the patch,
// in parametric coordinates, and the Craig-Bampton interface it defines: the control
// points whose basis function has a non-zero trace on the face inside the region (the
// "exterior control points in the contact area" of paper Sect. 5).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/splines/spline_space.h"

namespace ffriga {

struct ContactRegion {
  int direction = 1;  // parametric direction normal to the face (0 xi, 1 eta, 2 zeta)
  bool upper = true;  // face at the upper end of that direction (xi_max, ...)
  // Bounds per remaining parametric direction, in increasing direction order (d - 1).
  std::vector<std::array<double, 2>> bounds;
};

// "xi_min" ... "zeta_max" <-> (direction, upper). One table for both directions.
bool parseFaceName(const std::string& name, int* direction, bool* upper);
std::string faceName(int direction, bool upper);

// Parametric value of the face (the first or last knot of `direction`), from the space's
// elements.
double faceCoordinate(const SplineSpace& space, const ContactRegion& region);

// Control points (sorted) whose functions do not vanish on the face inside the region:
// detected at 4 Gauss points per direction on every face element's overlap with the
// region (the trace of a non-zero polynomial piece vanishes at no Gauss point set of that
// size unless it vanishes identically: p <= 7 per direction guarantees it).
std::vector<int> interfaceControlPoints(const SplineSpace& space, const ContactRegion& region);

}  // namespace ffriga
