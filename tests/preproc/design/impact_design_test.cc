// A body designed from its impact (issue 26, preproc/design/impact_design.h): the rule's
// geometry checked against the exact half-disk (the contact region really spans 2 a of arc,
// the finest spans really lie below a / N), the boxes nested on their level grids, Hertz's
// contact radius for each kind of partner, and the body file's `design` block read into a
// model that igaprep's checks accept and its pipeline reduces.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "common/mechanics/hertz.h"
#include "preproc/body_preprocessor.h"
#include "preproc/design/impact_design.h"
#include "preproc/geometry/geometry_builders.h"
#include "preproc/input/body_config.h"

namespace ffriga {
namespace {

const IsotropicMaterial kSteel{2.11e11, 0.3, 7850.0};
constexpr double kR = 0.01;

// The paper's Sect. 5 impact (two steel spheres r = 1 cm at 0.2 m/s).
DesignRequest paperImpact() {
  DesignRequest q;
  q.approach_speed = 0.2;
  return q;
}

ImpactDesign paperDesign(double n = kDefaultElementsPerContactRadius) {
  DesignRequest q = paperImpact();
  q.elements_per_contact_radius = n;
  return designHalfDiskImpact(kR, kSteel, sphereMass(kR, kSteel.density), q);
}

// The angle from the pole (0, r) of the half-disk's upper arc at knot xi, from the exact
// patch (not from the rule's formula).
double angleAt(double xi) {
  const NurbsPatch disk = halfDisk(kR);
  const double u[2] = {xi, 1.0};
  const Eigen::VectorXd x = disk.evaluate(u).x;
  return std::atan2(x(0), x(1));
}

bool onGrid(double x, double h) {
  return std::abs(x / h - std::round(x / h)) < 1e-9;
}

TEST_CASE("designed half-disk: Hertz's contact radius for each partner", "[design]") {
  const double m = sphereMass(kR, kSteel.density);
  const HertzSphere self{kSteel.youngs_modulus, kSteel.poisson_ratio, kR, m};
  const ImpactDesign same = paperDesign();
  const HertzImpact h = hertzImpact(self, self, 0.2);
  // a^2 = R* delta (Johnson 4.23 with F = K delta^1.5): R* = r / 2 for two equal spheres.
  CHECK(same.contact_radius == Approx(std::sqrt(0.5 * kR * h.max_approach)).epsilon(1e-14));
  CHECK(same.contact_radius == Approx(1.678e-4).epsilon(1e-3));  // the paper's a = 0.17 mm
  CHECK(same.max_pressure == Approx(hertzContactPatch(self, self, h.max_force).max_pressure));
  // A rigid plane: R* = r, E* = E / (1 - nu^2), m* = m.
  DesignRequest plane = paperImpact();
  plane.partner = DesignRequest::Partner::kPlane;
  const ImpactDesign p = designHalfDiskImpact(kR, kSteel, m, plane);
  const double inf = std::numeric_limits<double>::infinity();
  const HertzImpact hp = hertzImpact(self, HertzSphere{inf, 0.0, inf, inf}, 0.2);
  CHECK(p.contact_radius == Approx(std::sqrt(kR * hp.max_approach)).epsilon(1e-14));
  // A partner sphere given explicitly equal to the body is the same body.
  DesignRequest sphere = paperImpact();
  sphere.partner = DesignRequest::Partner::kSphere;
  sphere.partner_sphere = self;
  CHECK(designHalfDiskImpact(kR, kSteel, m, sphere).contact_radius ==
        Approx(same.contact_radius).epsilon(1e-14));
  // The contact radius given directly gives the same model as the impact that has it.
  DesignRequest given;
  given.from_impact = false;
  given.contact_radius = same.contact_radius;
  const ImpactDesign g = designHalfDiskImpact(kR, kSteel, m, given);
  CHECK_FALSE(g.hertz.has_value());
  CHECK(g.hierarchy.levels == same.hierarchy.levels);
  CHECK(g.region == same.region);
}

TEST_CASE("designed half-disk: region, finest spans and boxes on the exact geometry", "[design]") {
  for (const double n : {6.0, 12.0, 24.0}) {
    const ImpactDesign d = paperDesign(n);
    const double a = d.contact_radius;
    const int halvings = d.hierarchy.levels - 1;
    // Finest spans at the pole, measured on the exact patch (arc: the angle of the first
    // finest knot times r) and from the knot grid (depth: 2 r (1 - eta)).
    const double dxi = std::ldexp(1.0 / 16.0, -halvings), deta = std::ldexp(1.0 / 25.0, -halvings);
    const double arc = kR * angleAt(dxi), depth = 2.0 * kR * deta;
    CHECK(arc == Approx(d.finest_arc).epsilon(1e-3));  // sqrt(2) r dxi: the arc's speed at 0
    CHECK(depth == Approx(d.finest_depth).epsilon(1e-12));
    CHECK(std::max(arc, depth) <= a / n);
    // ... and the fewest halvings that get there: one less would not.
    CHECK(2.0 * std::max(d.finest_arc, d.finest_depth) > a / n);
    // The contact region covers 2 a of arc (and less than one finest span more).
    REQUIRE(d.region.size() == 1);
    CHECK(d.region[0][0] == 0.0);
    const double regionArc = kR * angleAt(d.region[0][1]);
    CHECK(regionArc >= kRegionRadii * a);
    CHECK(regionArc < kRegionRadii * a + 1.01 * d.finest_arc);
    CHECK(onGrid(d.region[0][1], dxi));
    // Boxes: nested, each bound on the grid of the level below, reaching 2 a of arc and
    // 0.5 a deep plus kLayerCells cells of that level.
    double xiHi = 1.0, etaLo = 0.0;
    for (int l = 1; l <= halvings; ++l) {
      const ParamBox& b = d.hierarchy.boxes[l - 1][0];
      const double gx = std::ldexp(1.0 / 16.0, -(l - 1)), ge = std::ldexp(1.0 / 25.0, -(l - 1));
      CHECK(b.lower[0] == 0.0);
      CHECK(b.upper[1] == 1.0);
      CHECK(onGrid(b.upper[0], gx));
      CHECK(onGrid(b.lower[1], ge));
      CHECK(b.upper[0] <= xiHi);
      CHECK(b.lower[1] >= etaLo);
      xiHi = b.upper[0];
      etaLo = b.lower[1];
      const double layerArc = kLayerCells * std::sqrt(2.0) * kR * gx;
      CHECK(kR * angleAt(b.upper[0]) >= kRegionRadii * a + 0.99 * layerArc);
      CHECK(2.0 * kR * (1.0 - b.lower[1]) >=
            kFinestDepthRadii * a + kLayerCells * 2.0 * kR * ge - 1e-15);
    }
    CHECK(d.region[0][1] <= xiHi);
  }
}

// The exact solid sphere's surface point at (xi, 1, zeta), and the great-circle distance
// from the contact point (+z) to it.
double sphereDistance(double xi, double zeta) {
  const NurbsPatch sphere = solidSphere(kR);
  const double u[3] = {xi, 1.0, zeta};
  const Eigen::VectorXd x = sphere.evaluate(u).x;
  return kR * std::acos(std::clamp(x(2) / x.norm(), -1.0, 1.0));
}

TEST_CASE("designed sphere: region and boxes on the exact solid sphere", "[design]") {
  DesignRequest q = paperImpact();
  q.elements_per_contact_radius = kDefaultElementsPerContactRadiusSolid;
  const ImpactDesign d = designSphereImpact(kR, kSteel, sphereMass(kR, kSteel.density), q);
  const double a = d.contact_radius;
  // Default level for solids (N = 2): the finest spans below a / 2, one halving less not.
  CHECK(std::max(d.finest_arc, d.finest_depth) <= a / 2.0);
  CHECK(2.0 * d.finest_arc > a / 2.0);
  // The region reaches 2 a from the contact point along both surface directions, measured
  // on the exact sphere, and is centred on the contact point (1/2, 1/8).
  REQUIRE(d.region.size() == 2);
  const auto& xi = d.region[0];
  const auto& zeta = d.region[1];
  CHECK(xi[0] + xi[1] == Approx(1.0));
  CHECK(zeta[0] + zeta[1] == Approx(0.25));
  for (const double x : {xi[0], xi[1]})
    CHECK(sphereDistance(x, kSphereContactXi[2]) >= kRegionRadii * a);
  for (const double z : {zeta[0], zeta[1]})
    CHECK(sphereDistance(kSphereContactXi[0], z) >= kRegionRadii * a);
  // Boxes nested, inside the first quarter of zeta (a C0 line of the circle at 1/4) and off
  // the degenerate faces xi = 0, 1 and the seam zeta = 0.
  const ParamBox* outer = nullptr;
  for (const LevelBoxes& level : d.hierarchy.boxes) {
    const ParamBox& b = level[0];
    CHECK(b.lower[0] > 0.0);
    CHECK(b.upper[0] < 1.0);
    CHECK(b.lower[2] > 0.0);
    CHECK(b.upper[2] < 0.25);
    CHECK(b.upper[1] == 1.0);
    if (outer) {
      for (int k = 0; k < 3; ++k) {
        CHECK(b.lower[k] >= outer->lower[k]);
        CHECK(b.upper[k] <= outer->upper[k]);
      }
    }
    outer = &b;
  }
  CHECK(xi[0] >= outer->lower[0]);
  CHECK(zeta[1] <= outer->upper[2]);
  // The stress line runs down the z axis from the contact point.
  CHECK(d.stress_from.size() == 3);
  CHECK(d.stress_from(2) == kR);
  CHECK(d.stress_from(2) - d.stress_to(2) == Approx(kStressLineRadii * a));
}

TEST_CASE("designed body file: a solid sphere passes igaprep's checks", "[design]") {
  const std::string yaml =
      "name: designed3d\n"
      "model: solid\n"
      "material: {youngs_modulus: 2.11e11, poisson_ratio: 0.3, density: 7850}\n"
      "geometry: {type: sphere, radius: 0.01}\n"
      "design: {contact_radius: 1.0e-3}\n";
  const BodyConfig c = parseBodyConfig(parseYamlText(yaml, "designed3d.yaml"));
  REQUIRE(c.design.has_value());
  CHECK(c.design->elements_per_contact_radius == kDefaultElementsPerContactRadiusSolid);
  // The file gives no normal modes: a designed solid gets kDefaultNormalModesSolid.
  CHECK(c.reduction.normal_modes == kDefaultNormalModesSolid);
  const BodyConfig given = parseBodyConfig(
      parseYamlText(yaml + "reduction: {normal_modes: 7}\n", "designed3d.yaml"));
  CHECK(given.reduction.normal_modes == 7);
  REQUIRE(c.contacts.size() == 1);
  CHECK(c.contacts[0].bounds.size() == 2);
  const HierarchicalSpace space = bodySpace(c);
  CHECK(space.numLevels() == c.hierarchy.levels);
}

TEST_CASE("designed half-disk: a contact radius beyond the face is refused", "[design]") {
  DesignRequest q;
  q.from_impact = false;
  q.contact_radius = 0.45 * kR;  // 2 a = 0.9 r of arc > pi / 4 r
  CHECK_THROWS_WITH(designHalfDiskImpact(kR, kSteel, 1.0, q),
                    Catch::Contains("half the patch's extent"));
  q.contact_radius = 0.35 * kR;  // 0.7 r < pi / 4 r: still a (coarse) design
  CHECK_NOTHROW(designHalfDiskImpact(kR, kSteel, 1.0, q));
}

TEST_CASE("designed body file: the design block gives a model igaprep reduces", "[design]") {
  const std::string yaml =
      "name: designed\n"
      "model: axisymmetric\n"
      "material: {youngs_modulus: 2.11e11, poisson_ratio: 0.3, density: 7850}\n"
      "geometry: {type: half_disk, radius: 0.01}\n"
      "design: {contact_radius: 1.0e-3, elements_per_contact_radius: 4}\n"
      "reduction: {normal_modes: 4}\n"
      "visualisation: {subdivisions: 0}\n";
  const BodyConfig c = parseBodyConfig(parseYamlText(yaml, "designed.yaml"));
  REQUIRE(c.design.has_value());
  CHECK(c.hierarchy.levels == c.design->hierarchy.levels);
  REQUIRE(c.contacts.size() == 1);
  CHECK(c.contacts[0].designed);
  CHECK(c.contacts[0].direction == 1);
  CHECK(c.contacts[0].upper);
  REQUIRE(c.visualisation.stress_lines.size() == 1);
  CHECK(c.visualisation.stress_lines[0].name == "axis");
  PreprocessSummary summary;
  const FlexibleBodySid sid = preprocessBody(
      c, [](const std::string&) {}, &summary);
  CHECK(sid.design.present);
  CHECK(sid.design.contact_radius == 1.0e-3);
  CHECK(sid.design.finest_element <= 1.0e-3 / 4);
  CHECK(sid.design.approach_speed == 0.0);  // a was given, not an impact
  REQUIRE(sid.surfaces.size() == 1);
  // The stress line runs 3.5 a down the axis from the pole (body frame: centre at 0).
  REQUIRE(sid.stress_lines.size() == 1);
  CHECK(sid.stress_lines[0].from(1) - sid.stress_lines[0].to(1) == Approx(3.5e-3));
}

}  // namespace
}  // namespace ffriga
