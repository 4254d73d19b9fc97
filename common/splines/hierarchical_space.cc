#include "common/splines/hierarchical_space.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "common/base/error.h"
#include "common/splines/refinement.h"

namespace ffriga {

namespace {

// Upper bound on nlvl: 2^-30 of a span is far below any physical element size and keeps
// knot values exactly representable.
constexpr int kMaxLevels = 30;

KnotVector halved(const KnotVector& U) {
  std::vector<double> k = U.knots();
  const std::vector<double> mid = uniformInsertionKnots(U, 1);
  k.insert(k.end(), mid.begin(), mid.end());
  std::sort(k.begin(), k.end());
  return KnotVector(std::move(k), U.degree());
}

template <class F>
void forEachIndex(const std::array<int, 3>& lo, const std::array<int, 3>& n, F f) {
  std::array<int, 3> i{0, 0, 0};
  for (i[2] = lo[2]; i[2] < lo[2] + n[2]; ++i[2])
    for (i[1] = lo[1]; i[1] < lo[1] + n[1]; ++i[1])
      for (i[0] = lo[0]; i[0] < lo[0] + n[0]; ++i[0]) f(i);
}

// Spans of the ancestors of a level-L cell with the given spans: anc[m] = the level-m cell
// that contains the cell's midpoint, m = 0 .. L (anc[L] = spans).
std::vector<std::array<int, 3>> ancestorSpans(const std::vector<std::vector<KnotVector>>& knots,
                                              int d, int L, const std::array<int, 3>& spans) {
  std::vector<std::array<int, 3>> anc(L + 1);
  anc[L] = spans;
  std::array<double, 3> mid{0, 0, 0};
  for (int a = 0; a < d; ++a) {
    const KnotVector& U = knots[L][a];
    mid[a] = 0.5 * (U[spans[a]] + U[spans[a] + 1]);
  }
  for (int m = L - 1; m >= 0; --m) {
    for (int a = 0; a < d; ++a) anc[m][a] = knots[m][a].findSpan(mid[a]);
  }
  return anc;
}

}  // namespace

std::vector<std::vector<KnotVector>> levelKnotVectors(const NurbsPatch& patch, int levels) {
  std::vector<std::vector<KnotVector>> k(1, patch.knotVectors());
  for (int l = 1; l < levels; ++l) {
    k.emplace_back();
    for (const auto& U : k[l - 1]) k[l].push_back(halved(U));
  }
  return k;
}

std::string checkLevels(const NurbsPatch& patch, int levels) {
  if (levels < 1 || levels > kMaxLevels) {
    return Str() << "expected 1 to " << kMaxLevels << " levels, found " << levels;
  }
  // The level knot vectors cover the whole domain: cap their size (2^20 spans per
  // direction, 8 MB of knots) before building them.
  for (int a = 0; a < patch.paramDim(); ++a) {
    const double spans = std::ldexp(patch.knots(a).numElements(), levels - 1);
    if (spans > 1 << 20) {
      return Str() << levels << " levels give " << spans << " knot spans along direction " << a
                   << " on the finest level (at most " << (1 << 20)
                   << " supported): more levels than the knot spans allow";
    }
  }
  return "";
}

bool intervalInBoxes(const LevelBoxes& boxes, int a, double lo, double hi) {
  for (const ParamBox& box : boxes)
    if (lo >= box.lower[a] && hi <= box.upper[a]) return true;
  return false;
}

bool boxInside(const ParamBox& b, const ParamBox& outer, int d) {
  for (int a = 0; a < d; ++a)
    if (b.lower[a] < outer.lower[a] || b.upper[a] > outer.upper[a]) return false;
  return true;
}

namespace {

// Box `box` of level l = b + 1 along direction a: snapped onto the level-(l-1) knot lines,
// non-empty, and wide enough for one level-l B-spline. Empty reason: no problem.
std::string checkBoxDirection(const std::vector<std::vector<KnotVector>>& knots, int l, int a,
                              ParamBox& box) {
  const KnotVector& U = knots[l - 1][a];
  const double tol = 1e-9 * (U.back() - U.front());
  for (double* x : {&box.lower[a], &box.upper[a]}) {
    if (*x < U.front() - tol || *x > U.back() + tol) {
      return Str() << "bound " << *x << " lies outside the parameter domain [" << U.front() << ", "
                   << U.back() << "]";
    }
    const std::vector<double> br = U.breaks();
    const auto it = std::lower_bound(br.begin(), br.end(), *x);
    const double above = it == br.end() ? br.back() : *it;
    const double below = it == br.begin() ? br.front() : *(it - 1);
    const double nearest = std::abs(above - *x) < std::abs(*x - below) ? above : below;
    if (std::abs(nearest - *x) > tol) {
      return Str() << "bound " << *x << " is not a knot line of level " << l - 1
                   << " (boxes of level " << l << " must be unions of level-" << l - 1
                   << " cells), nearest knot lines: " << below << " and " << above;
    }
    *x = nearest;
  }
  if (!(box.lower[a] < box.upper[a])) {
    return Str() << "empty box: lower bound " << box.lower[a] << " is not below upper bound "
                 << box.upper[a];
  }
  // At least one level-l B-spline with its support inside the box along a.
  const KnotVector& V = knots[l][a];
  const int p = V.degree();
  for (int j = 0; j < V.numBasis(); ++j)
    if (V[j] >= box.lower[a] && V[j + p + 1] <= box.upper[a]) return "";
  return Str() << "the box of level " << l << " is too narrow: no degree-" << p
               << " B-spline of level " << l << " has its support inside [" << box.lower[a] << ", "
               << box.upper[a] << "] (more levels than the knot spans allow: widen the box)";
}

// Whether two closed boxes are apart: separated along at least one of the d directions
// (touching counts as not apart).
bool boxesApart(const ParamBox& x, const ParamBox& y, int d) {
  for (int a = 0; a < d; ++a)
    if (x.upper[a] < y.lower[a] || y.upper[a] < x.lower[a]) return true;
  return false;
}

std::string describeBox(const ParamBox& b, int d) {
  Str s;
  for (int a = 0; a < d; ++a)
    s << (a ? " x " : "") << "[" << b.lower[a] << ", " << b.upper[a] << "]";
  return s;
}

// Box k of level l = b + 1 against the others: inside a box of level l - 1 (a level of one
// box names the direction and the two intervals), apart from the level's other boxes.
BoxProblem checkBoxPlacement(const HierarchyOptions& o, int b, int k, int d) {
  const ParamBox& box = o.boxes[b][k];
  if (b > 0 && o.boxes[b - 1].size() == 1) {
    const ParamBox& outer = o.boxes[b - 1][0];
    for (int a = 0; a < d; ++a) {
      if (box.lower[a] < outer.lower[a] || box.upper[a] > outer.upper[a]) {
        return {b, k, a,
                Str() << "boxes are not nested: [" << box.lower[a] << ", " << box.upper[a]
                      << "] of level " << b + 1 << " is not inside [" << outer.lower[a] << ", "
                      << outer.upper[a] << "] of level " << b};
      }
    }
  } else if (b > 0) {
    bool nested = false;
    for (const ParamBox& outer : o.boxes[b - 1]) nested = nested || boxInside(box, outer, d);
    if (!nested) {
      return {b, k, -1,
              Str() << "boxes are not nested: " << describeBox(box, d) << " of level " << b + 1
                    << " is not inside any box of level " << b};
    }
  }
  for (int m = 0; m < k; ++m) {
    if (!boxesApart(box, o.boxes[b][m], d)) {
      return {b, k, -1,
              Str() << "boxes " << m << " and " << k << " of level " << b + 1
                    << " overlap or touch (" << describeBox(o.boxes[b][m], d) << " and "
                    << describeBox(box, d) << "): the boxes of a level must lie apart"};
    }
  }
  return {};
}

}  // namespace

BoxProblem validateBoxes(const NurbsPatch& patch, HierarchyOptions& o) {
  const int d = patch.paramDim();
  const std::string levelProblem = checkLevels(patch, o.levels);
  if (!levelProblem.empty()) return {-1, 0, -1, levelProblem};
  if (static_cast<int>(o.boxes.size()) != o.levels - 1) {
    return {-1, 0, -1,
            Str() << "expected one entry of boxes per refined level (" << o.levels - 1 << " for "
                  << o.levels << " levels), found " << o.boxes.size()};
  }
  const auto knots = levelKnotVectors(patch, o.levels);
  for (int b = 0; b < o.levels - 1; ++b) {
    if (o.boxes[b].empty()) return {b, 0, -1, "a refined level without a box"};
    for (int k = 0; k < static_cast<int>(o.boxes[b].size()); ++k) {
      for (int a = 0; a < d; ++a) {
        const std::string why = checkBoxDirection(knots, b + 1, a, o.boxes[b][k]);
        if (!why.empty()) return {b, k, a, why};
      }
      const BoxProblem placement = checkBoxPlacement(o, b, k, d);
      if (!placement.reason.empty()) return placement;
    }
  }
  return {};
}

NurbsPatch globalReferencePatch(const NurbsPatch& patch, const HierarchyOptions& o) {
  const auto knots = levelKnotVectors(patch, o.levels);
  NurbsPatch out = patch;
  for (int a = 0; a < patch.paramDim(); ++a) {
    std::vector<double> X;
    for (int l = 1; l < o.levels; ++l) {
      const KnotVector& U = knots[l - 1][a];
      for (int s : U.elementSpans()) {
        // The level-l knot line inside span s, computed as uniformInsertionKnots() does
        // (once, however many of the level's boxes the span lies in along a).
        if (intervalInBoxes(o.boxes[l - 1], a, U[s], U[s + 1]))
          X.push_back(U[s] + (U[s + 1] - U[s]) / 2);
      }
    }
    if (!X.empty()) out = insertKnots(out, a, X);
  }
  return out;
}

int HierarchicalSpace::LevelIndex::at(const std::array<int, 3>& i) const {
  int k = 0;
  for (int a = 2; a >= 0; --a) {
    const int r = i[a] - lo[a];
    if (r < 0 || r >= n[a]) return -1;
    k = k * n[a] + r;
  }
  return id[k];
}

HierarchicalSpace::HierarchicalSpace(const NurbsPatch& patch, HierarchyOptions options)
    : base_(patch), options_(std::move(options)), d_(patch.paramDim()), nlvl_(options_.levels) {
  const BoxProblem problem = validateBoxes(base_, options_);
  if (!problem.reason.empty()) {
    throw std::invalid_argument(Str() << "hierarchy box " << problem.box + 1 << " direction "
                                      << problem.dir << ": " << problem.reason);
  }
  for (int a = 0; a < d_; ++a) {
    p_[a] = patch.degree(a);
    nloc_ *= p_[a] + 1;
  }
  knots_ = levelKnotVectors(base_, nlvl_);
  ParamBox domain;
  for (int a = 0; a < d_; ++a) {
    domain.lower[a] = base_.knots(a).front();
    domain.upper[a] = base_.knots(a).back();
  }
  regions_.push_back({domain});
  for (const LevelBoxes& b : options_.boxes) regions_.push_back(b);
  rows_.resize(nlvl_);
  for (int l = 1; l < nlvl_; ++l) {
    for (int a = 0; a < d_; ++a) {
      const Eigen::SparseMatrix<double> T = refinementMatrix(knots_[l - 1][a], knots_[l][a]);
      auto& rows = rows_[l][a];
      rows.assign(T.rows(), {});
      for (int i = 0; i < T.outerSize(); ++i) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(T, i); it; ++it) {
          if (it.value() != 0.0) rows[it.row()].emplace_back(i, it.value());
        }
      }
    }
  }
  identity_ = Eigen::MatrixXd::Identity(nloc_, nloc_);
  buildFunctions();
  buildElements();
  buildGeometry();
  // Weights folded into the extraction for elementBasis(): w_k C_e(k, j).
  for (Element& el : elements_) {
    Eigen::VectorXd w(el.functions.size());
    for (int k = 0; k < w.size(); ++k) w(k) = weights_(el.functions[k]);
    if (el.identity) {
      el.weightedT = w;  // K x 1: the weights of the local functions
    } else {
      el.weightedT = (w.asDiagonal() * el.extraction).transpose();
    }
  }
}

bool HierarchicalSpace::knotRangeInRegion(int level, int region, const std::array<int, 3>& first,
                                          const std::array<int, 3>& spans) const {
  if (region >= nlvl_) return false;
  for (const ParamBox& box : regions_[region]) {
    bool inside = true;
    for (int a = 0; a < d_ && inside; ++a) {
      const KnotVector& U = knots_[level][a];
      inside = U[first[a]] >= box.lower[a] && U[first[a] + spans[a]] <= box.upper[a];
    }
    if (inside) return true;
  }
  return false;
}

bool HierarchicalSpace::supportInRegion(int level, int region, const std::array<int, 3>& i) const {
  return knotRangeInRegion(level, region, i, {p_[0] + 1, p_[1] + 1, p_[2] + 1});
}

bool HierarchicalSpace::cellInRegion(int level, int region, const std::array<int, 3>& spans) const {
  return knotRangeInRegion(level, region, spans, {1, 1, 1});
}

void HierarchicalSpace::buildFunctions() {
  funcId_.resize(nlvl_);
  for (int l = 0; l < nlvl_; ++l) {
    LevelIndex& idx = funcId_[l];
    levelFuncStart_.push_back(static_cast<int>(funcLevel_.size()));
    // Index range of the level-l functions with support in one of Omega^l's boxes, per
    // direction (the range over all its boxes: the dense index covers the gaps too).
    for (int a = 0; a < d_; ++a) {
      const KnotVector& U = knots_[l][a];
      int lo = U.numBasis(), hi = -1;
      for (int j = 0; j < U.numBasis(); ++j) {
        if (intervalInBoxes(regions_[l], a, U[j], U[j + p_[a] + 1])) {
          lo = std::min(lo, j);
          hi = std::max(hi, j);
        }
      }
      idx.lo[a] = lo;
      idx.n[a] = std::max(0, hi - lo + 1);
    }
    idx.id.assign(static_cast<std::size_t>(idx.n[0]) * idx.n[1] * idx.n[2], -1);
    forEachIndex(idx.lo, idx.n, [&](const std::array<int, 3>& i) {
      if (!supportInRegion(l, l, i) || supportInRegion(l, l + 1, i)) return;
      int k = 0;
      for (int a = 2; a >= 0; --a) k = k * idx.n[a] + (i[a] - idx.lo[a]);
      idx.id[k] = static_cast<int>(funcLevel_.size());
      funcLevel_.push_back(l);
      funcIndex_.push_back(i);
    });
  }
  levelFuncStart_.push_back(static_cast<int>(funcLevel_.size()));
}

Eigen::MatrixXd HierarchicalSpace::localRefinement(int level, const std::array<int, 3>& cs,
                                                   const std::array<int, 3>& ps) const {
  // 1D blocks B_a(jl, il) = T^level_a(cs - p + jl, ps - p + il), then their Kronecker product
  // with the first direction fastest.
  Eigen::MatrixXd B[3];
  for (int a = 0; a < 3; ++a) {
    if (a >= d_) {
      B[a] = Eigen::MatrixXd::Ones(1, 1);
      continue;
    }
    const int p = p_[a];
    B[a] = Eigen::MatrixXd::Zero(p + 1, p + 1);
    for (int jl = 0; jl <= p; ++jl) {
      for (const auto& [i, v] : rows_[level][a][cs[a] - p + jl]) {
        const int il = i - (ps[a] - p);
        if (il >= 0 && il <= p) B[a](jl, il) = v;
      }
    }
  }
  Eigen::MatrixXd M(nloc_, nloc_);
  const int n0 = static_cast<int>(B[0].rows()), n1 = static_cast<int>(B[1].rows()),
            n2 = static_cast<int>(B[2].rows());
  for (int j2 = 0; j2 < n2; ++j2)
    for (int j1 = 0; j1 < n1; ++j1)
      for (int j0 = 0; j0 < n0; ++j0)
        for (int i2 = 0; i2 < n2; ++i2)
          for (int i1 = 0; i1 < n1; ++i1)
            for (int i0 = 0; i0 < n0; ++i0)
              M(j0 + n0 * (j1 + n1 * j2), i0 + n0 * (i1 + n1 * i2)) =
                  B[0](j0, i0) * B[1](j1, i1) * B[2](j2, i2);
  return M;
}

void HierarchicalSpace::buildElements() {
  elemId_.resize(nlvl_);
  cellSpans_.resize(nlvl_);
  for (int l = 0; l < nlvl_; ++l) {
    for (int a = 0; a < d_; ++a) cellSpans_[l][a] = knots_[l][a].elementSpans();
  }
  for (int l = 0; l < nlvl_; ++l) {
    levelElemStart_.push_back(static_cast<int>(elements_.size()));
    buildLevelElements(l);
  }
  levelElemStart_.push_back(static_cast<int>(elements_.size()));
  for (Element& el : elements_) buildExtraction(el);
}

void HierarchicalSpace::buildLevelElements(int l) {
  const auto& spans = cellSpans_;
  LevelIndex& idx = elemId_[l];
  // The range of cell ordinals over Omega^l's boxes, per direction.
  for (int a = 0; a < d_; ++a) {
    int lo = -1, hi = -2;
    for (int c = 0; c < static_cast<int>(spans[l][a].size()); ++c) {
      const int s = spans[l][a][c];
      if (intervalInBoxes(regions_[l], a, knots_[l][a][s], knots_[l][a][s + 1])) {
        if (lo < 0) lo = c;
        hi = c;
      }
    }
    idx.lo[a] = lo;
    idx.n[a] = hi - lo + 1;
  }
  idx.id.assign(static_cast<std::size_t>(idx.n[0]) * idx.n[1] * idx.n[2], -1);
  forEachIndex(idx.lo, idx.n, [&](const std::array<int, 3>& c) {
    Element el;
    el.level = l;
    for (int a = 0; a < d_; ++a) el.spans[a] = spans[l][a][c[a]];
    if (!cellInRegion(l, l, el.spans) || cellInRegion(l, l + 1, el.spans)) return;
    int k = 0;
    for (int a = 2; a >= 0; --a) k = k * idx.n[a] + (c[a] - idx.lo[a]);
    idx.id[k] = static_cast<int>(elements_.size());
    elements_.push_back(std::move(el));
  });
}

void HierarchicalSpace::truncateRefinement(int level, const std::array<int, 3>& spans,
                                           Eigen::MatrixXd& MT) const {
  int r = 0;
  forEachIndex({0, 0, 0}, {p_[0] + 1, d_ > 1 ? p_[1] + 1 : 1, d_ > 2 ? p_[2] + 1 : 1},
               [&](const std::array<int, 3>& j) {
                 std::array<int, 3> i{0, 0, 0};
                 for (int a = 0; a < d_; ++a) i[a] = spans[a] - p_[a] + j[a];
                 if (supportInRegion(level, level, i)) MT.row(r).setZero();
                 ++r;
               });
}

void HierarchicalSpace::buildExtraction(Element& el) const {
  // E_m maps level-m local coefficients to level-L local ones,
  // E_L = I, E_{m} = E_{m+1} Mask_{m+1} T_{m+1} (Mask: THB truncation, identity for HB).
  const int L = el.level;
  const std::vector<std::array<int, 3>> anc = ancestorSpans(knots_, d_, L, el.spans);
  std::vector<std::pair<int, Eigen::VectorXd>> rows;
  Eigen::MatrixXd E = Eigen::MatrixXd::Identity(nloc_, nloc_);
  for (int m = L; m >= 0; --m) {
    if (m < L) {
      Eigen::MatrixXd MT = localRefinement(m + 1, anc[m + 1], anc[m]);
      if (options_.truncated) truncateRefinement(m + 1, anc[m + 1], MT);
      E = E.lazyProduct(MT).eval();  // small: no (OpenMP-parallel) GEMM
    }
    int r = 0;
    forEachIndex({0, 0, 0}, {p_[0] + 1, d_ > 1 ? p_[1] + 1 : 1, d_ > 2 ? p_[2] + 1 : 1},
                 [&](const std::array<int, 3>& j) {
                   std::array<int, 3> i{0, 0, 0};
                   for (int a = 0; a < d_; ++a) i[a] = anc[m][a] - p_[a] + j[a];
                   const int f = funcId_[m].at(i);
                   // Knot insertion coefficients are non-negative: a column is zero only
                   // if the function vanishes on the element (exactly).
                   if (f >= 0 && E.col(r).cwiseAbs().maxCoeff() > 0.0) {
                     rows.emplace_back(f, E.col(r));
                   }
                   ++r;
                 });
  }
  std::sort(rows.begin(), rows.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  el.extraction.resize(rows.size(), nloc_);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    el.functions.push_back(rows[k].first);
    el.extraction.row(k) = rows[k].second.transpose();
  }
  el.identity = static_cast<int>(rows.size()) == nloc_ &&
                el.extraction == Eigen::MatrixXd::Identity(nloc_, nloc_);
  if (el.identity) el.extraction.resize(0, 0);  // elementExtraction() returns identity_
}

void HierarchicalSpace::buildGeometry() {
  // Memoised level-l coefficients g^l_i (see the header): THB without masks, HB with.
  const Eigen::MatrixXd Q0 = base_.homogeneous();
  const int cols = static_cast<int>(Q0.cols());
  std::vector<std::unordered_map<long long, Eigen::RowVectorXd>> memo(nlvl_);
  auto linear = [&](int l, const std::array<int, 3>& i) {
    long long k = 0;
    for (int a = d_ - 1; a >= 0; --a) k = k * knots_[l][a].numBasis() + i[a];
    return k;
  };
  std::function<Eigen::RowVectorXd(int, const std::array<int, 3>&)> coef =
      [&](int l, const std::array<int, 3>& i) -> Eigen::RowVectorXd {
    if (l == 0) return Q0.row(static_cast<int>(linear(0, i)));
    const long long key = linear(l, i);
    auto it = memo[l].find(key);
    if (it != memo[l].end()) return it->second;
    Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(cols);
    const auto& r0 = rows_[l][0][i[0]];
    const std::vector<std::pair<int, double>> one{{0, 1.0}};
    const auto& r1 = d_ > 1 ? rows_[l][1][i[1]] : one;
    const auto& r2 = d_ > 2 ? rows_[l][2][i[2]] : one;
    for (const auto& [j2, v2] : r2)
      for (const auto& [j1, v1] : r1)
        for (const auto& [j0, v0] : r0) {
          const std::array<int, 3> j{j0, j1, j2};
          if (!options_.truncated && !supportInRegion(l - 1, l, j)) continue;
          g += (v0 * v1 * v2) * coef(l - 1, j);
        }
    memo[l].emplace(key, g);
    return g;
  };
  const int n = static_cast<int>(funcLevel_.size());
  points_.resize(n, cols - 1);
  weights_.resize(n);
  for (int k = 0; k < n; ++k) {
    if (funcLevel_[k] == 0) {  // g^0 = Q^0 (THB and HB): the patch's own data, bit for bit
      const int i = static_cast<int>(linear(0, funcIndex_[k]));
      weights_(k) = base_.weights()(i);
      points_.row(k) = base_.points().row(i);
      continue;
    }
    const Eigen::RowVectorXd g = coef(funcLevel_[k], funcIndex_[k]);
    weights_(k) = g(cols - 1);
    points_.row(k) = g.head(cols - 1) / weights_(k);
  }
  // THB weights are refined weights (convex combinations of positive ones): positive. HB
  // weights are coefficients of W in a basis without partition of unity: they may be
  // negative (W = sum w_k B_k stays positive), but a zero weight leaves the function without
  // a control point.
  const double wmax = weights_.cwiseAbs().maxCoeff();
  for (int k = 0; k < n; ++k) {
    if (!(std::abs(weights_(k)) > 1e-12 * wmax)) {
      throw std::invalid_argument(
          Str() << "the non-truncated hierarchical basis gives function " << k << " (level "
                << funcLevel_[k] << ") the weight " << weights_(k)
                << ": the rational HB basis is not defined for these boxes; use THB (truncated)");
    }
  }
}

int HierarchicalSpace::numFunctionsOnLevel(int level) const {
  return levelFuncStart_[level + 1] - levelFuncStart_[level];
}
int HierarchicalSpace::numElementsOnLevel(int level) const {
  return levelElemStart_[level + 1] - levelElemStart_[level];
}

ElementBox HierarchicalSpace::element(int e) const {
  ElementBox box;
  const Element& el = elements_[e];
  box.level = el.level;
  for (int a = 0; a < d_; ++a) {
    box.lower[a] = knots_[el.level][a][el.spans[a]];
    box.upper[a] = knots_[el.level][a][el.spans[a] + 1];
  }
  return box;
}

int HierarchicalSpace::findElement(const double* xi) const {
  for (int l = nlvl_ - 1; l >= 0; --l) {
    std::array<int, 3> c{0, 0, 0};
    for (int a = 0; a < d_; ++a) {
      const int s = knots_[l][a].findSpan(xi[a]);
      const auto& sp = cellSpans_[l][a];
      c[a] = static_cast<int>(std::lower_bound(sp.begin(), sp.end(), s) - sp.begin());
    }
    const int e = elemId_[l].at(c);
    if (e >= 0) return e;
  }
  throw std::invalid_argument(Str() << "no element contains the parameter point");
}

void HierarchicalSpace::elementBsplineBasis(int e, const double* xi, int order,
                                            PatchBasis& out) const {
  const Element& el = elements_[e];
  if (el.identity) {
    tensorBasis(knots_[el.level], el.spans.data(), xi, order, out.table);
  } else {
    Eigen::MatrixXd table;
    tensorBasis(knots_[el.level], el.spans.data(), xi, order, table);
    out.table = table.lazyProduct(el.extraction.transpose());
  }
  out.index = el.functions;
}

void HierarchicalSpace::elementBasis(int e, const double* xi, int order, PatchBasis& out) const {
  // Fast path (no heap allocation after the first call): the weighted basis
  // Bw(r, k) = w_k B_k,r = sum_j b_{j,r} w_k C_e(k, j), then the quotient rule of
  // rationalize() (rational_basis.h).
  thread_local Eigen::MatrixXd table, Bw;
  thread_local Eigen::VectorXd W;
  const Element& el = elements_[e];
  tensorBasis(knots_[el.level], el.spans.data(), xi, order, table);
  const int rows = static_cast<int>(table.rows());
  const int n = static_cast<int>(el.functions.size());
  Bw.resize(rows, n);
  if (el.identity) {
    Bw.noalias() = table * el.weightedT.col(0).asDiagonal();
  } else {
    for (int r = 0; r < rows; ++r) Bw.row(r).noalias() = table.row(r) * el.weightedT;
  }
  W = Bw.rowwise().sum();
  out.table.resize(rows, n);
  const double invW = 1.0 / W(0);
  out.table.row(0) = Bw.row(0) * invW;
  if (order >= 1) {
    for (int a = 0; a < d_; ++a)
      out.table.row(1 + a) = (Bw.row(1 + a) - out.table.row(0) * W(1 + a)) * invW;
  }
  if (order >= 2) {
    for (int a = 0; a < d_; ++a) {
      for (int b = a; b < d_; ++b) {
        const int ab = secondDerivativeRow(d_, a, b);
        out.table.row(ab) = (Bw.row(ab) - out.table.row(1 + a) * W(1 + b) -
                             out.table.row(1 + b) * W(1 + a) - out.table.row(0) * W(ab)) *
                            invW;
      }
    }
  }
  out.index = el.functions;
}

std::vector<int> HierarchicalSpace::faceFunctions(int dir, int side) const {
  FFRIGA_CHECK(dir >= 0 && dir < d_ && (side == 0 || side == 1), "dir " << dir << " side " << side);
  std::vector<char> on(numFunctions(), 0);
  const int p = p_[dir];
  int stride = 1;
  for (int a = 0; a < dir; ++a) stride *= p_[a] + 1;
  for (const Element& el : elements_) {
    const KnotVector& U = knots_[el.level][dir];
    const int last = U.numBasis() - 1;
    if (side == 0 ? el.spans[dir] != p : el.spans[dir] != last) continue;
    const int jl = side == 0 ? 0 : p;  // the local function that is 1 on the face
    for (int c = 0; c < nloc_; ++c) {
      if ((c / stride) % (p + 1) != jl) continue;
      const Eigen::MatrixXd& C = el.identity ? identity_ : el.extraction;
      for (int r = 0; r < C.rows(); ++r) {
        if (C(r, c) != 0.0) on[el.functions[r]] = 1;
      }
    }
  }
  std::vector<int> f;
  for (int k = 0; k < numFunctions(); ++k)
    if (on[k]) f.push_back(k);
  return f;
}

}  // namespace ffriga
