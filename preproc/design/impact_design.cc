#include "preproc/design/impact_design.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "common/base/error.h"
#include "common/mechanics/hertz_ellipse.h"
#include "preproc/design/contact_chart.h"
#include "preproc/geometry/contact_region.h"
#include "preproc/geometry/geometry_builders.h"
#include "preproc/geometry/patch_volume.h"

namespace ffriga {

namespace {

// A bound is on a grid line when within this of it (the checks snap within 1e-9).
constexpr double kGridTolerance = 1e-9;

double ceilToGrid(double x, double h) {
  return std::ceil(x / h - kGridTolerance) * h;
}
double floorToGrid(double x, double h) {
  return std::floor(x / h + kGridTolerance) * h;
}

// The partner of the request as Hertz sees it (a plane: infinitely stiff, large and heavy).
HertzSphere partnerOf(const DesignRequest& request, const HertzSphere& self) {
  const double inf = std::numeric_limits<double>::infinity();
  if (request.partner == DesignRequest::Partner::kPlane) return HertzSphere{inf, 0.0, inf, inf};
  if (request.partner == DesignRequest::Partner::kSphere) return request.partner_sphere;
  return self;
}

// Hertz's elliptical impact (common/mechanics/hertz_ellipse.h) of a surface with principal
// curvatures k1 < k2 against the request's partner, principal directions aligned (the same
// body turned over onto itself): the contact law's stiffness from the ellipse at 1 N, the
// impact with it, the ellipse at the force peak.
void resolveEllipticalImpact(double k1, double k2, const HertzSphere& self,
                             const DesignRequest& request, ImpactDesign* d) {
  const HertzSphere partner = partnerOf(request, self);
  const double kp1 = request.partner == DesignRequest::Partner::kSame ? k1 : 1.0 / partner.radius;
  const double kp2 = request.partner == DesignRequest::Partner::kSame ? k2 : 1.0 / partner.radius;
  // Aligned (relativeCurvatures at alpha = 0), formed directly: the same bits as always.
  const RelativeCurvatures r{0.5 * (k1 + kp1), 0.5 * (k2 + kp2)};
  const HertzImpact h = ellipticalHertzImpact(r, self, partner, request.approach_speed);
  const HertzEllipse peak = hertzEllipse(r.A, r.B, effectiveModulus(self, partner), h.max_force);
  d->hertz = h;
  d->approach_speed = request.approach_speed;
  d->contact_radius = peak.semi_major;
  d->contact_minor_radius = peak.semi_minor;
  d->max_pressure = peak.max_pressure;
}

// Hertz's impact for the request, and its contact patch at the force peak; `curvatures` of
// an explicit patch's point (ascending; empty for the built-in spheres of `radius`), an
// elliptical contact where they differ by more than kSphericalTolerance.
void resolveImpact(double radius, const std::vector<double>& curvatures,
                   const IsotropicMaterial& material, double mass, const DesignRequest& request,
                   ImpactDesign* d) {
  if (!request.from_impact) {
    d->contact_radius = d->contact_minor_radius = request.contact_radius;
    return;
  }
  const HertzSphere self{material.youngs_modulus, material.poisson_ratio, radius, mass};
  if (!curvatures.empty() &&
      curvatures.back() - curvatures.front() > kSphericalTolerance * curvatures.back()) {
    resolveEllipticalImpact(curvatures.front(), curvatures.back(), self, request, d);
    return;
  }
  const HertzSphere partner = partnerOf(request, self);
  const HertzImpact h = hertzImpact(self, partner, request.approach_speed);
  // The patch at the force peak: a = (3 F R* / (4 E*))^(1/3) = sqrt(R* delta_max).
  const HertzContactPatch patch = hertzContactPatch(self, partner, h.max_force);
  d->hertz = h;
  d->approach_speed = request.approach_speed;
  d->contact_radius = d->contact_minor_radius = patch.radius;
  d->max_pressure = patch.max_pressure;
}

// The interval of direction c covered by a box reaching `lateral` along the surface (both
// sides, or the one away from the patch's edge) or `deep` into the body, snapped outwards
// onto the grid of spacing g, inside the direction's limits (a limit is reached only where
// the contact point lies on it) and inside `outer` (the coarser box).
std::array<double, 2> interval(const ChartDirection& c, double lateral, double deep, double g,
                               const std::array<double, 2>& outer) {
  const bool onLowest = c.at <= c.lowest, onHighest = c.at >= c.highest;
  const double lo = c.depth ? c.knot(deep) : c.knot(-lateral);
  const double hi = c.depth ? c.knot(deep) : c.knot(lateral);
  std::array<double, 2> iv;
  iv[0] = onLowest ? c.lowest : std::max(floorToGrid(std::min(lo, c.at), g), c.lowest + g);
  iv[1] = onHighest ? c.highest : std::min(ceilToGrid(std::max(hi, c.at), g), c.highest - g);
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
    d->hierarchy.boxes.push_back({box});
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
                                   : std::array<double, 2>{d->hierarchy.boxes.back()[0].lower[k],
                                                           d->hierarchy.boxes.back()[0].upper[k]};
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
    if (d->contact_minor_radius < d->contact_radius) {
      out.push_back(Str() << "elliptical contact (principal curvatures differ): semi-axes a = "
                          << d->contact_radius << " m, b = " << d->contact_minor_radius
                          << " m, peak pressure p0 = " << d->max_pressure << " Pa");
    } else {
      out.push_back(Str() << "contact radius a = sqrt(R* delta) = " << d->contact_radius
                          << " m, peak pressure p0 = " << d->max_pressure << " Pa");
    }
  } else {
    out.push_back(Str() << "contact radius a = " << d->contact_radius << " m (given)");
  }
  out.push_back("level 0: " + level0);
  out.push_back(Str() << "levels: " << d->hierarchy.levels << " (" << d->hierarchy.levels - 1
                      << " halvings bring the finest spans at the contact point to "
                      << d->finest_arc << " m along the surface and " << d->finest_depth
                      << " m deep, below "
                      << (d->contact_minor_radius < d->contact_radius ? "b" : "a") << " / "
                      << d->elements_per_contact_radius << " = "
                      << d->contact_minor_radius / d->elements_per_contact_radius << " m)");
  out.push_back(Str() << "boxes: " << kRegionRadii << " a along the surface and "
                      << kFinestDepthRadii << " a deep, plus " << kLayerCells
                      << " cells of the next coarser level, per level");
  std::string region;
  for (const auto& iv : d->region)
    region += Str() << (region.empty() ? "" : " x ") << "[" << iv[0] << ", " << iv[1] << "]";
  out.push_back(Str() << "contact region: " << region << " on face "
                      << faceName(d->face_direction, d->face_upper) << ", " << kRegionRadii
                      << " a along the surface on the finest grid");
  out.push_back(Str() << "stress line 'axis': " << kStressLineRadii << " a deep under the "
                      << "contact point, " << d->stress_points << " points");
}

// The design on a chart: levels, boxes, region, the stress line from the contact point
// inwards along the normal, at most `thickness` deep (the body's extent there).
ImpactDesign designOnChart(const std::vector<ChartDirection>& chart, double radius,
                           const std::vector<double>& curvatures, const IsotropicMaterial& material,
                           double mass, const DesignRequest& request,
                           const Eigen::VectorXd& surface, const Eigen::VectorXd& outward,
                           double thickness) {
  ImpactDesign d;
  resolveImpact(radius, curvatures, material, mass, request, &d);
  const double a = d.contact_radius;
  d.elements_per_contact_radius = request.elements_per_contact_radius;
  d.surface_radius = radius;
  d.principal_curvatures = curvatures.empty()
                               ? std::array<double, 2>{1.0 / radius, 1.0 / radius}
                               : std::array<double, 2>{curvatures.front(), curvatures.back()};
  d.contact_point = surface;
  d.contact_normal = outward;
  designHierarchy(chart, d.contact_minor_radius, request.elements_per_contact_radius, &d);
  designRegion(chart, a, &d);
  const double depth = std::min(kStressLineRadii * a, thickness);
  d.stress_from = surface;
  d.stress_to = surface - depth * outward;
  d.stress_points =
      std::clamp(static_cast<int>(std::ceil(2.0 * depth / d.finest_depth)) + 1, 101, 2001);
  return d;
}

// Level 0 of an explicit patch (header comment): degree kLevel0Degree, uniform spans of
// about the same length in every direction, on a grid that holds the patch's own knots.
RefinementConfig designLevel0(const NurbsPatch& patch, const std::vector<double>& xi,
                              std::vector<double>* span0) {
  const int dims = patch.paramDim();
  const std::vector<double> lengths = isoCurveLengths(patch, xi);
  const double h = *std::min_element(lengths.begin(), lengths.end()) / kLevel0MinSpans;
  RefinementConfig r;
  span0->clear();
  for (int a = 0; a < dims; ++a) {
    const KnotVector& kn = patch.knots(a);
    if (kn.front() != 0.0 || kn.back() != 1.0) {
      throw std::invalid_argument(Str() << "a designed patch needs knot vectors from 0 to 1; "
                                        << "direction " << a << " runs from " << kn.front()
                                        << " to " << kn.back());
    }
    const int least = std::max(kLevel0MinSpans, static_cast<int>(std::ceil(lengths[a] / h)));
    int n = least;
    auto onGrid = [&kn](int m) {
      for (double b : kn.breaks())
        if (std::abs(b * m - std::round(b * m)) > kGridTolerance * m) return false;
      return true;
    };
    while (!onGrid(n) && n < 8 * least) ++n;
    if (!onGrid(n)) {
      throw std::invalid_argument(Str() << "the knots of direction " << a << " lie on no uniform"
                                        << " grid of " << least << " to " << 8 * least
                                        << " spans; the design's level 0 needs one");
    }
    r.elevate_degree.push_back(std::max(0, kLevel0Degree - patch.degree(a)));
    r.insert_knots.push_back(0);
    std::vector<double> insert;
    const std::vector<double> breaks = kn.breaks();
    for (int j = 1; j < n; ++j) {
      const double u = static_cast<double>(j) / n;
      if (std::none_of(breaks.begin(), breaks.end(),
                       [u](double b) { return std::abs(b - u) < kGridTolerance; }))
        insert.push_back(u);
    }
    r.insert.push_back(insert);
    span0->push_back(1.0 / n);
  }
  return r;
}

// The checks of an explicit patch's contact point (schemas/body_design.md): on the body,
// not degenerate, on the axis of an axisymmetric section (and smooth there), inside the
// face of a solid, convex; spherical where the design comes from an impact.
void checkContactPoint(const FacePoint& f, const std::vector<double>& xi, int face_direction,
                       bool axisymmetric, bool from_impact) {
  for (std::size_t a = 0; a < xi.size(); ++a) {
    if (static_cast<int>(a) != face_direction && (xi[a] < 0.0 || xi[a] > 1.0))
      throw std::invalid_argument(Str() << "the contact point's parameters must lie in [0, 1] "
                                        << "(on the face); direction " << a << " has " << xi[a]);
  }
  if (f.degenerate()) {
    throw std::invalid_argument(
        "the contact point is a degenerate point of the face (its surface Jacobian vanishes: "
        "a pole, a collapsed edge or a seam); choose a regular point");
  }
  const double tol = 1e-9 * f.size;
  if (axisymmetric) {
    if (std::abs(f.x(0)) > tol) {
      throw std::invalid_argument(Str() << "an axisymmetric impact happens on the axis x = 0; "
                                        << "the contact point is at x = " << f.x(0) << " m");
    }
    const Eigen::VectorXd t = f.tangents[0].normalized();
    if (std::abs(t(1)) > 1e-6) {
      throw std::invalid_argument(Str()
                                  << "the surface is not smooth on the axis (its meridian "
                                  << "meets the axis at " << std::acos(std::abs(t(1))) * 180 / M_PI
                                  << " degrees, not 90): a tip, no Hertz contact");
    }
  } else {
    for (std::size_t a = 0; a < xi.size(); ++a) {
      if (static_cast<int>(a) != face_direction && (xi[a] <= 0.0 || xi[a] >= 1.0))
        throw std::invalid_argument(Str()
                                    << "the contact point of a solid must lie inside its "
                                    << "face; direction " << a << " is on the edge " << xi[a]);
    }
  }
  // (+ 0.0: a flat face prints 0, not -0)
  const double k1 = f.curvatures.front() + 0.0, k2 = f.curvatures.back() + 0.0;
  if (!(k1 > 0.0)) {
    const std::string both = f.curvatures.size() > 1
                                 ? std::string(Str() << "s " << k1 << " and " << k2)
                                 : Str() << " " << k1;
    throw std::invalid_argument(Str() << "the contact point is not convex (principal curvature"
                                      << both << " 1/m; concave < 0, flat 0): Hertz's contact "
                                      << "needs a convex point");
  }
  if (from_impact && k2 / k1 > kMaxCurvatureRatio) {
    throw std::invalid_argument(Str() << "the principal radii of curvature " << 1.0 / k2 << " and "
                                      << 1.0 / k1 << " m differ by more than a factor "
                                      << kMaxCurvatureRatio << ": a contact line rather than a "
                                      << "Hertz ellipse; give design.contact_radius (the "
                                      << "ellipse's larger semi-axis)");
  }
}

}  // namespace

double sphereMass(double radius, double density) {
  return density * 4.0 / 3.0 * M_PI * radius * radius * radius;
}

ImpactDesign designHalfDiskImpact(double radius, const IsotropicMaterial& material, double mass,
                                  const DesignRequest& request) {
  ImpactDesign d = designOnChart(halfDiskChart(radius), radius, {}, material, mass, request,
                                 Eigen::Vector2d(0.0, radius), Eigen::Vector2d(0.0, 1.0), radius);
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
                                const DesignRequest& request, const Eigen::Vector3d& direction) {
  const std::vector<ChartDirection> chart = sphereChart(radius);
  const Eigen::Vector3d n = direction.normalized();
  ImpactDesign d = designOnChart(chart, radius, {}, material, mass, request, radius * n, n, radius);
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

ImpactDesign designPatchImpact(const NurbsPatch& patch, bool axisymmetric,
                               const IsotropicMaterial& material, int face_direction,
                               bool face_upper, const std::vector<double>& parameters,
                               const DesignRequest& request) {
  std::vector<double> xi;
  for (int a = 0, k = 0; a < patch.paramDim(); ++a)
    xi.push_back(a == face_direction ? (face_upper ? 1.0 : 0.0) : parameters[k++]);
  const FacePoint f = facePoint(patch, face_direction, face_upper, xi);
  checkContactPoint(f, xi, face_direction, axisymmetric, request.from_impact);
  std::vector<double> span0;
  const RefinementConfig level0 = designLevel0(patch, xi, &span0);
  const std::vector<ChartDirection> chart = patchChart(patch, f, face_direction, xi, span0);
  // The surface's radius of curvature at the point (spherical: the mean of the two).
  double mean = 0.0;
  for (double k : f.curvatures) mean += k / f.curvatures.size();
  const double mass = material.density * patchVolume(patch, axisymmetric);
  ImpactDesign d = designOnChart(chart, 1.0 / mean, f.curvatures, material, mass, request, f.x,
                                 f.normal, chart[face_direction].reach_limit);
  d.face_direction = face_direction;
  d.face_upper = face_upper;
  if (f.curvatures.back() - f.curvatures.front() > kSphericalTolerance * f.curvatures.back()) {
    d.surface_radius = 0.0;  // not a sphere's point
    d.principal_direction = f.directions.front();
  }
  d.refinement = level0;
  std::string spans;
  for (int a = 0; a < patch.paramDim(); ++a) {
    spans += Str() << (a ? " x " : "") << std::lround(1.0 / span0[a]);
  }
  explain(request,
          Str() << "the patch at degree >= " << kLevel0Degree << ", " << spans
                << " uniform spans (at least " << kLevel0MinSpans
                << " across its shortest extent), surface radius of curvature " << 1.0 / mean
                << " m at the contact point, mass " << mass << " kg",
          &d);
  return d;
}

}  // namespace ffriga
