// Hierarchical B-spline / NURBS space over one patch (paper Sect. 3.3; truncation after
// Giannelli, Juettler, Speleers, "THB-splines: the truncated basis for hierarchical
// splines", CAGD 29 (2012) 485-498).
//
// Levels. Level 0 is the patch's own tensor space S^0 (knot vectors U^0). Level l+1 halves
// every non-empty knot span of level l (U^{l+1} = U^l plus all span midpoints, paper
// Eq. 8-11), so S^0 in S^1 in ... in S^{L-1}, L = nlvl. The two-scale relation
//   B^l_i = sum_j T^{l+1}(j, i) B^{l+1}_j
// comes from refinementMatrix() (Boehm knot insertion, Piegl & Tiller A5.4).
//
// Regions. Omega^0 is the parameter domain; Omega^l (l = 1..L-1) is a union of closed boxes
// per level, given in knot coordinates, nested: every box of level l+1 lies in a box of
// level l, so Omega^{l+1} in Omega^l. The boxes of one level are disjoint and do not touch
// (separated along at least one direction), so that a connected set -- the support of a
// B-spline, a cell -- lies in Omega^l exactly when it lies in one of its boxes: every test
// below is "inside some box of the level". Several boxes per level refine around several
// points (a body with contact regions at both ends). Box semantics: every bound of a box of
// Omega^l must be a knot line (breakpoint) of level l-1, so Omega^l is a union of
// level-(l-1) cells (required by the hierarchical construction). Bounds closer than 1e-9
// (relative to the domain length) to a level-(l-1) knot line are snapped to it exactly;
// any other bound is rejected by validateBoxes() with the nearest admissible values.
//
// Basis (hierarchical B-splines, HB, paper):
//   H = union_l { B^l_i : supp B^l_i in Omega^l and supp B^l_i not in Omega^{l+1} }.
// Truncated (THB, default): for s = sum_j c_j B^{l+1}_j,
//   trunc^{l+1} s = sum_{j : supp B^{l+1}_j not in Omega^{l+1}} c_j B^{l+1}_j,
// applied level after level to every active B^l_i. THB span the same space as HB and form
// a partition of unity.
//
// Elements are the cells of level l inside Omega^l and outside Omega^{l+1}. On an element of
// level l every active function is a combination of the (p+1)^d level-l tensor B-splines
// that do not vanish on it:
//   B_active(xi) = C_e b^l(xi),  C_e: n_e x (p+1)^d   (element extraction operator),
// built from local blocks of T (and the truncation masks) at construction. Evaluating the
// rational basis (elementBasis) is tensorBasis() on level l, one small dense product with
// the weighted operator diag(w) C_e, and the quotient rule of rationalize(); elements whose
// operator is the identity (only own-level functions, untruncated) skip the product.
//
// Geometry (exact rational patch). With the homogeneous coefficients Q^l = [w P, w] of the
// patch refined to level l (Q^{l+1} = T^{l+1} Q^l):
//   THB: coefficient of active B^l_i = Q^l_i (the "preservation of coefficients" property
//        of THB-splines, GJS 2012).
//   HB:  g^0 = Q^0; coefficient of active B^l_i = g^l_i;
//        g^{l+1} = T^{l+1} (g^l restricted to the B^l_j with supp in Omega^{l+1})
//        (on cells outside Omega^{l+1} the coarser HB functions already reproduce the patch;
//        what is left lives in Omega^{l+1} and is expanded on level l+1).
// Control point = coefficient / weight, weight = last homogeneous coordinate, so that
//   x(xi) = sum_k R_k(xi) P_k,  R_k = w_k B_k / sum_l w_l B_l   equals the original patch.
// THB weights are positive. HB weights may be negative or even zero (the HB functions are
// no partition of unity); the constructor throws if a weight is zero (|w| <= 1e-12 max|w|).
//
// Numbering: functions level by level, within a level lexicographic (first direction
// fastest); elements likewise. With nlvl = 1 both equal TensorSpace's numbering.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/splines/spline_space.h"

namespace ffriga {

// A box in parameter (knot) coordinates: lower[a] <= xi_a <= upper[a], a < d.
struct ParamBox {
  std::array<double, 3> lower{0, 0, 0};
  std::array<double, 3> upper{0, 0, 0};
};

// The boxes whose union is one level's region Omega^l (at least one).
using LevelBoxes = std::vector<ParamBox>;

struct HierarchyOptions {
  int levels = 1;                 // nlvl >= 1
  std::vector<LevelBoxes> boxes;  // levels - 1 entries: Omega^1 .. Omega^{nlvl-1}
  bool truncated = true;          // THB (true) or the paper's HB (false)
};

// Problem with one box, for error messages: the level's index (box = 0: Omega^1), the box
// within that level (member; 0 for a level of one box), direction (-1 if the problem
// concerns the whole box) and a one-line reason. Empty reason = no problem.
struct BoxProblem {
  int box = -1;
  int member = 0;
  int dir = -1;
  std::string reason;
};

// Whether the box b lies in the box outer (closed boxes, the first d directions).
bool boxInside(const ParamBox& b, const ParamBox& outer, int d);

// Whether the interval [lo, hi] along direction a lies inside one of the boxes' intervals
// along a (a level's knot span, or a B-spline's support, against its region's boxes).
bool intervalInBoxes(const LevelBoxes& boxes, int a, double lo, double hi);

// The knot vectors of levels 0..levels-1 (level l+1 halves every span of level l).
std::vector<std::vector<KnotVector>> levelKnotVectors(const NurbsPatch& patch, int levels);

// Empty if `levels` is admissible for the patch: 1 <= levels <= 30 and at most 2^20 knot
// spans per direction on the finest level; otherwise the reason.
std::string checkLevels(const NurbsPatch& patch, int levels);

// Checks (and snaps, in place) the boxes of `options` against the level grids of `patch`:
// count (levels - 1, each level at least one box), lo < hi inside the domain, alignment
// with level l-1 knot lines, nesting (each box inside a box of the level before), boxes of
// one level apart (neither overlapping nor touching), and that every box holds at least
// one B-spline of its own level in every direction (otherwise the level adds nothing: more
// levels than the knot spans allow). Returns the first problem found.
BoxProblem validateBoxes(const NurbsPatch& patch, HierarchyOptions& options);

// The globally refined reference of a hierarchy (paper Sect. 5): the patch with every knot
// line of every level l >= 1 inside one of its boxes inserted across the whole domain, so
// that its knot vectors equal the finest level's inside the finest boxes. `options` must
// have passed validateBoxes().
NurbsPatch globalReferencePatch(const NurbsPatch& patch, const HierarchyOptions& options);

class HierarchicalSpace : public SplineSpace {
 public:
  // Throws std::invalid_argument with the reason if validateBoxes() finds a problem.
  HierarchicalSpace(const NurbsPatch& patch, HierarchyOptions options);

  int paramDim() const override { return d_; }
  const Eigen::MatrixXd& controlPoints() const override { return points_; }
  const Eigen::VectorXd& weights() const override { return weights_; }
  int numElements() const override { return static_cast<int>(elements_.size()); }
  ElementBox element(int e) const override;
  int findElement(const double* xi) const override;
  void elementBasis(int e, const double* xi, int order, PatchBasis& out) const override;

  // Polynomial (THB or HB) basis on element e: out.table = tensor table * C_e^T (a slow
  // reference path; elementBasis() is the fast one).
  void elementBsplineBasis(int e, const double* xi, int order, PatchBasis& out) const;

  int numLevels() const { return nlvl_; }
  bool truncated() const { return options_.truncated; }
  const HierarchyOptions& options() const { return options_; }
  const NurbsPatch& basePatch() const { return base_; }
  const std::vector<KnotVector>& levelKnots(int level) const { return knots_[level]; }
  // The boxes of Omega^l (the whole domain for l = 0) after snapping.
  const LevelBoxes& region(int level) const { return regions_[level]; }

  // Function k: level and tensor index in that level's tensor space.
  int functionLevel(int k) const { return funcLevel_[k]; }
  const std::array<int, 3>& functionTensorIndex(int k) const { return funcIndex_[k]; }
  int numFunctionsOnLevel(int level) const;
  int numElementsOnLevel(int level) const;

  // Element e: level, knot span per direction in that level's knot vectors, active
  // functions and extraction operator C_e (rows: functions, columns: the level's local
  // tensor B-splines, first direction fastest).
  int elementLevel(int e) const { return elements_[e].level; }
  const std::array<int, 3>& elementSpans(int e) const { return elements_[e].spans; }
  const std::vector<int>& elementFunctions(int e) const { return elements_[e].functions; }
  const Eigen::MatrixXd& elementExtraction(int e) const {
    return elements_[e].identity ? identity_ : elements_[e].extraction;
  }

  // Active functions that do not vanish on the face xi_dir = front (side 0) / back (side 1).
  std::vector<int> faceFunctions(int dir, int side) const;

 private:
  struct Element {
    int level = 0;
    std::array<int, 3> spans{0, 0, 0};
    std::vector<int> functions;
    Eigen::MatrixXd extraction;  // n_e x (p+1)^d
    Eigen::MatrixXd weightedT;   // (diag(w) C_e)^T, K x n_e (identity: the K weights)
    bool identity = false;       // C_e is the identity (functions = the level's local ones)
  };
  struct LevelIndex {  // dense id arrays over the index ranges of the region's boxes
    std::array<int, 3> lo{0, 0, 0};
    std::array<int, 3> n{1, 1, 1};
    std::vector<int> id;  // -1: none
    int at(const std::array<int, 3>& i) const;
  };

  // Whether the level's knot range [U_a[first_a], U_a[first_a + spans_a]] (every direction
  // a < d) lies in one box of Omega^region (none for region >= nlvl).
  bool knotRangeInRegion(int level, int region, const std::array<int, 3>& first,
                         const std::array<int, 3>& spans) const;
  // Whether the support of the level's B-spline with tensor index i lies in Omega^region.
  bool supportInRegion(int level, int region, const std::array<int, 3>& i) const;
  // Whether the level's cell of knot spans `spans` lies in Omega^region.
  bool cellInRegion(int level, int region, const std::array<int, 3>& spans) const;
  void buildFunctions();
  void buildElements();
  // The elements of level l: the cells of Omega^l outside Omega^{l+1}, with their ids.
  void buildLevelElements(int l);
  // Element el's active functions and extraction operator C_e (rows: functions, sorted).
  void buildExtraction(Element& el) const;
  // THB truncation of T^level's local block MT: zeroes the rows of the level's functions on
  // the cell `spans` whose support lies in Omega^level.
  void truncateRefinement(int level, const std::array<int, 3>& spans, Eigen::MatrixXd& MT) const;
  void buildGeometry();
  Eigen::MatrixXd localRefinement(int level, const std::array<int, 3>& childSpans,
                                  const std::array<int, 3>& parentSpans) const;

  NurbsPatch base_;
  HierarchyOptions options_;
  int d_ = 1;
  int nlvl_ = 1;
  std::array<int, 3> p_{0, 0, 0};
  int nloc_ = 1;                                // (p+1)^d
  std::vector<std::vector<KnotVector>> knots_;  // [level][dir]
  std::vector<LevelBoxes> regions_;             // Omega^0 .. Omega^{nlvl-1}
  // [level][dir]: rows of T^{level} (level-1 -> level): for fine j, pairs (coarse i, value).
  std::vector<std::array<std::vector<std::vector<std::pair<int, double>>>, 3>> rows_;
  std::vector<int> funcLevel_;
  std::vector<std::array<int, 3>> funcIndex_;
  std::vector<LevelIndex> funcId_;  // per level: tensor index -> function number
  std::vector<LevelIndex> elemId_;  // per level: cell ordinal -> element number
  std::vector<std::array<std::vector<int>, 3>> cellSpans_;  // [level][dir]: non-empty spans
  std::vector<int> levelFuncStart_, levelElemStart_;
  std::vector<Element> elements_;
  Eigen::MatrixXd identity_;  // (p+1)^d identity, the extraction of identity elements
  Eigen::MatrixXd points_;
  Eigen::VectorXd weights_;
};

}  // namespace ffriga
