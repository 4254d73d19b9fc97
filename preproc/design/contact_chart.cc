#include "preproc/design/contact_chart.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "common/base/error.h"
#include "preproc/geometry/geometry_builders.h"

namespace ffriga {

namespace {

// The knot u of a rational quadratic quarter arc (weights 1, sqrt(1/2), 1) at angle theta
// from its start: the inverse of theta(u) = pi/4 + 2 atan((2 u - 1) tan(pi/8)).
double knotOfQuarterArc(double theta) {
  return 0.5 * (1.0 + std::tan(0.5 * theta - M_PI / 8.0) / std::tan(M_PI / 8.0));
}
// Its angle per knot at u: theta'(u) = 4 tan(pi/8) / (1 + ((2u - 1) tan(pi/8))^2).
double quarterArcSpeed(double u) {
  const double t = (2.0 * u - 1.0) * std::tan(M_PI / 8.0);
  return 4.0 * std::tan(M_PI / 8.0) / (1.0 + t * t);
}

// Samples per iso-parametric curve of a patch: the tabulated arc length and depth are
// polylines through 2048 points (relative error ~ (curvature x spacing)^2 / 24, below 1e-6
// for the designs' curves).
constexpr int kCurveSamples = 2048;

// y at x by linear interpolation in the table (xs non-decreasing), clamped to its ends.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const std::size_t j =
      static_cast<std::size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
  const double t = (x - xs[j - 1]) / (xs[j] - xs[j - 1]);
  return ys[j - 1] + t * (ys[j] - ys[j - 1]);
}

// A monotone table f(u) (u increasing, f non-decreasing): f at u, and its inverse, u at f.
struct MonotoneTable {
  std::vector<double> u, f;
  double inverse(double value) const { return interpolate(f, u, value); }
  double at(double uu) const { return interpolate(u, f, uu); }
};

// The iso-parametric curve through xi in direction a, sampled at kCurveSamples + 1 knots.
std::vector<Eigen::VectorXd> sampleCurve(const NurbsPatch& patch, std::vector<double> xi, int a) {
  const KnotVector& kn = patch.knots(a);
  std::vector<Eigen::VectorXd> x;
  for (int j = 0; j <= kCurveSamples; ++j) {
    xi[a] = kn.front() + (kn.back() - kn.front()) * j / kCurveSamples;
    x.push_back(patch.evaluate(xi.data()).x);
  }
  return x;
}

// Cumulative arc length along direction a's iso-curve through xi, from its start.
MonotoneTable arcLength(const NurbsPatch& patch, const std::vector<double>& xi, int a) {
  const std::vector<Eigen::VectorXd> x = sampleCurve(patch, xi, a);
  const KnotVector& kn = patch.knots(a);
  MonotoneTable t;
  double s = 0.0;
  for (int j = 0; j <= kCurveSamples; ++j) {
    if (j > 0) s += (x[j] - x[j - 1]).norm();
    t.u.push_back(kn.front() + (kn.back() - kn.front()) * j / kCurveSamples);
    t.f.push_back(s);
  }
  return t;
}

// The C0 knot lines (multiplicity >= degree, interior) of direction a nearest `at` on each
// side, or the patch's ends. A contact point on such a line has no tangent plane there.
std::array<double, 2> c0Limits(const KnotVector& kn, double at, int a) {
  std::array<double, 2> lim{kn.front(), kn.back()};
  for (double b : kn.breaks()) {
    if (b <= kn.front() || b >= kn.back() || kn.multiplicity(b) < kn.degree()) continue;
    if (std::abs(b - at) < 1e-12) {
      throw std::invalid_argument(Str() << "the contact point lies on a C0 knot line (knot " << b
                                        << " of direction " << a
                                        << "): the surface may have a kink there");
    }
    if (b < at) lim[0] = std::max(lim[0], b);
    if (b > at) lim[1] = std::min(lim[1], b);
  }
  return lim;
}

ChartDirection lateralDirection(const NurbsPatch& patch, const FacePoint& where,
                                const std::vector<double>& xi, int a, int k, double span0) {
  ChartDirection c;
  c.at = xi[a];
  c.span0 = span0;
  c.metres_per_knot = where.tangents[k].norm();
  const std::array<double, 2> lim = c0Limits(patch.knots(a), c.at, a);
  c.lowest = lim[0];
  c.highest = lim[1];
  c.one_sided = c.at <= c.lowest || c.at >= c.highest;
  auto table = std::make_shared<MonotoneTable>(arcLength(patch, xi, a));
  const double s0 = table->at(c.at);
  c.knot = [table, s0](double s) { return table->inverse(s0 + s); };
  const double below = s0 - table->at(c.lowest), above = table->at(c.highest) - s0;
  // Two-sided: to the nearest limit; one-sided (on the axis): half the arc to the far limit
  // (the region's diameter within the arc across the axis), as the built-in charts.
  c.reach_limit = c.at <= c.lowest    ? 0.5 * above
                  : c.at >= c.highest ? 0.5 * below
                                      : std::min(below, above);
  return c;
}

// Depth along direction a (the face's normal direction) from the face inwards: the normal
// depth -n . (x(u) - x_c), made monotone (its running maximum) along the curve.
ChartDirection depthDirection(const NurbsPatch& patch, const FacePoint& where,
                              const std::vector<double>& xi, int a, double span0) {
  ChartDirection c;
  c.depth = true;
  c.at = xi[a];
  c.span0 = span0;
  std::vector<double> p = xi;
  const PatchPoint pt = patch.evaluate(p.data(), 1);
  c.metres_per_knot = pt.dx.col(a).norm();  // an element's edge into the body
  const std::vector<Eigen::VectorXd> x = sampleCurve(patch, xi, a);
  const KnotVector& kn = patch.knots(a);
  const bool upper = c.at >= kn.back();
  auto table = std::make_shared<MonotoneTable>();
  double deepest = 0.0;
  for (int j = 0; j <= kCurveSamples; ++j) {
    const int i = upper ? kCurveSamples - j : j;  // from the face inwards
    deepest = std::max(deepest, -where.normal.dot(x[i] - where.x));
    table->u.push_back(static_cast<double>(j) / kCurveSamples);  // distance in knots
    table->f.push_back(deepest);
  }
  const double span = kn.back() - kn.front();
  c.knot = [table, upper, span, kn](double d) {
    const double t = table->inverse(d) * span;
    return upper ? kn.back() - t : kn.front() + t;
  };
  c.reach_limit = deepest;  // the depth the curve reaches
  return c;
}

}  // namespace

// The half-disk of paper Eq. (19), contact at its pole (0, 1): xi along the upper arc
// (theta = theta(xi)), eta from the lower to the upper arc (depth 2 r (1 - eta) on the
// axis). Level 0: the paper's 400-element model, 16 x 25 spans.
std::vector<ChartDirection> halfDiskChart(double r) {
  ChartDirection xi;
  xi.one_sided = true;
  xi.span0 = 1.0 / 16.0;
  xi.metres_per_knot = r * quarterArcSpeed(0.0);
  xi.knot = [r](double s) { return knotOfQuarterArc(s / r); };
  xi.reach_limit = 0.5 * r * M_PI / 2.0;  // the quarter arc from the pole to the equator
  ChartDirection eta;
  eta.depth = true;
  eta.at = 1.0;
  eta.span0 = 1.0 / 25.0;
  eta.metres_per_knot = 2.0 * r;
  eta.knot = [r](double d) { return 1.0 - d / (2.0 * r); };
  return {xi, eta};
}

// The solid sphere (the half-disk revolved, geometry_builders.h), contact at (1/2, 1, 1/8):
// polar angle theta0 = theta(1/2) = pi/4 along xi, azimuth phi0 = pi/4 along zeta (the
// first quarter of the circle, zeta in [0, 1/4]: u = 4 zeta), eta into the body along the
// half-disk's chord, which meets the normal at theta0 under 45 degrees (normal depth
// 2 r cos^2(theta0) (1 - eta) = r (1 - eta)). Level 0: degrees 3 x 3 x 3, 4 x 4 x 16 spans
// (sphere3d_coarse.yaml).
std::vector<ChartDirection> sphereChart(double r) {
  const double theta0 = M_PI / 4.0, phi0 = M_PI / 4.0;
  ChartDirection xi;
  xi.at = kSphereContactXi[0];
  xi.span0 = 1.0 / 4.0;
  xi.metres_per_knot = r * quarterArcSpeed(xi.at);
  xi.knot = [r, theta0](double s) { return knotOfQuarterArc(theta0 + s / r); };
  xi.reach_limit = 0.5 * r * M_PI / 2.0;  // the pole or the equator pi/4 away, each side
  ChartDirection eta;
  eta.depth = true;
  eta.at = 1.0;
  eta.span0 = 1.0 / 4.0;
  eta.metres_per_knot = 2.0 * r * std::cos(theta0);  // the chord: an element's edge
  eta.knot = [r](double d) { return 1.0 - d / r; };
  ChartDirection zeta;
  zeta.at = kSphereContactXi[2];
  zeta.span0 = 1.0 / 16.0;
  const double ring = r * std::sin(theta0);  // radius of the parallel through the contact
  zeta.metres_per_knot = ring * 4.0 * quarterArcSpeed(0.5);
  zeta.knot = [ring, phi0](double s) { return 0.25 * knotOfQuarterArc(phi0 + s / ring); };
  zeta.highest = 0.25;                         // a C0 knot line of the circle: no box crosses it
  zeta.reach_limit = 0.5 * ring * M_PI / 2.0;  // the seam or that line pi/4 away, each side
  return {xi, eta, zeta};
}

std::vector<ChartDirection> patchChart(const NurbsPatch& patch, const FacePoint& where,
                                       int face_direction, const std::vector<double>& xi,
                                       const std::vector<double>& span0) {
  std::vector<ChartDirection> chart;
  int k = 0;
  for (int a = 0; a < patch.paramDim(); ++a) {
    chart.push_back(a == face_direction ? depthDirection(patch, where, xi, a, span0[a])
                                        : lateralDirection(patch, where, xi, a, k++, span0[a]));
  }
  return chart;
}

std::vector<double> isoCurveLengths(const NurbsPatch& patch, const std::vector<double>& xi) {
  std::vector<double> lengths;
  for (int a = 0; a < patch.paramDim(); ++a) lengths.push_back(arcLength(patch, xi, a).f.back());
  return lengths;
}

}  // namespace ffriga
