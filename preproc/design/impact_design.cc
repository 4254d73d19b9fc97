#include "preproc/design/impact_design.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/base/error.h"

namespace ffriga {

namespace {

// The paper's 400-element model (sphere2d_base.yaml): degrees raised by two (p = 4, q = 3),
// 16 x 25 uniform spans.
constexpr int kBaseSpansXi = 16;
constexpr int kBaseSpansEta = 25;
// A bound is on a grid line when within this of it (the checks snap within 1e-9).
constexpr double kGridTolerance = 1e-9;

// The knot xi of the half-disk's upper arc at angle theta from the pole (inverse of the
// rational quadratic quarter arc's theta(xi) = pi/4 + 2 atan((2 xi - 1) tan(pi/8))).
double xiOfAngle(double theta) {
  return 0.5 * (1.0 + std::tan(0.5 * theta - M_PI / 8.0) / std::tan(M_PI / 8.0));
}

double ceilToGrid(double x, double h) { return std::ceil(x / h - kGridTolerance) * h; }
double floorToGrid(double x, double h) { return std::floor(x / h + kGridTolerance) * h; }

// Hertz's impact for the request, and the contact radius a = sqrt(R* delta_max).
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
  const double rStar = 1.0 / (1.0 / radius + 1.0 / partner.radius);
  d->hertz = h;
  d->approach_speed = request.approach_speed;
  d->contact_radius = std::sqrt(rStar * h.max_approach);
  d->max_pressure = hertzContactPatch(self, partner, h.max_force).max_pressure;
}

// Level count and boxes (header comment: levels, boxes).
void designHierarchy(double r, double a, double n, ImpactDesign* d) {
  const double dxi0 = 1.0 / kBaseSpansXi, deta0 = 1.0 / kBaseSpansEta;
  const double arc0 = std::sqrt(2.0) * r * dxi0, depth0 = 2.0 * r * deta0;
  const double target = a / n;
  const int halvings =
      std::max(0, static_cast<int>(std::ceil(std::log2(std::max(arc0, depth0) / target))));
  d->hierarchy.levels = halvings + 1;
  d->hierarchy.boxes.clear();
  double xiHi = 1.0, etaLo = 0.0;
  for (int l = 1; l <= halvings; ++l) {
    const double scale = std::ldexp(1.0, -(l - 1));  // level l - 1's spans: base x scale
    const double gx = dxi0 * scale, ge = deta0 * scale;
    const double arc = kRegionRadii * a + kLayerCells * arc0 * scale;
    const double depth = kFinestDepthRadii * a + kLayerCells * depth0 * scale;
    // Outwards onto the level l - 1 grid, inside the previous box (nested), off the
    // degenerate equator xi = 1 and off the lower arc.
    xiHi = std::min({ceilToGrid(xiOfAngle(arc / r), gx), xiHi, 1.0 - gx});
    etaLo = std::max({floorToGrid(1.0 - depth / (2.0 * r), ge), etaLo, ge});
    ParamBox box;
    box.lower = {0.0, etaLo, 0.0};
    box.upper = {xiHi, 1.0, 0.0};
    d->hierarchy.boxes.push_back(box);
  }
  d->finest_arc = arc0 * std::ldexp(1.0, -halvings);
  d->finest_depth = depth0 * std::ldexp(1.0, -halvings);
}

// The contact region: kRegionRadii a of arc on the finest grid, inside the finest box.
void designRegion(double r, double a, ImpactDesign* d) {
  const double theta = kRegionRadii * a / r;
  // The quarter arc from the pole to the equator (a degenerate point) is the face: a region
  // that would need more than half of it is no longer a Hertz contact of a sphere.
  if (theta > M_PI / 4.0) {
    throw std::invalid_argument(
        Str() << "the contact radius a = " << a << " m needs a contact region of "
              << kRegionRadii << " a = " << kRegionRadii * a << " m of arc, more than half ("
              << M_PI / 4.0 * r << " m) of the quarter arc from the pole to the equator");
  }
  const double gx = std::ldexp(1.0 / kBaseSpansXi, -(d->hierarchy.levels - 1));
  double xi = ceilToGrid(xiOfAngle(theta), gx);
  if (!d->hierarchy.boxes.empty()) xi = std::min(xi, d->hierarchy.boxes.back().upper[0]);
  d->region = {{0.0, xi}};
}

void explain(double r, const DesignRequest& q, ImpactDesign* d) {
  auto& out = d->reasons;
  if (d->hertz) {
    const HertzImpact& h = *d->hertz;
    out.push_back(Str() << "impact: approach speed " << d->approach_speed << " m/s against "
                        << (q.partner == DesignRequest::Partner::kSame    ? "the same body"
                            : q.partner == DesignRequest::Partner::kPlane ? "a rigid plane"
                                                                          : "a sphere")
                        << "; Hertz: force peak " << h.max_force << " N, approach "
                        << h.max_approach << " m, duration " << h.duration << " s");
    out.push_back(Str() << "contact radius a = sqrt(R* delta) = " << d->contact_radius
                        << " m, peak pressure p0 = " << d->max_pressure << " Pa");
  } else {
    out.push_back(Str() << "contact radius a = " << d->contact_radius << " m (given)");
  }
  out.push_back(Str() << "level 0: the paper's 400-element model (degrees 4 x 3, " << kBaseSpansXi
                      << " x " << kBaseSpansEta << " spans), at the pole "
                      << std::sqrt(2.0) * r / kBaseSpansXi << " m of arc x "
                      << 2.0 * r / kBaseSpansEta << " m deep");
  out.push_back(Str() << "levels: " << d->hierarchy.levels << " (" << d->hierarchy.levels - 1
                      << " halvings bring the finest spans to " << d->finest_arc << " x "
                      << d->finest_depth << " m, below a / " << d->elements_per_contact_radius
                      << " = " << d->contact_radius / d->elements_per_contact_radius << " m)");
  out.push_back(Str() << "boxes: " << kRegionRadii << " a of arc and " << kFinestDepthRadii
                      << " a deep, plus " << kLayerCells
                      << " cells of the next coarser level, per level");
  out.push_back(Str() << "contact region: xi in [0, " << d->region[0][1] << "], "
                      << kRegionRadii << " a of arc on the finest grid");
  out.push_back(Str() << "stress line 'axis': " << kStressLineRadii << " a deep under the "
                      << "contact point, " << d->stress_points << " points");
}

}  // namespace

double sphereMass(double radius, double density) {
  return density * 4.0 / 3.0 * M_PI * radius * radius * radius;
}

ImpactDesign designHalfDiskImpact(double radius, const IsotropicMaterial& material,
                                  double mass, const DesignRequest& request) {
  ImpactDesign d;
  resolveImpact(radius, material, mass, request, &d);
  const double a = d.contact_radius;
  d.elements_per_contact_radius = request.elements_per_contact_radius;
  d.refinement.elevate_degree = {2, 2};
  d.refinement.insert_knots = {kBaseSpansXi - 1, kBaseSpansEta - 1};
  d.refinement.insert = {{}, {}};
  designHierarchy(radius, a, request.elements_per_contact_radius, &d);
  designRegion(radius, a, &d);
  // The axis under the pole (geometry coordinates: the pole is (0, r)), one point per
  // finest depth span / 2 at most 2001.
  const double depth = std::min(kStressLineRadii * a, radius);
  d.stress_from = {0.0, radius};
  d.stress_to = {0.0, radius - depth};
  d.stress_points = std::clamp(static_cast<int>(std::ceil(2.0 * depth / d.finest_depth)) + 1,
                               101, 2001);
  explain(radius, request, &d);
  return d;
}

}  // namespace ffriga
