// Explicit patches designed from their impact (issue 26, impact_design.h designPatchImpact)
// and the geometry under it: the face point's normal and principal curvatures against
// closed forms (sphere, spheroid, flat and concave faces), the patch volume against the
// sphere's and spheroid's, the tabulated chart of the half-disk given as an explicit patch
// against the exact chart of the built-in one, the checks that refuse a point, and the
// built-in sphere turned to a contact direction.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "common/mechanics/hertz_ellipse.h"
#include "preproc/design/contact_chart.h"
#include "preproc/design/impact_design.h"
#include "preproc/geometry/face_point.h"
#include "preproc/geometry/geometry_builders.h"
#include "preproc/geometry/patch_volume.h"

namespace ffriga {
namespace {

const IsotropicMaterial kSteel{2.11e11, 0.3, 7850.0};
constexpr double kR = 0.01;

// The half-disk of paper Eq. (19) scaled to semi-axes A (radial) and C (axial): the
// meridian section of a spheroid. Its pole (0, C) has curvature C / A^2.
NurbsPatch spheroidSection(double A, double C) {
  const NurbsPatch disk = halfDisk(1.0);
  Eigen::MatrixXd P = disk.points();
  P.col(0) *= A;
  P.col(1) *= C;
  return NurbsPatch(disk.knotVectors(), P, disk.weights());
}

// The upper edge y = h + k x^2 over x in [0, w] (a quadratic Bezier: exact), a flat lower
// edge at y = 0: k > 0 a dish (concave), k = 0 flat.
NurbsPatch dishSection(double k) {
  const double w = 0.01, h = 0.004;
  Eigen::MatrixXd P(6, 2);
  P << 0, 0, w / 2, 0, w, 0, 0, h, w / 2, h, w, h + k * w * w;
  return NurbsPatch({KnotVector({0, 0, 0, 1, 1, 1}, 2), KnotVector({0, 0, 1, 1}, 1)}, P,
                    Eigen::VectorXd::Ones(6));
}

// The unit solid sphere (contact point (1/2, 1, 1/8) at +z) scaled to semi-axes a, b, c
// along x, y, z: an ellipsoid, whose point (1/2, 1, 1/8) is the end (0, 0, c) of its z axis.
NurbsPatch ellipsoid(double a, double b, double c) {
  const NurbsPatch ball = solidSphere(1.0);
  Eigen::MatrixXd P = ball.points();
  P.col(0) *= a;
  P.col(1) *= b;
  P.col(2) *= c;
  return NurbsPatch(ball.knotVectors(), P, ball.weights());
}

DesignRequest impactAt(double v) {
  DesignRequest q;
  q.approach_speed = v;
  return q;
}

TEST_CASE("face point: normal and principal curvatures", "[design]") {
  // The half-disk's pole: outward normal +y, curvature 1 / r.
  const FacePoint pole = facePoint(halfDisk(kR), 1, true, {0.0, 1.0});
  CHECK(pole.normal(1) == Approx(1.0));
  REQUIRE(pole.curvatures.size() == 1);
  CHECK(pole.curvatures[0] == Approx(1.0 / kR).epsilon(1e-12));
  // The lower arc at its pole (0, -r): normal -y, still convex.
  const FacePoint south = facePoint(halfDisk(kR), 1, false, {0.0, 0.0});
  CHECK(south.normal(1) == Approx(-1.0));
  CHECK(south.curvatures[0] == Approx(1.0 / kR).epsilon(1e-12));
  // A spheroid's pole: C / A^2 (the radius of curvature A^2 / C).
  const FacePoint sp = facePoint(spheroidSection(0.01, 0.005), 1, true, {0.0, 1.0});
  CHECK(sp.curvatures[0] == Approx(0.005 / 1e-4).epsilon(1e-12));
  // The solid sphere anywhere regular: both principal curvatures 1 / r, normal radial.
  const NurbsPatch ball = solidSphere(kR);
  for (const std::vector<double>& xi :
       {std::vector<double>{0.5, 1.0, 0.125}, std::vector<double>{0.3, 1.0, 0.6}}) {
    const FacePoint f = facePoint(ball, 1, true, xi);
    REQUIRE(f.curvatures.size() == 2);
    CHECK(f.curvatures[0] == Approx(1.0 / kR).epsilon(1e-10));
    CHECK(f.curvatures[1] == Approx(1.0 / kR).epsilon(1e-10));
    CHECK((f.normal - f.x / kR).norm() < 1e-12);
  }
  // Flat and concave: 0 and -2 k.
  CHECK(std::abs(facePoint(dishSection(0.0), 1, true, {0.0, 1.0}).curvatures[0]) < 1e-9);
  CHECK(facePoint(dishSection(50.0), 1, true, {0.0, 1.0}).curvatures[0] == Approx(-100.0));
  // The half-disk's collapsed edge xi = 1 is degenerate.
  CHECK(facePoint(halfDisk(kR), 0, true, {1.0, 0.5}).degenerate());
  CHECK_FALSE(pole.degenerate());
}

TEST_CASE("patch volume: sphere, spheroid, box", "[design]") {
  const double sphere = 4.0 / 3.0 * M_PI * kR * kR * kR;
  CHECK(patchVolume(halfDisk(kR), true) == Approx(sphere).epsilon(1e-9));
  CHECK(patchVolume(solidSphere(kR), false) == Approx(sphere).epsilon(1e-9));
  CHECK(patchVolume(spheroidSection(0.01, 0.005), true) ==
        Approx(4.0 / 3.0 * M_PI * 1e-4 * 0.005).epsilon(1e-9));
  // The dish section revolved: int 2 pi x y(x) dx of y = h + k x^2 over [0, w].
  const double w = 0.01, h = 0.004, k = 50.0;
  CHECK(patchVolume(dishSection(k), true) ==
        Approx(2.0 * M_PI * (h * w * w / 2 + k * w * w * w * w / 4)).epsilon(1e-12));
}

TEST_CASE("patch chart: the half-disk as an explicit patch against the exact chart", "[design]") {
  const NurbsPatch disk = halfDisk(kR);
  const std::vector<double> xi{0.0, 1.0};
  const FacePoint f = facePoint(disk, 1, true, xi);
  const std::vector<ChartDirection> tab = patchChart(disk, f, 1, xi, {1.0 / 16, 1.0 / 25});
  const std::vector<ChartDirection> exact = halfDiskChart(kR);
  CHECK(tab[0].one_sided);
  CHECK(tab[1].depth);
  CHECK(tab[0].metres_per_knot == Approx(exact[0].metres_per_knot).epsilon(1e-12));
  CHECK(tab[1].metres_per_knot == Approx(exact[1].metres_per_knot).epsilon(1e-12));
  // Knots at 0.1 .. 1.5 mm of arc and depth: the tabulated inverse within 1e-6 of a span.
  for (double s : {1e-4, 5e-4, 1.5e-3}) {
    CHECK(tab[0].knot(s) == Approx(exact[0].knot(s)).margin(1e-6));
    CHECK(tab[1].knot(s) == Approx(exact[1].knot(s)).margin(1e-6));
  }
  // Half the quarter arc from the pole to the equator.
  CHECK(tab[0].reach_limit == Approx(exact[0].reach_limit).epsilon(1e-6));
  // The sphere's circle direction: its C0 knot lines bound the chart.
  const NurbsPatch ball = solidSphere(kR);
  const std::vector<double> at{0.5, 1.0, 0.125};
  const std::vector<ChartDirection> sph =
      patchChart(ball, facePoint(ball, 1, true, at), 1, at, {0.25, 0.25, 1.0 / 16});
  CHECK(sph[2].lowest == 0.0);
  CHECK(sph[2].highest == 0.25);
  CHECK(sph[2].reach_limit == Approx(sphereChart(kR)[2].reach_limit).epsilon(1e-6));
}

TEST_CASE("designed explicit patch: the half-disk given as NURBS, a spheroid", "[design]") {
  const NurbsPatch disk = halfDisk(kR);
  const ImpactDesign d = designPatchImpact(disk, true, kSteel, 1, true, {0.0}, impactAt(0.2));
  const ImpactDesign built = designHalfDiskImpact(
      kR, kSteel, 4.0 / 3.0 * M_PI * kR * kR * kR * kSteel.density, impactAt(0.2));
  // The same impact: Hertz's contact radius from the curvature and the quadrature mass.
  CHECK(d.contact_radius == Approx(built.contact_radius).epsilon(1e-8));
  CHECK(d.surface_radius == Approx(kR).epsilon(1e-12));
  // Level 0: cubic, 8 spans along the arc (pi r / 2), 11 along the axis (2 r).
  REQUIRE(d.refinement.elevate_degree == std::vector<int>{1, 2});
  CHECK(d.refinement.insert[0].size() == 7);
  CHECK(d.refinement.insert[1].size() == 10);
  CHECK(std::max(d.finest_arc, d.finest_depth) <= d.contact_radius / 12);
  CHECK(d.face_direction == 1);
  CHECK(d.contact_normal(1) == Approx(1.0));
  // The region spans 2 a of arc at least.
  CHECK(d.region[0][0] == 0.0);
  CHECK(kR * std::atan2(disk.evaluate(std::vector<double>{d.region[0][1], 1.0}.data()).x(0),
                        disk.evaluate(std::vector<double>{d.region[0][1], 1.0}.data()).x(1)) >=
        kRegionRadii * d.contact_radius);
  // A spheroid's pole: Hertz with its radius of curvature A^2 / C.
  const ImpactDesign s =
      designPatchImpact(spheroidSection(0.01, 0.005), true, kSteel, 1, true, {0.0}, impactAt(0.05));
  CHECK(s.surface_radius == Approx(0.02).epsilon(1e-10));
  const double m = kSteel.density * 4.0 / 3.0 * M_PI * 1e-4 * 0.005;
  const HertzSphere self{kSteel.youngs_modulus, kSteel.poisson_ratio, 0.02, m};
  CHECK(s.hertz->max_force == Approx(hertzImpact(self, self, 0.05).max_force).epsilon(1e-8));
}

TEST_CASE("designed explicit patch: points the rule refuses", "[design]") {
  const NurbsPatch disk = halfDisk(kR);
  auto refuses = [&](const NurbsPatch& p, int face, bool upper, std::vector<double> at,
                     const char* what) {
    try {
      designPatchImpact(p, p.paramDim() == 2, kSteel, face, upper, at, impactAt(0.2));
      FAIL("accepted: " << what);
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()).find(what) != std::string::npos);
    }
  };
  refuses(disk, 1, true, {1.5}, "must lie in [0, 1]");
  refuses(disk, 1, true, {0.3}, "on the axis x = 0");
  refuses(disk, 0, true, {0.5}, "degenerate point");
  refuses(dishSection(0.0), 1, true, {0.0}, "not convex");
  refuses(dishSection(50.0), 1, true, {0.0}, "not convex");
  const NurbsPatch ball = solidSphere(kR);
  refuses(ball, 1, true, {0.5, 0.25}, "C0 knot line");
  refuses(ball, 1, true, {0.0, 0.1}, "degenerate point");
  refuses(ball, 1, true, {0.5, 0.0}, "inside its face");
  // A needle-like ellipsoid: principal curvatures 400 times apart at +z.
  const NurbsPatch needle = ellipsoid(0.01, 0.0005, 0.01);
  const FacePoint tip = facePoint(needle, 1, true, {0.5, 1.0, 0.125});
  REQUIRE(tip.curvatures[1] / tip.curvatures[0] > kMaxCurvatureRatio);
  refuses(needle, 1, true, {0.5, 0.125}, "contact line");
  // The sphere itself is designed at any regular point (level 0 from the rule).
  const ImpactDesign d = designPatchImpact(ball, false, kSteel, 1, true, {0.4, 0.1}, impactAt(0.2));
  CHECK(d.surface_radius == Approx(kR).epsilon(1e-9));
}

TEST_CASE("designed explicit patch: an elliptical contact point", "[design]") {
  // An ellipsoid of semi-axes 12, 10, 8 mm (x, y, z) at the end of its z axis, the solid
  // sphere's contact point (1/2, 1, 1/8) scaled: principal curvatures c / a^2 = 8 / 144 and
  // 8 / 100 per mm (radii 18 and 12.5 mm), B / A = 1.44 against itself.
  const NurbsPatch body = ellipsoid(0.012, 0.010, 0.008);
  const FacePoint f = facePoint(body, 1, true, {0.5, 1.0, 0.125});
  CHECK(f.curvatures[0] == Approx(0.008 / (0.012 * 0.012)).epsilon(1e-9));
  CHECK(f.curvatures[1] == Approx(0.008 / (0.010 * 0.010)).epsilon(1e-9));
  // Their directions: along the 12 mm axis (x) and the 10 mm axis (y).
  REQUIRE(f.directions.size() == 2);
  CHECK(std::abs(f.directions[0](0)) == Approx(1.0).epsilon(1e-12));
  CHECK(std::abs(f.directions[1](1)) == Approx(1.0).epsilon(1e-12));
  const double volume = 4.0 / 3.0 * M_PI * 0.012 * 0.010 * 0.008;
  CHECK(patchVolume(body, false) == Approx(volume).epsilon(1e-9));
  const ImpactDesign d =
      designPatchImpact(body, false, kSteel, 1, true, {0.5, 0.125}, impactAt(0.2));
  // Hertz's ellipse for A = k1, B = k2 (the same body), E* = E / (2 (1 - nu^2)).
  const double Es = kSteel.youngs_modulus / (2.0 * (1.0 - 0.09));
  const double m = kSteel.density * volume / 2.0;
  const HertzImpact h =
      hertzImpact(hertzEllipse(f.curvatures[0], f.curvatures[1], Es, 1.0).stiffness, m, 0.2);
  const HertzEllipse peak = hertzEllipse(f.curvatures[0], f.curvatures[1], Es, h.max_force);
  REQUIRE(d.hertz);
  CHECK(d.hertz->max_force == Approx(h.max_force).epsilon(1e-9));
  CHECK(d.contact_radius == Approx(peak.semi_major).epsilon(1e-9));
  CHECK(d.contact_minor_radius == Approx(peak.semi_minor).epsilon(1e-9));
  CHECK(d.contact_radius / d.contact_minor_radius == Approx(1.27500).epsilon(1e-4));
  // Sized from b, reaching as far as a; not a sphere's point.
  CHECK(std::max(d.finest_arc, d.finest_depth) <= d.contact_minor_radius / 2);
  CHECK(d.surface_radius == 0.0);
  CHECK(d.principal_curvatures[0] == Approx(f.curvatures[0]).epsilon(1e-12));
  CHECK(d.principal_curvatures[1] == Approx(f.curvatures[1]).epsilon(1e-12));
  REQUIRE(d.principal_direction.size() == 3);
  CHECK(std::abs(d.principal_direction(0)) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("built-in sphere turned to its contact direction", "[design]") {
  const double xi[3] = {kSphereContactXi[0], kSphereContactXi[1], kSphereContactXi[2]};
  for (const Eigen::Vector3d& dir :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, -2, 0.5), Eigen::Vector3d(0, 0, -1)}) {
    const NurbsPatch ball = solidSphere(kR, dir);
    CHECK((ball.evaluate(xi).x - kR * dir.normalized()).norm() < 1e-14);
    const ImpactDesign d = designSphereImpact(kR, kSteel, 1.0, impactAt(0.2), dir);
    CHECK((d.stress_from - kR * dir.normalized()).norm() < 1e-14);
    CHECK((d.stress_to - d.stress_from).normalized().dot(-dir.normalized()) == Approx(1.0));
  }
}

}  // namespace
}  // namespace ffriga
