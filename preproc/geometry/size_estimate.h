// A size estimate of a body before anything large is allocated (issue 13): from the body
// file's geometry and refinement alone, without refining, the control points, DOFs and
// stored nonzeros of K of the global level-0 patch (a hierarchical body has at least these),
// and the memory of K and M with their Cholesky factor (a lower bound: 12 bytes per stored
// entry of K and M, and a fill of the factor of 5 times K's entries in 2D and 20 times in
// 3D, as measured on the sphere models: sphere3d_coarse, 3.1e6 entries, factor 6.0e7).
// An input beyond the limit is refused with the estimate in the message; igaprep's
// --max-memory raises the limit (default: this machine's physical memory).
#pragma once

#include "common/splines/hierarchical_space.h"
#include "common/splines/nurbs_patch.h"
#include "preproc/geometry/body_geometry.h"

namespace ffriga {

struct SizeEstimate {
  double control_points = 0.0;
  double dofs = 0.0;
  double nonzeros = 0.0;  // stored entries of K (upper triangle)
  double bytes = 0.0;     // K, M and the factor of K, lower bound
};

// The global level-0 patch of the exact patch refined by `refinement`.
SizeEstimate estimateSize(const NurbsPatch& exact, const RefinementConfig& refinement);
// A global reference (hierarchy.as_global_reference): every level's knot lines inside its
// box inserted across the patch, from the refined level-0 patch and the boxes.
SizeEstimate estimateGlobalReferenceSize(const NurbsPatch& refined,
                                         const HierarchyOptions& hierarchy);

// This machine's physical memory (bytes), 0 if unknown.
double physicalMemoryBytes();

}  // namespace ffriga
