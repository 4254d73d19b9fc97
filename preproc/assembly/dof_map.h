// Degrees of freedom of a vector field u(x) = sum_k R_k(x) u_k on a SplineSpace, with
// coincident control points tied (collapsed edges, poles and seams of a NURBS patch must
// move together, DESIGN.md "Elasticity") and, for axisymmetric models, the radial
// displacement u_r = 0 at control points on the axis (x = 0) so that the displacement field
// stays single-valued and smooth on the axis.
//
// Numbering: every control point k maps to a node (the smallest index of its coincident
// group); DOF numbers increase with (node, component), so that a column of a sparse matrix
// built node by node has sorted row indices. Fixed components get DOF -1.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "common/splines/spline_space.h"

namespace ffriga {

class DofMap {
 public:
  // tolerance: absolute distance (m) below which control points coincide; a negative
  // value means 1e-12 times the size of the control net.
  DofMap(const SplineSpace& space, bool axisymmetric, double tolerance = -1.0);
  // With the groups of tied control points given (each group moves as one point; e.g.
  // tiedControlPoints() of body_config.h for hierarchical spaces, which ties only points of
  // the same level).
  DofMap(const SplineSpace& space, bool axisymmetric, const std::vector<std::vector<int>>& tied,
         double tolerance = -1.0);
  static double defaultTolerance(const SplineSpace& space);

  int numControlPoints() const { return static_cast<int>(node_.size()); }
  int components() const { return components_; }
  int numDofs() const { return num_dofs_; }
  // DOF of component c of control point k, -1 if fixed (u_r on the axis).
  int dof(int k, int c) const { return dof_[k * components_ + c]; }
  int node(int k) const { return node_[k]; }
  int numTiedPoints() const { return num_tied_; }
  int numFixedDofs() const { return num_fixed_; }

  // Displacements of every control point (ncp * components rows, component fastest) from
  // DOF vectors (numDofs rows): the tying and the axis condition applied.
  Eigen::MatrixXd expand(const Eigen::MatrixXd& x) const;
  // Restriction of control-point vectors to DOFs (picks the node's value; the inverse of
  // expand for fields that satisfy the ties and the axis condition).
  Eigen::MatrixXd restrict(const Eigen::MatrixXd& u) const;

 private:
  int components_ = 0;
  int num_dofs_ = 0;
  int num_tied_ = 0;
  int num_fixed_ = 0;
  std::vector<int> node_;
  std::vector<int> dof_;
};

}  // namespace ffriga
