// The paper's hierarchical body files and their global references (configs/bodies):
// the references' knot vectors equal the finest level inside the finest box (Sect. 5), and
// the hierarchical models are much smaller.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <set>
#include <string>

#include "preproc/input/body_config.h"

namespace ffriga {
namespace {

std::vector<double> knotsIn(const KnotVector& U, double lo, double hi) {
  std::vector<double> k;
  for (double u : U.knots())
    if (u >= lo && u <= hi) k.push_back(u);
  return k;
}

// The elements that touch the contact face inside the contact region, as (lower, upper)
// corners with the face direction's lower bound (the depth of the layer next to the face).
using FaceElement = std::array<double, 5>;
std::set<FaceElement> contactElements(const ContactConfig& c, const HierarchicalSpace& s) {
  const int dn = c.direction;
  std::set<FaceElement> out;
  for (int e = 0; e < s.numElements(); ++e) {
    const ElementBox b = s.element(e);
    const double face = c.upper ? s.levelKnots(0)[dn].knots().back()
                                        : s.levelKnots(0)[dn].knots().front();
    if ((c.upper ? b.upper[dn] : b.lower[dn]) != face) continue;
    FaceElement f{};
    f[0] = c.upper ? b.lower[dn] : b.upper[dn];
    bool inside = true;
    int r = 0;
    for (int a = 0; a < s.paramDim(); ++a) {
      if (a == dn) continue;
      // Elements overlapping the region's interior; they must lie inside it (checked below
      // through the area sum).
      inside = inside && b.upper[a] > c.bounds[r][0] && b.lower[a] < c.bounds[r][1];
      f[1 + 2 * r] = b.lower[a];
      f[2 + 2 * r] = b.upper[a];
      ++r;
    }
    if (inside) out.insert(f);
  }
  return out;
}

// The contact elements of every model of a family are the same (paper Sect. 6: "the number
// and size of predefined contact elements are identical for all six models") and tile the
// contact region exactly.
void checkSameContactElements(const std::string& stem, int from, int to) {
  const std::string dir = std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/";
  std::set<FaceElement> first;
  for (int n = from; n <= to; ++n) {
    for (const char* kind : {"_h", "_g"}) {
      const BodyConfig c = loadBodyConfig(dir + stem + kind + std::to_string(n) + ".yaml");
      INFO(stem << kind << n);
      REQUIRE(c.contacts.size() == 1);
      const ContactConfig& contact = c.contacts[0];
      const std::set<FaceElement> el = contactElements(contact, bodySpace(c));
      double area = 0.0, region = 1.0;
      for (const auto& b : contact.bounds) region *= b[1] - b[0];
      for (const FaceElement& f : el) {
        double a = 1.0;
        for (std::size_t r = 0; r < contact.bounds.size(); ++r) {
          CHECK(f[1 + 2 * r] >= contact.bounds[r][0]);  // no element sticks out
          CHECK(f[2 + 2 * r] <= contact.bounds[r][1]);
          a *= f[2 + 2 * r] - f[1 + 2 * r];
        }
        area += a;
      }
      // Sums of O(100) products of knot spans: round-off only.
      CHECK(std::abs(area - region) <= 1e-12 * region);
      if (first.empty()) {
        first = el;
      } else {
        // Dyadic knots (3D) and midpoints computed by the same formula: exact equality.
        CHECK(el == first);
      }
    }
  }
}

void checkPair(const std::string& stem, int n, double maxRatio, double maxFunctionRatio) {
  const std::string dir = std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/";
  const BodyConfig h = loadBodyConfig(dir + stem + "_h" + std::to_string(n) + ".yaml");
  const BodyConfig g = loadBodyConfig(dir + stem + "_g" + std::to_string(n) + ".yaml");
  INFO(stem << " nlvl = " << n);
  REQUIRE(h.hierarchy.levels == n);
  REQUIRE(g.global_reference);
  const HierarchicalSpace H = bodySpace(h);
  const HierarchicalSpace G = bodySpace(g);
  REQUIRE(G.numLevels() == 1);
  const ParamBox fine = H.region(n - 1)[0];
  for (int a = 0; a < H.paramDim(); ++a) {
    // Knot values are computed by the same midpoint formula on both sides: exact equality.
    CHECK(knotsIn(G.levelKnots(0)[a], fine.lower[a], fine.upper[a]) ==
          knotsIn(H.levelKnots(n - 1)[a], fine.lower[a], fine.upper[a]));
  }
  // The acceptance ratio of issue 3 is on ndof (igaprep's count, tied points removed);
  // the function counts meet it too.
  CHECK(countDofs(H, h.model == ffriga::ModelKind::kAxisymmetric).ndof <= maxRatio * countDofs(G, g.model == ffriga::ModelKind::kAxisymmetric).ndof);
  CHECK(H.numFunctions() <= maxFunctionRatio * G.numFunctions());
}

TEST_CASE("axisymmetric sphere: hierarchical models and global references", "[configs]") {
  for (int n = 3; n <= 6; ++n) checkPair("sphere2d", n, 0.5, 0.5);
}

TEST_CASE("solid sphere: hierarchical models and global references", "[configs]") {
  // The design of 2026-12-03 (header of configs/bodies/sphere3d_h3.yaml): one cell layout,
  // its coarse levels merged into a graded level 0 for fewer levels. ndof ratios 0.334,
  // 0.191 and 0.126, function ratios 0.343, 0.198 and 0.129 for nlvl = 3, 4, 5; the bounds
  // are these rounded up to the next 0.01, so a design change that grows a hierarchical
  // model against its reference fails here. nlvl = 3 is the large one: with two halvings
  // only, its level 0 must already hold 1/64 spans (a quarter of the finest) at the contact.
  checkPair("sphere3d", 3, 0.34, 0.35);
  checkPair("sphere3d", 4, 0.20, 0.20);
  checkPair("sphere3d", 5, 0.13, 0.13);
}

TEST_CASE("solid sphere: the three global references are one space", "[configs]") {
  // Every hierarchical model has the same cells; a reference holds every knot line of them
  // across the patch, so sphere3d_g3, g4 and g5 must have identical knot vectors.
  const std::string dir = std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/";
  const HierarchicalSpace g5 = bodySpace(loadBodyConfig(dir + "sphere3d_g5.yaml"));
  for (int n = 3; n <= 4; ++n) {
    INFO("sphere3d_g" << n);
    const HierarchicalSpace g = bodySpace(loadBodyConfig(dir + "sphere3d_g" + std::to_string(n) + ".yaml"));
    REQUIRE(g.numLevels() == 1);
    for (int a = 0; a < g.paramDim(); ++a)  // dyadic knots: exact equality
      CHECK(g.levelKnots(0)[a].knots() == g5.levelKnots(0)[a].knots());
  }
}

// Not checked for the 2D family: there only the finest level reaches 10 um at the pole, the
// contact region [0, 0.022624] also holds coarser elements in some models (sphere2d_g6: 16
// elements, sphere2d_h3: 32).
TEST_CASE("solid sphere: identical contact elements in all six models", "[configs]") {
  checkSameContactElements("sphere3d", 3, 5);
}

TEST_CASE("HB and THB bodies count the same DOFs", "[configs]") {
  BodyConfig c =
      loadBodyConfig(std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/sphere2d_h6.yaml");
  const HierarchicalSpace thb = bodySpace(c);
  c.hierarchy.truncated = false;
  const HierarchicalSpace hb = bodySpace(c);
  REQUIRE(hb.numFunctions() == thb.numFunctions());  // same active set
  CHECK(countDofs(hb, c.model == ffriga::ModelKind::kAxisymmetric).ndof == countDofs(thb, c.model == ffriga::ModelKind::kAxisymmetric).ndof);
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
