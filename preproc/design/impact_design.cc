#include "preproc/design/impact_design.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "common/base/error.h"
#include "preproc/geometry/geometry_builders.h"

namespace ffriga {

namespace {

// A bound is on a grid line when within this of it (the checks snap within 1e-9).
constexpr double kGridTolerance = 1e-9;

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

double ceilToGrid(double x, double h) {
  return std::ceil(x / h - kGridTolerance) * h;
}
double floorToGrid(double x, double h) {
  return std::floor(x / h + kGridTolerance) * h;
}

// How one parametric direction of the patch passes through the contact point: along the
// surface (lateral, the boxes reach kRegionRadii a plus layers to both sides, or to one side
// where the contact point lies on the patch's edge: the half-disk's axis) or into the body
// (depth, from the contact face inwards).
struct ChartDirection {
  bool depth = false;
  bool one_sided = false;              // lateral, the contact point on the lower edge (knot 0)
  double at = 0.0;                     // the contact point's knot
  double span0 = 0.0;                  // level-0 knot span there
  double metres_per_knot = 0.0;        // length per knot there (m)
  std::function<double(double)> knot;  // knot at signed distance s (m) from the contact
                                       // point along the surface, or at depth s (>= 0)
  double lowest = 0.0, highest = 1.0;  // the boxes' limits (exclusive unless the contact
                                       // point's own edge)
  double reach_limit = 0.0;            // lateral: half the surface's extent from the contact point
                                       // to the nearest limit (m): the largest region it admits
};

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
  zeta.highest = 0.25;  // a C0 knot line of the circle: no box crosses it
  zeta.reach_limit = 0.5 * ring * M_PI / 2.0;  // the seam or that line pi/4 away, each side
  return {xi, eta, zeta};
}

// Hertz's impact for the request, and its contact patch at the force peak.
void resolveImpact(double radius, const IsotropicMaterial& material, double mass,
                   const DesignRequest& request, ImpactDesign* d) {
  if (!request.from_impact) {
    d->contact_radius = request.contact_radius;
    return;
  }
  const HertzSphere self{material.youngs_modulus, material.poisson_ratio, radius, mass};
  const double inf = std::numeric_limits<double>::infinity();
  HertzSphere partner = self;
  if (request.partner == DesignRequest::Partner::kPlane) partner = HertzSphere{inf, 0.0, inf, inf};
  if (request.partner == DesignRequest::Partner::kSphere) partner = request.partner_sphere;
  const HertzImpact h = hertzImpact(self, partner, request.approach_speed);
  // The patch at the force peak: a = (3 F R* / (4 E*))^(1/3) = sqrt(R* delta_max).
  const HertzContactPatch patch = hertzContactPatch(self, partner, h.max_force);
  d->hertz = h;
  d->approach_speed = request.approach_speed;
  d->contact_radius = patch.radius;
  d->max_pressure = patch.max_pressure;
}

// The interval of direction c covered by a box reaching `lateral` along the surface (both
// sides) or `deep` into the body, snapped outwards onto the grid of spacing g, inside the
// direction's limits and inside `outer` (the coarser box).
std::array<double, 2> interval(const ChartDirection& c, double lateral, double deep, double g,
                               const std::array<double, 2>& outer) {
  std::array<double, 2> iv;
  if (c.depth) {
    iv = {std::max(floorToGrid(c.knot(deep), g), c.lowest + g), c.at};
  } else {
    const double lo = c.one_sided ? c.lowest : floorToGrid(c.knot(-lateral), g);
    iv = {c.one_sided ? lo : std::max(lo, c.lowest + g),
          std::min(ceilToGrid(c.knot(lateral), g), c.highest - g)};
  }
  return {std::max(iv[0], outer[0]), std::min(iv[1], outer[1])};
}

// Level count and boxes (header comment: levels, boxes).
void designHierarchy(const std::vector<ChartDirection>& chart, double a, double n,
                     ImpactDesign* d) {
  double coarsest = 0.0;
  for (const ChartDirection& c : chart) coarsest = std::max(coarsest, c.span0 * c.metres_per_knot);
  const int halvings = std::max(0, static_cast<int>(std::ceil(std::log2(coarsest / (a / n)))));
  const int dims = static_cast<int>(chart.size());
  d->hierarchy.levels = halvings + 1;
  d->hierarchy.boxes.clear();
  std::vector<std::array<double, 2>> outer(dims, {0.0, 1.0});
  for (int l = 1; l <= halvings; ++l) {
    const double scale = std::ldexp(1.0, -(l - 1));  // level l - 1's spans: level 0's x scale
    ParamBox box;
    for (int k = 0; k < dims; ++k) {
      const ChartDirection& c = chart[k];
      const double g = c.span0 * scale, layer = kLayerCells * g * c.metres_per_knot;
      outer[k] = interval(c, kRegionRadii * a + layer, kFinestDepthRadii * a + layer, g, outer[k]);
      box.lower[k] = outer[k][0];
      box.upper[k] = outer[k][1];
    }
    d->hierarchy.boxes.push_back(box);
  }
  d->finest_arc = 0.0;
  for (const ChartDirection& c : chart) {
    const double h = std::ldexp(c.span0 * c.metres_per_knot, -halvings);
    if (c.depth)
      d->finest_depth = h;
    else
      d->finest_arc = std::max(d->finest_arc, h);
  }
}

// The contact region: kRegionRadii a to each side along the surface, on the finest grid,
// inside the finest box. A region beyond half the patch's extent there (the half-disk's
// quarter arc from pole to equator, the sphere's octant around its contact point) is no
// longer a Hertz contact of a sphere.
void designRegion(const std::vector<ChartDirection>& chart, double a, ImpactDesign* d) {
  const double reach = kRegionRadii * a;
  double limit = std::numeric_limits<double>::infinity();
  for (const ChartDirection& c : chart)
    if (!c.depth) limit = std::min(limit, c.reach_limit);
  if (reach > limit) {
    throw std::invalid_argument(
        Str() << "the contact radius a = " << a << " m needs a contact region reaching "
              << kRegionRadii << " a = " << reach << " m along the surface, more than " << limit
              << " m, half the patch's extent around the contact point");
  }
  d->region.clear();
  const int halvings = d->hierarchy.levels - 1;
  for (std::size_t k = 0; k < chart.size(); ++k) {
    const ChartDirection& c = chart[k];
    if (c.depth) continue;
    const std::array<double, 2> finest =
        d->hierarchy.boxes.empty() ? std::array<double, 2>{0.0, 1.0}
                                   : std::array<double, 2>{d->hierarchy.boxes.back().lower[k],
                                                           d->hierarchy.boxes.back().upper[k]};
    d->region.push_back(interval(c, reach, 0.0, std::ldexp(c.span0, -halvings), finest));
  }
}

const char* partnerName(DesignRequest::Partner p) {
  return p == DesignRequest::Partner::kSame    ? "the same body"
         : p == DesignRequest::Partner::kPlane ? "a rigid plane"
                                               : "a sphere";
}

void explain(const DesignRequest& q, const std::string& level0, ImpactDesign* d) {
  auto& out = d->reasons;
  if (d->hertz) {
    const HertzImpact& h = *d->hertz;
    out.push_back(Str() << "impact: approach speed " << d->approach_speed << " m/s against "
                        << partnerName(q.partner) << "; Hertz: force peak " << h.max_force
                        << " N, approach " << h.max_approach << " m, duration " << h.duration
                        << " s");
    out.push_back(Str() << "contact radius a = sqrt(R* delta) = " << d->contact_radius
                        << " m, peak pressure p0 = " << d->max_pressure << " Pa");
  } else {
    out.push_back(Str() << "contact radius a = " << d->contact_radius << " m (given)");
  }
  out.push_back("level 0: " + level0);
  out.push_back(Str() << "levels: " << d->hierarchy.levels << " (" << d->hierarchy.levels - 1
                      << " halvings bring the finest spans at the contact point to "
                      << d->finest_arc << " m along the surface and " << d->finest_depth
                      << " m deep, below a / " << d->elements_per_contact_radius << " = "
                      << d->contact_radius / d->elements_per_contact_radius << " m)");
  out.push_back(Str() << "boxes: " << kRegionRadii << " a along the surface and "
                      << kFinestDepthRadii << " a deep, plus " << kLayerCells
                      << " cells of the next coarser level, per level");
  std::string region;
  for (const auto& iv : d->region)
    region += Str() << (region.empty() ? "" : " x ") << "[" << iv[0] << ", " << iv[1] << "]";
  out.push_back(Str() << "contact region: " << region << " on face eta_max, " << kRegionRadii
                      << " a along the surface on the finest grid");
  out.push_back(Str() << "stress line 'axis': " << kStressLineRadii << " a deep under the "
                      << "contact point, " << d->stress_points << " points");
}

// The design on a chart: levels, boxes, region, the stress line from `surface` inwards
// along `inward` (geometry coordinates).
ImpactDesign designOnChart(const std::vector<ChartDirection>& chart, double radius,
                           const IsotropicMaterial& material, double mass,
                           const DesignRequest& request, const Eigen::VectorXd& surface,
                           const Eigen::VectorXd& inward) {
  ImpactDesign d;
  resolveImpact(radius, material, mass, request, &d);
  const double a = d.contact_radius;
  d.elements_per_contact_radius = request.elements_per_contact_radius;
  designHierarchy(chart, a, request.elements_per_contact_radius, &d);
  designRegion(chart, a, &d);
  const double depth = std::min(kStressLineRadii * a, radius);
  d.stress_from = surface;
  d.stress_to = surface + depth * inward;
  d.stress_points =
      std::clamp(static_cast<int>(std::ceil(2.0 * depth / d.finest_depth)) + 1, 101, 2001);
  return d;
}

}  // namespace

double sphereMass(double radius, double density) {
  return density * 4.0 / 3.0 * M_PI * radius * radius * radius;
}

ImpactDesign designHalfDiskImpact(double radius, const IsotropicMaterial& material, double mass,
                                  const DesignRequest& request) {
  ImpactDesign d = designOnChart(halfDiskChart(radius), radius, material, mass, request,
                                 Eigen::Vector2d(0.0, radius), Eigen::Vector2d(0.0, -1.0));
  d.refinement.elevate_degree = {2, 2};
  d.refinement.insert_knots = {15, 24};
  d.refinement.insert = {{}, {}};
  explain(request,
          Str() << "the paper's 400-element model (degrees 4 x 3, 16 x 25 spans), at the pole "
                << std::sqrt(2.0) * radius / 16.0 << " m of arc x " << 2.0 * radius / 25.0
                << " m deep",
          &d);
  return d;
}

ImpactDesign designSphereImpact(double radius, const IsotropicMaterial& material, double mass,
                                const DesignRequest& request) {
  const std::vector<ChartDirection> chart = sphereChart(radius);
  ImpactDesign d =
      designOnChart(chart, radius, material, mass, request, Eigen::Vector3d(0.0, 0.0, radius),
                    Eigen::Vector3d(0.0, 0.0, -1.0));
  d.refinement.elevate_degree = {1, 2, 1};
  d.refinement.insert_knots = {3, 3, 3};
  d.refinement.insert = {{}, {}, {}};
  explain(request,
          Str() << "degrees 3 x 3 x 3, 4 x 4 x 16 spans (sphere3d_coarse), at the contact point "
                << chart[0].span0 * chart[0].metres_per_knot << " x "
                << chart[2].span0 * chart[2].metres_per_knot << " m along the surface, "
                << chart[1].span0 * chart[1].metres_per_knot << " m deep",
          &d);
  return d;
}

}  // namespace ffriga
