// Contact surface extraction (common/splines/contact_surface.h) and its evaluator
// (common/splines/extracted_surface.h) against the volume basis of the hierarchical space.
#include "common/splines/contact_surface.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "common/splines/extracted_surface.h"
#include "common/splines/gauss_legendre.h"
#include "preproc/input/body_config.h"
#include "tests/support/test_util.h"

namespace ffriga {
namespace {

HierarchicalSpace loadSpace(const std::string& stem) {
  return bodySpace(
      loadBodyConfig(std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/" + stem + ".yaml"));
}

// Surface region = the face part of the finest box.
ParamBox faceRegion(const HierarchicalSpace& H, int dir) {
  ParamBox r;
  const ParamBox box = H.region(H.numLevels() - 1)[0];
  int i = 0;
  for (int a = 0; a < H.paramDim(); ++a) {
    if (a == dir) continue;
    r.lower[i] = box.lower[a];
    r.upper[i] = box.upper[a];
    ++i;
  }
  return r;
}

// The runtime's evaluator of a ContactSurface at (e, s), as a PatchPoint.
PatchPoint evaluateSurface(const ContactSurface& cs, const HierarchicalSpace& H, int e,
                           const double* s, int order) {
  const ExtractedSurface surf(cs, H.weights());
  PatchPoint p;
  surf.evaluate(e, s, H.controlPoints(), order, p);
  return p;
}

// Compares ExtractedSurface with HierarchicalSpace::evaluate on the face xi_dir = 1.
void checkAgainstVolume(const HierarchicalSpace& H, const ContactSurface& cs, int dir) {
  const int d = H.paramDim(), dc = d - 1;
  double ex = 0, edx = 0, eddx = 0;
  for (int e = 0; e < static_cast<int>(cs.element_level.size()); ++e) {
    // Derivatives of a Bezier (or B-spline) form on an element of width h are differences
    // of O(|x|) coefficients times 1/h^k: round-off scales as eps |x| / h^k.
    const double h = (cs.element_upper.row(e) - cs.element_lower.row(e)).minCoeff();
    for (int q = 0; q < 3; ++q) {
      double s[2], xi[3];
      int i = 0;
      for (int a = 0; a < d; ++a) {
        if (a == dir) {
          xi[a] = 1.0;
          continue;
        }
        s[i] = test::uniform(cs.element_lower(e, i), cs.element_upper(e, i));
        xi[a] = s[i];
        ++i;
      }
      const PatchPoint a = evaluateSurface(cs, H, e, s, 2);
      const PatchPoint b = H.evaluate(xi, 2);
      ex = std::max(ex, (a.x - b.x).norm() / b.x.norm());
      int j = 0;
      for (int c = 0; c < d; ++c) {
        if (c == dir) continue;
        edx = std::max(edx, (a.dx.col(j) - b.dx.col(c)).norm() * h / b.x.norm());
        int k = 0;
        for (int c2 = 0; c2 < d; ++c2) {
          if (c2 == dir) continue;
          if (k >= j) {
            const Eigen::VectorXd sa = a.ddx.col(secondDerivativeRow(dc, j, k) - 1 - dc);
            const Eigen::VectorXd sb = b.ddx.col(secondDerivativeRow(d, c, c2) - 1 - d);
            eddx = std::max(eddx, (sa - sb).norm() * h * h / b.x.norm());
          }
          ++k;
        }
        ++j;
      }
    }
  }
  // Same rational map through two evaluation paths (Bezier form vs B-spline form with
  // hierarchical extraction): round-off of sums of O(10) terms, relative to |x| / h^k.
  CHECK(ex < 1e-13);
  CHECK(edx < 1e-13);
  CHECK(eddx < 1e-13);
}

TEST_CASE("axisymmetric contact surface: traces, weights, collocation", "[contact]") {
  const HierarchicalSpace H = loadSpace("sphere2d_h4");
  const ParamBox region = faceRegion(H, 1);  // face eta = 1: the upper arc, parameter xi
  const ContactSurface cs = extractContactSurface(H, 1, 1, region);
  REQUIRE(cs.dim == 1);
  checkAgainstVolume(H, cs, 1);
  // Surface functions are among the volume functions that do not vanish on the face.
  const std::vector<int> face = H.faceFunctions(1, 1);
  for (int f : cs.functions) CHECK(std::binary_search(face.begin(), face.end(), f));
  // The weights sum to the arc length of the region, r * theta, with theta the polar angle
  // of the region's end (xi = 0 is the pole).
  const double xiEnd[2] = {region.upper[0], 1.0};
  const Eigen::VectorXd x = H.evaluate(xiEnd).x;
  const double arc = 0.01 * std::atan2(x(0), x(1));
  // Gauss quadrature (p+3 points) of a smooth rational integrand on elements of ~1e-3 of
  // the parameter range: error far below 1e-12 relative.
  CHECK(std::abs(cs.collocation_weights.sum() - arc) < 1e-12 * arc);
  // One collocation point per function, inside the region; the upper arc's normal
  // (rotated tangent times outward_sign) points away from the centre.
  CHECK(cs.collocation_points.rows() ==
        static_cast<int>(std::set<int>(cs.functions.begin(), cs.functions.end()).size()));
  CHECK(cs.collocation_points.minCoeff() >= region.lower[0]);
  CHECK(cs.collocation_points.maxCoeff() <= region.upper[0]);
  const double s[1] = {0.5 * (cs.element_lower(0, 0) + cs.element_upper(0, 0))};
  const PatchPoint p = evaluateSurface(cs, H, 0, s, 1);
  const Eigen::Vector2d n(p.dx(1, 0), -p.dx(0, 0));
  CHECK(cs.outward_sign * n.dot(p.x) > 0.0);

  // Gauss collocation: the same surface, p + 1 Gauss-Legendre points per element (inside
  // their element, none on the axis), weights quadrature x Jacobian that sum to the same
  // arc and integrate the radius, sum w_g r_g = integral of r ds = R^2 (1 - cos theta) (the
  // ring factor the runtime applies; Gauss rules of p + 1 points on smooth integrands over
  // elements of ~1e-3 of the range: 1e-12 and 1e-10 relative).
  const ContactSurface gs = extractContactSurface(H, 1, 1, region, "contact",
                                                  CollocationRule::kGauss);
  const int ne = static_cast<int>(gs.element_level.size());
  REQUIRE(gs.collocation_points.rows() == ne * (gs.degrees[0] + 1));
  CHECK(gs.collocation_rule == CollocationRule::kGauss);
  CHECK(std::abs(gs.collocation_weights.sum() - arc) < 1e-12 * arc);
  double moment = 0.0;  // integral of r ds over the arc from the pole: r^2 (1 - cos theta)
  for (Eigen::Index k = 0; k < gs.collocation_points.rows(); ++k) {
    const int e = gs.collocation_element[k];
    const double sk = gs.collocation_points(k, 0);
    CHECK(sk > gs.element_lower(e, 0));
    CHECK(sk < gs.element_upper(e, 0));
    const double at[1] = {sk};
    moment += gs.collocation_weights(k) * evaluateSurface(gs, H, e, at, 0).x(0);
  }
  const double theta = std::atan2(x(0), x(1));
  const double exact = 0.01 * 0.01 * (1.0 - std::cos(theta));
  CHECK(std::abs(moment - exact) < 1e-10 * exact);
}

TEST_CASE("solid contact surface: traces, weights, collocation", "[contact]") {
  const HierarchicalSpace H = loadSpace("sphere3d_h4");
  const ParamBox region = faceRegion(H, 1);  // face eta = 1 around (0.5, 1, 0.125)
  const ContactSurface cs = extractContactSurface(H, 1, 1, region);
  REQUIRE(cs.dim == 2);
  checkAgainstVolume(H, cs, 1);
  // Area of the region by an independent quadrature through the volume space (8 points
  // per direction on the region's finest elements).
  double area = 0.0;
  for (int e = 0; e < static_cast<int>(cs.element_level.size()); ++e) {
    const QuadratureRule q0 = gaussLegendre(8, cs.element_lower(e, 0), cs.element_upper(e, 0));
    const QuadratureRule q1 = gaussLegendre(8, cs.element_lower(e, 1), cs.element_upper(e, 1));
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j) {
        const double xi[3] = {q0.points[i], 1.0, q1.points[j]};
        const PatchPoint p = H.evaluate(xi, 1);
        area += q0.weights[i] * q1.weights[j] *
                Eigen::Vector3d(p.dx.col(0)).cross(Eigen::Vector3d(p.dx.col(2))).norm();
      }
  }
  // Both are Gauss rules on the same smooth integrand (6 vs 8 points): 1e-12 relative.
  CHECK(std::abs(cs.collocation_weights.sum() - area) < 1e-12 * area);
  // The sphere's outward normal is the position direction (centre at the origin).
  const double s[2] = {0.5 * (cs.element_lower(0, 0) + cs.element_upper(0, 0)),
                       0.5 * (cs.element_lower(0, 1) + cs.element_upper(0, 1))};
  const PatchPoint p = evaluateSurface(cs, H, 0, s, 1);
  const Eigen::Vector3d n = Eigen::Vector3d(p.dx.col(0)).cross(Eigen::Vector3d(p.dx.col(1)));
  CHECK(cs.outward_sign * n.dot(p.x) > 0.0);
  for (int k = 0; k < cs.collocation_points.rows(); ++k) {
    CHECK(cs.collocation_element[k] >= 0);
    CHECK(cs.collocation_weights(k) > 0.0);
  }
}

TEST_CASE("Bernstein derivatives", "[contact]") {
  // Central differences of the values (step 1e-6: error ~1e-10 for degree <= 4).
  Eigen::MatrixXd d0, dp, dm;
  for (int p = 0; p <= 4; ++p) {
    const double t = 0.37, h = 1e-6;
    bernsteinBasis(p, t, 2, d0);
    bernsteinBasis(p, t + h, 1, dp);
    bernsteinBasis(p, t - h, 1, dm);
    double sum = 0;
    for (int b = 0; b <= p; ++b) {
      sum += d0(0, b);
      CHECK(d0(1, b) == Approx((dp(0, b) - dm(0, b)) / (2 * h)).margin(1e-8));
      CHECK(d0(2, b) == Approx((dp(1, b) - dm(1, b)) / (2 * h)).margin(1e-6));
    }
    CHECK(sum == Approx(1.0).epsilon(1e-15));  // partition of unity
  }
}

}  // namespace
}  // namespace ffriga
