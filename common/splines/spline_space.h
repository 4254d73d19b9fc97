// A spline space over one patch with a rational basis, seen element by element: the
// interface that assembly (preproc), SID export and contact (runtime) use, so that they
// work unchanged on a tensor-product NURBS patch and on its hierarchical refinement.
//
//   x(xi) = sum_k R_k(xi) P_k  with  R_k = w_k B_k / sum_l w_l B_l          (Eq. 4-5)
//
// where B_k are the space's polynomial basis functions (tensor B-splines, or THB-splines).
// Functions and control points share one numbering 0..numFunctions()-1. Elements are boxes
// in parameter space on which every basis function is a polynomial.
#pragma once

#include <array>

#include <Eigen/Dense>

#include "common/splines/nurbs_patch.h"

namespace ffriga {

struct ElementBox {
  std::array<double, 3> lower{0, 0, 0};  // parametric lower corner
  std::array<double, 3> upper{0, 0, 0};  // parametric upper corner
  int level = 0;                         // refinement level (0 for a tensor patch)
};

class SplineSpace {
 public:
  virtual ~SplineSpace() = default;

  virtual int paramDim() const = 0;
  int spaceDim() const { return static_cast<int>(controlPoints().cols()); }
  int numFunctions() const { return static_cast<int>(controlPoints().rows()); }
  virtual const Eigen::MatrixXd& controlPoints() const = 0;  // numFunctions x s, metres
  virtual const Eigen::VectorXd& weights() const = 0;        // numFunctions, positive

  virtual int numElements() const = 0;
  virtual ElementBox element(int e) const = 0;
  // The element containing xi (xi on a shared boundary goes to one of them).
  virtual int findElement(const double* xi) const = 0;
  // Rational basis functions that do not vanish on element e, at xi inside that element,
  // with derivatives up to `order` (<= 2): out.index are function numbers, out.table as in
  // rational_basis.h.
  virtual void elementBasis(int e, const double* xi, int order, PatchBasis& out) const = 0;

  // Convenience: the point x(xi) with derivatives.
  PatchPoint evaluate(const double* xi, int order = 0) const;
};

// The tensor-product NURBS patch as a SplineSpace (elements: non-empty knot span boxes,
// numbered with the first direction fastest).
class TensorSpace : public SplineSpace {
 public:
  explicit TensorSpace(NurbsPatch patch);

  const NurbsPatch& patch() const { return patch_; }
  int paramDim() const override { return patch_.paramDim(); }
  const Eigen::MatrixXd& controlPoints() const override { return patch_.points(); }
  const Eigen::VectorXd& weights() const override { return patch_.weights(); }
  int numElements() const override { return patch_.numElements(); }
  ElementBox element(int e) const override;
  int findElement(const double* xi) const override;
  void elementBasis(int e, const double* xi, int order, PatchBasis& out) const override;

 private:
  NurbsPatch patch_;
  std::array<std::vector<int>, 3> spans_;  // element spans per direction
};

}  // namespace ffriga
