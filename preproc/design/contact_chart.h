// The chart of a contact point (the design rule's view of a patch, impact_design.h): how
// each parametric direction passes through the contact point, along the surface (lateral)
// or into the body (depth), with its level-0 knot span there, its length per knot and the
// knot at a given distance. The rule lays its boxes and the contact region on this chart.
//
//   halfDiskChart   the half-disk of paper Eq. (19) at its pole (0, 1), exact arcs;
//   sphereChart     the solid sphere at (1/2, 1, 1/8), exact arcs;
//   patchChart      any 2D section or 3D solid patch at a point of a boundary face, from
//                   the iso-parametric curves through the point, tabulated (arc length
//                   along the surface, normal depth into the body).
#pragma once

#include <functional>
#include <vector>

#include "common/splines/nurbs_patch.h"
#include "preproc/geometry/face_point.h"

namespace ffriga {

struct ChartDirection {
  bool depth = false;
  bool one_sided = false;              // lateral, the contact point on the patch's edge
                                       // (at == lowest or at == highest): the half-disk's axis
  double at = 0.0;                     // the contact point's knot
  double span0 = 0.0;                  // level-0 knot span there
  double metres_per_knot = 0.0;        // length per knot there (m)
  std::function<double(double)> knot;  // lateral: knot at signed distance s (m) from the
                                       // contact point along the surface (increasing with
                                       // s); depth: knot at normal depth s >= 0
  double lowest = 0.0, highest = 1.0;  // the boxes' limits (exclusive unless the contact
                                       // point's own edge): patch ends, C0 knot lines
  double reach_limit = 0.0;            // lateral: the largest reach of the region it admits
                                       // (m): the arc to the nearest limit on both sides, or
                                       // half the arc to the far limit from the patch's edge
                                       // (the axis); depth: the depth the curve reaches
};

std::vector<ChartDirection> halfDiskChart(double r);
std::vector<ChartDirection> sphereChart(double r);

// The chart of `patch` at the point `where` of its face {xi[face_direction] = face bound},
// level-0 knot spans `span0` per direction (knot vectors on [0, 1]). Lateral limits are the
// patch's ends and its C0 knot lines (multiplicity >= degree) nearest the point.
std::vector<ChartDirection> patchChart(const NurbsPatch& patch, const FacePoint& where,
                                       int face_direction, const std::vector<double>& xi,
                                       const std::vector<double>& span0);

// The length of each direction's iso-parametric curve through xi (m): the extents the
// level-0 grid of a designed patch is sized from.
std::vector<double> isoCurveLengths(const NurbsPatch& patch, const std::vector<double>& xi);

}  // namespace ffriga
