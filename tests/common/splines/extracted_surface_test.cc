#include "common/splines/extracted_surface.h"

#include <catch2/catch.hpp>

#include "tests/support/surface_fixtures.h"
#include "tests/support/test_util.h"

using namespace ffriga;

TEST_CASE("Bernstein basis: partition of unity and derivatives", "[surface]") {
  Eigen::MatrixXd B, Bp, Bm;
  for (int p = 0; p <= 5; ++p) {
    const double t = 0.37, h = 1e-5;
    bernsteinBasis(p, t, 2, B);
    REQUIRE(std::abs(B.row(0).sum() - 1.0) < 1e-15);
    bernsteinBasis(p, t + h, 2, Bp);
    bernsteinBasis(p, t - h, 2, Bm);
    // Central differences: truncation error h^2 |B'''| / 6 <= 1e-10 * p^3 scale; 1e-6 is safe.
    REQUIRE(((Bp.row(0) - Bm.row(0)) / (2 * h) - B.row(1)).cwiseAbs().maxCoeff() < 1e-6);
    REQUIRE(((Bp.row(1) - Bm.row(1)) / (2 * h) - B.row(2)).cwiseAbs().maxCoeff() < 1e-5);
  }
}

TEST_CASE("extracted surface reproduces the NURBS patch with derivatives", "[surface]") {
  for (int d = 1; d <= 2; ++d) {
    for (int trial = 0; trial < 10; ++trial) {
      const NurbsPatch patch = test::randomPatch(d, d + 1);
      const ContactSurface cs = test::bezierExtract(patch);
      const ExtractedSurface surf(cs, patch.weights());
      for (int k = 0; k < 20; ++k) {
        const double s[2] = {test::uniform(), test::uniform()};
        const int e = surf.findElement(s);
        REQUIRE(e >= 0);
        SurfacePoint sp;
        surf.evaluate(e, s, patch.points(), 2, sp);
        const PatchPoint ref = patch.evaluate(s, 2);
        // Extraction and rationalisation reorder the same sums: round-off only. Derivatives on
        // short random spans grow like 1/h^2, so compare against their own scale.
        const double scale = 1.0 + ref.ddx.cwiseAbs().maxCoeff();
        REQUIRE((sp.x - ref.x).cwiseAbs().maxCoeff() < 1e-13);
        REQUIRE((sp.dx - ref.dx).cwiseAbs().maxCoeff() < 1e-13 * scale);
        REQUIRE((sp.ddx - ref.ddx).cwiseAbs().maxCoeff() < 1e-13 * scale);
      }
    }
  }
}
