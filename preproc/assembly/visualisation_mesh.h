// The visualisation mesh of a body (common/sid/sid.h VisualisationMesh): every element of the
// spline space split into `subdivisions` cells per parametric direction, with corner points
// on the exact geometry. Points are shared between cells of neighbouring elements when
// their parameters agree (to 2^-40 of the parameter range); points that coincide
// physically with other parameters (poles, the axis of a half-disk, across hierarchical
// levels' hanging corners) stay separate, which ParaView draws without gaps because they
// sit at the same place. Cells: quadrilaterals (d = 2) or hexahedra (d = 3), corners in
// VTK/XDMF order ((0,0), (1,0), (1,1), (0,1), then the same at zeta = 1).
#pragma once

#include <vector>

#include "common/sid/sid.h"
#include "common/splines/spline_space.h"
#include "preproc/assembly/stress_modes.h"

namespace ffriga {

struct MeshTopology {
  std::vector<ParametricPoint> points;
  Eigen::MatrixXi cells;  // nc x 2^d
};

// Points and cells, deterministic: elements in the space's order, corners in lexicographic
// order (first direction fastest).
MeshTopology meshTopology(const SplineSpace& space, int subdivisions);

// The mesh with displacement and stress modes sampled at its points (stress_modes.h).
VisualisationMesh visualisationMesh(const SplineSpace& space, int subdivisions,
                                    const Eigen::MatrixXd& Phi, const IsotropicMaterial& material,
                                    bool axisymmetric, const Eigen::VectorXd& origin, double size);

}  // namespace ffriga
