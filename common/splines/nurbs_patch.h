// NURBS curve, surface or volume: a tensor-product patch with d = 1, 2 or 3 parametric
// directions in a physical space of dimension s = 2 or 3 (paper Eq. 4-5):
//
//   x(xi) = sum_k R_k(xi) P_k,   R_k = N_k(xi) w_k / sum_l N_l(xi) w_l,
//   N_k(xi) = N_{i,p}(xi_0) M_{j,q}(xi_1) L_{l,r}(xi_2).
//
// Control points are numbered lexicographically with the first direction fastest:
// k = i0 + n0 * (i1 + n1 * i2). Coordinates are in metres; weights are dimensionless and
// must be positive.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Dense>

#include "common/splines/knot_vector.h"
#include "common/splines/rational_basis.h"

namespace ffriga {

// The non-zero basis functions of a patch at one parametric point.
struct PatchBasis {
  std::vector<int> index;  // control point index of each column
  Eigen::MatrixXd table;   // numDerivativeRows(d, order) x index.size(), see rational_basis.h
};

// A point of the patch with its parametric derivatives.
struct PatchPoint {
  Eigen::VectorXd x;    // position (s)
  Eigen::MatrixXd dx;   // first derivatives, s x d, column a = dx/dxi_a
  Eigen::MatrixXd ddx;  // second derivatives, s x d(d+1)/2, columns as the rows of a table
};

class NurbsPatch {
 public:
  NurbsPatch() = default;
  // Throws std::invalid_argument when the numbers of control points or weights do not
  // match the knot vectors, when d is not 1..3 or s not 2..3, or a weight is not positive.
  NurbsPatch(std::vector<KnotVector> knots, Eigen::MatrixXd points, Eigen::VectorXd weights);

  int paramDim() const { return static_cast<int>(knots_.size()); }
  int spaceDim() const { return static_cast<int>(points_.cols()); }
  int numControlPoints() const { return static_cast<int>(points_.rows()); }
  int numBasis(int dir) const { return knots_[dir].numBasis(); }
  int degree(int dir) const { return knots_[dir].degree(); }
  int numElements() const;
  const KnotVector& knots(int dir) const { return knots_[dir]; }
  const std::vector<KnotVector>& knotVectors() const { return knots_; }
  const Eigen::MatrixXd& points() const { return points_; }
  const Eigen::VectorXd& weights() const { return weights_; }

  // Linear index of the tensor index (i0, i1, i2); unused trailing entries are ignored.
  int linearIndex(const std::array<int, 3>& i) const;
  std::array<int, 3> tensorIndex(int k) const;

  // Homogeneous control points [w P, w] (n x (s + 1)) and their inverse.
  Eigen::MatrixXd homogeneous() const;
  static NurbsPatch fromHomogeneous(std::vector<KnotVector> knots, const Eigen::MatrixXd& Pw);

  // Polynomial (B-spline) and rational basis with derivatives up to `order` (<= 2) at xi.
  void bsplineBasis(const double* xi, int order, PatchBasis& out) const;
  void basis(const double* xi, int order, PatchBasis& out) const;
  // The same on given knot spans (one per direction): xi on an element's upper boundary is
  // evaluated with that element's polynomial pieces.
  void bsplineBasisOnSpans(const int* spans, const double* xi, int order, PatchBasis& out) const;
  void rationalBasisOnSpans(const int* spans, const double* xi, int order, PatchBasis& out) const;
  PatchPoint evaluate(const double* xi, int order = 0) const;

 private:
  std::vector<KnotVector> knots_;
  Eigen::MatrixXd points_;
  Eigen::VectorXd weights_;
};

// Point and derivatives from a basis table (rows as in rational_basis.h, one column per
// function; d parametric directions, derivatives up to `order`) and the functions' points:
// X = sum_i table(:, i) points(functions[i], :), split into x, dx and ddx.
PatchPoint pointFromTable(const Eigen::MatrixXd& table, const int* functions,
                          const Eigen::MatrixXd& points, int d, int order);
// The same into `pt`, reusing its storage (no allocation when sizes repeat: the contact
// search's hot path). Members above `order` keep what they held.
void pointFromTable(const Eigen::MatrixXd& table, const int* functions,
                    const Eigen::MatrixXd& points, int d, int order, PatchPoint& pt);

// Tensor-product B-spline basis on one element: given the spans and the parameter,
// fills the table of all (p0+1)...(pd-1 + 1) non-zero functions (first direction fastest).
void tensorBasis(const std::vector<KnotVector>& knots, const int* spans, const double* xi,
                 int order, Eigen::MatrixXd& table);

// Groups of control points that coincide within `tol` (absolute, metres): collapsed edges,
// poles, seams. Each group lists >= 2 indices in increasing order; groups are sorted by
// their first index. Later stages tie the degrees of freedom of each group.
std::vector<std::vector<int>> coincidentControlPoints(const NurbsPatch& patch, double tol);
// The same for any point set (rows of P).
std::vector<std::vector<int>> coincidentPoints(const Eigen::MatrixXd& P, double tol);

}  // namespace ffriga
