// Tests of HierarchicalSpace (THB and HB) on random nested box configurations in 2D and 3D,
// one box per level and several apart: partition of unity, linear independence, exact
// geometry, reproduction of the coarse space, agreement with a brute-force finest-level
// representation, nlvl = 1 = tensor space.
#include "common/splines/hierarchical_space.h"

#include <catch2/catch.hpp>

#include <map>
#include <sstream>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "common/splines/refinement.h"
#include "tests/support/test_util.h"

namespace ffriga {
namespace {

using test::uniform;
using test::uniformInt;

NurbsPatch randomPatch(const std::vector<int>& degrees, const std::vector<int>& interior) {
  std::vector<KnotVector> U;
  int n = 1;
  for (std::size_t a = 0; a < degrees.size(); ++a) {
    U.push_back(test::randomKnots(degrees[a], interior[a]));
    n *= U.back().numBasis();
  }
  const int s = degrees.size() == 3 ? 3 : 2;
  Eigen::MatrixXd P = Eigen::MatrixXd::Random(n, s);
  Eigen::VectorXd w(n);
  for (int k = 0; k < n; ++k) w(k) = uniform(0.5, 2.0);
  return NurbsPatch(std::move(U), std::move(P), std::move(w));
}

// Random nested boxes aligned with the level grids; each box spans at least p+1 cells of
// the previous level along every direction (so it holds a function of its own level) when
// the previous box is wide enough.
// A random box of level l inside `outer`, on the level-(l-1) grid.
ParamBox randomBoxInside(const NurbsPatch& patch, const std::vector<std::vector<KnotVector>>& knots,
                         int l, const ParamBox& outer) {
  ParamBox b;
  for (int a = 0; a < patch.paramDim(); ++a) {
    std::vector<double> br;
    for (double u : knots[l - 1][a].breaks())
      if (u >= outer.lower[a] && u <= outer.upper[a]) br.push_back(u);
    const int nc = static_cast<int>(br.size()) - 1;
    const int w = std::min(nc, uniformInt(std::min(nc, patch.degree(a) + 1), nc));
    const int lo = uniformInt(0, nc - w);
    b.lower[a] = br[lo];
    b.upper[a] = br[lo + w];
  }
  return b;
}

ParamBox domainOf(const NurbsPatch& patch) {
  ParamBox box;
  for (int a = 0; a < patch.paramDim(); ++a) {
    box.lower[a] = patch.knots(a).front();
    box.upper[a] = patch.knots(a).back();
  }
  return box;
}

HierarchyOptions randomHierarchy(const NurbsPatch& patch, int levels, bool truncated) {
  HierarchyOptions o;
  o.levels = levels;
  o.truncated = truncated;
  const auto knots = levelKnotVectors(patch, levels);
  ParamBox prev = domainOf(patch);
  for (int l = 1; l < levels; ++l) {
    const ParamBox b = randomBoxInside(patch, knots, l, prev);
    o.boxes.push_back({b});
    prev = b;
  }
  return o;
}

// Two boxes per level, apart: level 1 splits the domain along direction 0 into a lower and
// an upper part with at least one level-0 cell between them; every finer level puts one
// random box inside each box of the level before (so the two chains stay apart).
HierarchyOptions randomTwoChainHierarchy(const NurbsPatch& patch, int levels, bool truncated) {
  HierarchyOptions o;
  o.levels = levels;
  o.truncated = truncated;
  const auto knots = levelKnotVectors(patch, levels);
  // At least 5 cells along direction 0: each part 2 cells or more (4 level-1 cells hold a
  // B-spline of degree 3), 1 cell or more between them.
  const std::vector<double> br = knots[0][0].breaks();
  const int nc = static_cast<int>(br.size()) - 1;
  REQUIRE(nc >= 5);
  const int cut = uniformInt(2, nc - 3);
  ParamBox lower = domainOf(patch), upper = domainOf(patch);
  lower.upper[0] = br[cut];
  upper.lower[0] = br[uniformInt(cut + 1, nc - 2)];
  std::vector<ParamBox> prev{lower, upper};
  for (int l = 1; l < levels; ++l) {
    LevelBoxes level;
    for (const ParamBox& outer : prev) level.push_back(randomBoxInside(patch, knots, l, outer));
    o.boxes.push_back(level);
    prev = level;
  }
  return o;
}

std::string describe(const HierarchyOptions& o) {
  std::ostringstream s;
  for (const LevelBoxes& level : o.boxes) {
    s << "{";
    for (const ParamBox& b : level)
      s << "[" << b.lower[0] << "," << b.upper[0] << "]x[" << b.lower[1] << "," << b.upper[1]
        << "]x[" << b.lower[2] << "," << b.upper[2] << "] ";
    s << "} ";
  }
  return s.str();
}

Eigen::VectorXd randomPointIn(const ElementBox& box, int d) {
  Eigen::VectorXd x(d);
  for (int a = 0; a < d; ++a) x(a) = uniform(box.lower[a], box.upper[a]);
  return x;
}

// Brute force: every active function as a vector of finest-level coefficients, by refining
// e_i level by level with the dense 1D transfer matrices and (THB) dropping the
// coefficients of B-splines whose support lies in the next region.
std::vector<std::map<long long, double>> finestCoefficients(const HierarchicalSpace& H) {
  const int d = H.paramDim(), L = H.numLevels();
  std::vector<std::array<Eigen::MatrixXd, 3>> T(L);
  for (int l = 1; l < L; ++l)
    for (int a = 0; a < d; ++a)
      T[l][a] = Eigen::MatrixXd(refinementMatrix(H.levelKnots(l - 1)[a], H.levelKnots(l)[a]));
  auto nb = [&](int l, int a) { return a < d ? H.levelKnots(l)[a].numBasis() : 1; };
  auto key = [&](int l, const std::array<int, 3>& i) {
    return i[0] + static_cast<long long>(nb(l, 0)) * (i[1] + nb(l, 1) * i[2]);
  };
  auto inRegion = [&](int l, int r, const std::array<int, 3>& i) {
    if (r >= L) return false;
    for (const ParamBox& box : H.region(r)) {
      bool inside = true;
      for (int a = 0; a < d; ++a) {
        const KnotVector& U = H.levelKnots(l)[a];
        inside = inside && U[i[a]] >= box.lower[a] && U[i[a] + U.degree() + 1] <= box.upper[a];
      }
      if (inside) return true;
    }
    return false;
  };
  std::vector<std::map<long long, double>> out;
  for (int k = 0; k < H.numFunctions(); ++k) {
    int l = H.functionLevel(k);
    std::map<long long, double> c{{key(l, H.functionTensorIndex(k)), 1.0}};
    for (; l + 1 < L; ++l) {
      std::map<long long, double> f;
      for (const auto& [ki, v] : c) {
        std::array<int, 3> i{static_cast<int>(ki % nb(l, 0)),
                             static_cast<int>((ki / nb(l, 0)) % nb(l, 1)),
                             static_cast<int>(ki / nb(l, 0) / nb(l, 1))};
        // Fine functions j with T(j_a, i_a) != 0 in every direction.
        std::array<std::vector<int>, 3> nz;
        for (int a = 0; a < 3; ++a) {
          if (a >= d) nz[a] = {0};
          for (int j = 0; a < d && j < nb(l + 1, a); ++j)
            if (T[l + 1][a](j, i[a]) != 0.0) nz[a].push_back(j);
        }
        for (int j2 : nz[2])
          for (int j1 : nz[1])
            for (int j0 : nz[0]) {
              const std::array<int, 3> j{j0, j1, j2};
              double t = v;
              for (int a = 0; a < d; ++a) t *= T[l + 1][a](j[a], i[a]);
              f[key(l + 1, j)] += t;
            }
      }
      if (H.truncated()) {
        for (auto it = f.begin(); it != f.end();) {
          std::array<int, 3> j{static_cast<int>(it->first % nb(l + 1, 0)),
                               static_cast<int>((it->first / nb(l + 1, 0)) % nb(l + 1, 1)),
                               static_cast<int>(it->first / nb(l + 1, 0) / nb(l + 1, 1))};
          it = inRegion(l + 1, l + 1, j) ? f.erase(it) : std::next(it);
        }
      }
      c.swap(f);
    }
    out.push_back(std::move(c));
  }
  return out;
}

void checkSpace(const NurbsPatch& patch, const HierarchyOptions& o) {
  const HierarchicalSpace H(patch, o);
  const int d = H.paramDim();
  const int nf = H.numFunctions();
  INFO("d = " << d << ", levels = " << o.levels << ", truncated = " << o.truncated
              << ", functions = " << nf << ", elements = " << H.numElements() << ", boxes "
              << describe(o));
  const double size =
      (patch.points().colwise().maxCoeff() - patch.points().colwise().minCoeff()).maxCoeff();
  // Collocation matrix: (p+1)^d random points in every element (generically enough to
  // separate the functions on each element, which are independent polynomials there).
  int nloc = 1;
  for (int a = 0; a < d; ++a) nloc *= patch.degree(a) + 1;
  const int per = nloc;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(H.numElements() * per, nf);
  Eigen::MatrixXd coarse(H.numElements() * per, patch.numControlPoints());
  coarse.setZero();
  const auto brute = finestCoefficients(H);
  const std::vector<KnotVector>& fine = H.levelKnots(H.numLevels() - 1);
  double errPou = 0, errGeo = 0, errBrute = 0;
  PatchBasis B, R, T;
  for (int e = 0; e < H.numElements(); ++e) {
    const ElementBox box = H.element(e);
    for (int q = 0; q < per; ++q) {
      const Eigen::VectorXd xi = randomPointIn(box, d);
      REQUIRE(H.findElement(xi.data()) >= 0);
      H.elementBsplineBasis(e, xi.data(), 2, B);
      const int row = e * per + q;
      for (std::size_t c = 0; c < B.index.size(); ++c) M(row, B.index[c]) = B.table(0, c);
      // Scale of each derivative row: the largest finest-level B-spline of the row (1/h^k);
      // errors are measured relative to it (values: absolute).
      int spans[3] = {0, 0, 0};
      for (int a = 0; a < d; ++a) spans[a] = fine[a].findSpan(xi(a));
      Eigen::MatrixXd Tf;
      tensorBasis(fine, spans, xi.data(), 2, Tf);
      const Eigen::VectorXd scale = Tf.cwiseAbs().rowwise().maxCoeff().cwiseMax(1.0);
      if (o.truncated) {  // partition of unity: values sum to 1, derivatives to 0
        Eigen::VectorXd sum = B.table.rowwise().sum();
        sum(0) -= 1.0;
        errPou = std::max(errPou, sum.cwiseQuotient(scale).cwiseAbs().maxCoeff());
      }
      patch.bsplineBasis(xi.data(), 0, T);
      for (std::size_t c = 0; c < T.index.size(); ++c) coarse(row, T.index[c]) = T.table(0, c);
      // Geometry and its derivatives against the original patch.
      H.elementBasis(e, xi.data(), 2, R);
      Eigen::MatrixXd P(R.index.size(), patch.spaceDim());
      for (int c = 0; c < P.rows(); ++c) P.row(c) = H.controlPoints().row(R.index[c]);
      const Eigen::MatrixXd X = R.table * P;
      const PatchPoint ref = patch.evaluate(xi.data(), 2);
      errGeo = std::max(errGeo, (X.row(0).transpose() - ref.x).cwiseAbs().maxCoeff() / size);
      // Brute-force finest-level values with derivatives.
      for (std::size_t c = 0; c < B.index.size(); ++c) {
        Eigen::VectorXd v = Eigen::VectorXd::Zero(Tf.rows());
        int col = 0;
        const int q1 = d > 1 ? fine[1].degree() : 0, q2 = d > 2 ? fine[2].degree() : 0;
        for (int j2 = 0; j2 <= q2; ++j2)
          for (int j1 = 0; j1 <= q1; ++j1)
            for (int j0 = 0; j0 <= fine[0].degree(); ++j0, ++col) {
              const long long i0 = spans[0] - fine[0].degree() + j0;
              const long long i1 = d > 1 ? spans[1] - q1 + j1 : 0;
              const long long i2 = d > 2 ? spans[2] - q2 + j2 : 0;
              const long long n0 = fine[0].numBasis(), n1 = d > 1 ? fine[1].numBasis() : 1;
              const auto it = brute[B.index[c]].find(i0 + n0 * (i1 + n1 * i2));
              if (it != brute[B.index[c]].end()) v += it->second * Tf.col(col);
            }
        errBrute =
            std::max(errBrute, (v - B.table.col(c)).cwiseQuotient(scale).cwiseAbs().maxCoeff());
      }
    }
  }
  // Round-off of sums of O(10-100) terms, relative to the row's scale: ~1e-15; 1e-12
  // leaves a wide margin.
  CHECK(errPou < 1e-12);
  // Relative to the patch size; both sides are rational maps of O(1) terms: 1e-13.
  CHECK(errGeo < 1e-13);
  // Brute force, relative to the row's scale (values: absolute): products of up to L - 1
  // two-scale blocks with O(1) entries, round-off ~1e-15.
  CHECK(errBrute < 1e-12);
  // Linear independence: full column rank of the collocation matrix. Singular values of
  // a well-posed basis are O(1e-3..1); rank deficiency shows as < 1e-12 relative.
  Eigen::BDCSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  CHECK(sv(sv.size() - 1) / sv(0) > 1e-10);
  // Reproduction: every coarse B-spline is a combination of the active functions (least
  // squares on the collocation points; consistent system, residual at round-off). Solved by
  // column-pivoted QR: BDCSVD's solve left a residual of 0.04 on one random two-chain case
  // whose QR and JacobiSVD residuals were 1e-15 (every element's local fit exact).
  const Eigen::MatrixXd C = Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(M).solve(coarse);
  CHECK((M * C - coarse).cwiseAbs().maxCoeff() < 1e-11);
}

TEST_CASE("THB and HB spaces on random nested boxes in 2D", "[hierarchical]") {
  for (int trial = 0; trial < 6; ++trial) {
    const NurbsPatch patch =
        randomPatch({uniformInt(1, 3), uniformInt(1, 3)}, {uniformInt(2, 4), uniformInt(2, 4)});
    const int levels = uniformInt(2, 4);
    for (bool truncated : {true, false}) {
      checkSpace(patch, randomHierarchy(patch, levels, truncated));
    }
  }
}

TEST_CASE("THB and HB spaces on random nested boxes in 3D", "[hierarchical]") {
  for (int trial = 0; trial < 2; ++trial) {
    const NurbsPatch patch = randomPatch({uniformInt(1, 2), uniformInt(1, 2), uniformInt(1, 2)},
                                         {1, uniformInt(1, 2), 1});
    for (bool truncated : {true, false}) checkSpace(patch, randomHierarchy(patch, 3, truncated));
  }
}

TEST_CASE("THB and HB spaces on two chains of boxes apart", "[hierarchical]") {
  for (int trial = 0; trial < 4; ++trial) {
    const NurbsPatch patch =
        randomPatch({uniformInt(1, 3), uniformInt(1, 3)}, {uniformInt(4, 6), uniformInt(2, 4)});
    const int levels = uniformInt(2, 4);
    for (bool truncated : {true, false})
      checkSpace(patch, randomTwoChainHierarchy(patch, levels, truncated));
  }
  const NurbsPatch solid = randomPatch({uniformInt(1, 2), 1, uniformInt(1, 2)}, {4, 1, 1});
  for (bool truncated : {true, false})
    checkSpace(solid, randomTwoChainHierarchy(solid, 3, truncated));
}

TEST_CASE("two boxes apart refine like the same boxes in two separate hierarchies",
          "[hierarchical]") {
  // Far apart, each chain of boxes adds exactly the functions and elements it adds alone:
  // counts(both) - counts(none) = sum over the chains of counts(chain) - counts(none).
  const NurbsPatch one = randomPatch({2, 2}, {0, 0});  // one element, [0,1]^2
  const NurbsPatch patch =
      insertKnots(insertKnots(one, 0, uniformInsertionKnots(one.knots(0), 7)), 1,
                  uniformInsertionKnots(one.knots(1), 3));  // 8 x 4 uniform cells
  HierarchyOptions both;
  both.levels = 3;
  both.boxes = {
      {ParamBox{{0, 0, 0}, {0.25, 1, 0}}, ParamBox{{0.625, 0, 0}, {1, 1, 0}}},
      {ParamBox{{0, 0.25, 0}, {0.125, 0.75, 0}}, ParamBox{{0.75, 0, 0}, {0.9375, 0.5, 0}}}};
  HierarchyOptions first = both, second = both;
  for (int l = 0; l < 2; ++l) {
    first.boxes[l] = {both.boxes[l][0]};
    second.boxes[l] = {both.boxes[l][1]};
  }
  const HierarchicalSpace H2(patch, both), H0(patch, HierarchyOptions{}), Ha(patch, first),
      Hb(patch, second);
  CHECK(H2.numFunctions() - H0.numFunctions() ==
        (Ha.numFunctions() - H0.numFunctions()) + (Hb.numFunctions() - H0.numFunctions()));
  CHECK(H2.numElements() - H0.numElements() ==
        (Ha.numElements() - H0.numElements()) + (Hb.numElements() - H0.numElements()));
  checkSpace(patch, both);
}

TEST_CASE("one level is the tensor space", "[hierarchical]") {
  const NurbsPatch patch = randomPatch({3, 2}, {3, 4});
  const HierarchicalSpace H(patch, HierarchyOptions{});
  const TensorSpace S(patch);
  REQUIRE(H.numFunctions() == S.numFunctions());
  REQUIRE(H.numElements() == S.numElements());
  CHECK(H.controlPoints() == S.controlPoints());  // same numbering, coefficients unchanged
  CHECK(H.weights() == S.weights());
  PatchBasis a, b;
  for (int e = 0; e < H.numElements(); ++e) {
    CHECK(H.element(e).lower == S.element(e).lower);
    const Eigen::VectorXd xi = randomPointIn(H.element(e), 2);
    CHECK(H.findElement(xi.data()) == S.findElement(xi.data()));
    H.elementBasis(e, xi.data(), 2, a);
    S.elementBasis(e, xi.data(), 2, b);
    CHECK(a.index == b.index);
    // The same arithmetic on the same data: identical up to the last bit or two.
    CHECK((a.table - b.table).cwiseAbs().maxCoeff() < 1e-14);
  }
}

TEST_CASE("hierarchy boxes are checked and snapped", "[hierarchical]") {
  const NurbsPatch patch = randomPatch({2, 2}, {0, 0});  // one element, [0,1]^2
  const NurbsPatch fine =
      insertKnots(insertKnots(patch, 0, uniformInsertionKnots(patch.knots(0), 7)), 1,
                  uniformInsertionKnots(patch.knots(1), 7));  // 8 x 8
  HierarchyOptions o;
  o.levels = 3;
  o.boxes = {{ParamBox{{0, 0.5, 0}, {0.5, 1, 0}}}, {ParamBox{{0, 0.75, 0}, {0.25, 1, 0}}}};
  CHECK(validateBoxes(fine, o).reason.empty());
  o.boxes[0][0].upper[0] = 0.5 + 1e-12;  // snapped back onto the knot line
  CHECK(validateBoxes(fine, o).reason.empty());
  CHECK(o.boxes[0][0].upper[0] == 0.5);
  o.boxes[0][0].upper[0] = 0.51;
  CHECK_THAT(validateBoxes(fine, o).reason, Catch::Contains("not a knot line of level 0"));
  o.boxes[0][0].upper[0] = 1.5;
  CHECK_THAT(validateBoxes(fine, o).reason, Catch::Contains("outside the parameter domain"));
  o.boxes[0][0].upper[0] = 0.5;
  o.boxes[1][0].upper[0] = 0.625;
  CHECK_THAT(validateBoxes(fine, o).reason, Catch::Contains("not nested"));
  o.boxes[1][0] = ParamBox{{0.25, 0.75, 0}, {0.3125, 0.875, 0}};  // one level-1 cell wide
  CHECK_THAT(validateBoxes(fine, o).reason, Catch::Contains("too narrow"));
  o.boxes[1][0] = ParamBox{{0, 0.75, 0}, {0.25, 1, 0}};
  // A second box on level 1: apart (one level-0 cell between) is fine; touching or
  // overlapping is not, and its problem names it (member 1).
  o.boxes[0].push_back(ParamBox{{0.625, 0, 0}, {1, 0.5, 0}});
  CHECK(validateBoxes(fine, o).reason.empty());
  o.boxes[0][1].lower[0] = 0.5;
  BoxProblem touching = validateBoxes(fine, o);
  CHECK_THAT(touching.reason, Catch::Contains("overlap or touch"));
  CHECK(touching.box == 0);
  CHECK(touching.member == 1);
  o.boxes[0][1].lower[0] = 0.375;
  CHECK_THAT(validateBoxes(fine, o).reason, Catch::Contains("overlap or touch"));
  o.boxes[0][1].lower[0] = 0.625;
  o.boxes[1].push_back(ParamBox{{0.75, 0, 0}, {1, 0.25, 0}});  // inside level 1's second box
  CHECK(validateBoxes(fine, o).reason.empty());
  o.boxes[1][1] = ParamBox{{0.5, 0.5, 0}, {0.625, 0.625, 0}};  // in neither box of level 1
  CHECK_THAT(validateBoxes(fine, o).reason, Catch::Contains("not nested"));
  o.boxes[1].pop_back();
  o.boxes[1].clear();
  CHECK_THAT(validateBoxes(fine, o).reason, Catch::Contains("without a box"));
  o.boxes.pop_back();
  CHECK_THAT(validateBoxes(fine, o).reason,
             Catch::Contains("expected one entry of boxes per refined level"));
  CHECK_THROWS_AS(HierarchicalSpace(fine, o), std::invalid_argument);
}

}  // namespace
}  // namespace ffriga
