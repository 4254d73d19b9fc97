#include "runtime/contact/closest_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/base/error.h"
#include "common/splines/rational_basis.h"

namespace ffriga {

namespace {

// Element holding s; if s lies in a hole of the domain, the element whose box is nearest
// (s is then moved into that box).
int locate(const ExtractedSurface& surf, Eigen::VectorXd& s, int hint) {
  const int d = surf.dim();
  auto inside = [&](int e) {
    for (int a = 0; a < d; ++a) {
      if (s(a) < surf.surface().element_lower(e, a) || s(a) > surf.surface().element_upper(e, a))
        return false;
    }
    return true;
  };
  if (hint >= 0 && hint < surf.numElements() && inside(hint)) return hint;
  const int e = surf.findElement(s.data());
  if (e >= 0) return e;
  int best = 0;
  double bestDist = std::numeric_limits<double>::infinity();
  for (int k = 0; k < surf.numElements(); ++k) {
    const Eigen::VectorXd c = s.cwiseMax(surf.elementLower(k)).cwiseMin(surf.elementUpper(k));
    const double dist = (c - s).squaredNorm();
    if (dist < bestDist) {
      bestDist = dist;
      best = k;
    }
  }
  s = s.cwiseMax(surf.elementLower(best)).cwiseMin(surf.elementUpper(best));
  return best;
}

// Small fixed-capacity types (parametric dimension <= 2, space dimension <= 3; with
// ParamVector and SpaceVector of runtime/bodies/space_vector.h): the Newton loop runs for
// every collocation point at every right-hand side and must not allocate.
using ParamMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 2, 2>;

// Active bounds: the directions held at the domain boundary, where the descent direction -g
// points out of the domain (held[a]), and the free ones (freeDirs[0 .. nf - 1]).
int freeDirections(const Eigen::VectorXd& s, const ParamVector& g, const Eigen::VectorXd& lo,
                   const Eigen::VectorXd& hi, int d, int freeDirs[2], bool held[2]) {
  int nf = 0;
  for (int a = 0; a < d; ++a) {
    const bool atLo = s(a) <= lo(a) && g(a) > 0.0;
    const bool atHi = s(a) >= hi(a) && g(a) < 0.0;
    held[a] = atLo || atHi;
    if (!held[a]) freeDirs[nf++] = a;
  }
  return nf;
}

// Convergence: the gradient vanishes in every free direction (Eq. 15),
// |g_a| <= tol |x_a| (|r| + length) with length = max |x_a| times the domain's size.
bool gradientVanishes(const ParamVector& g, const Eigen::MatrixXd& X, const SpaceVector& r,
                      double paramScale, const int freeDirs[2], int nf,
                      const ProjectionOptions& o) {
  const double length = (X.colwise().norm().maxCoeff()) * paramScale;
  bool small = true;
  for (int i = 0; i < nf; ++i) {
    const int a = freeDirs[i];
    if (std::abs(g(a)) > o.tolerance * X.col(a).norm() * (r.norm() + length)) small = false;
  }
  return small;
}

// Newton step on the free directions, H_f step_f = -g_f (Gauss-Newton, G_f step_f = -g_f,
// if H is not positive definite there), zero in the held ones; `decrease` is the predicted
// decrease of phi, -1/2 g_f^T step_f.
ParamVector newtonStep(const ParamVector& g, const ParamMatrix& H, const ParamMatrix& G,
                       const int freeDirs[2], int nf, int d, double& decrease) {
  ParamMatrix Hf(nf, nf), Gf(nf, nf);
  ParamVector gf(nf);
  for (int i = 0; i < nf; ++i) {
    gf(i) = g(freeDirs[i]);
    for (int j = 0; j < nf; ++j) {
      Hf(i, j) = H(freeDirs[i], freeDirs[j]);
      Gf(i, j) = G(freeDirs[i], freeDirs[j]);
    }
  }
  Eigen::LLT<ParamMatrix> llt(Hf);
  const ParamVector sf = llt.info() == Eigen::Success ? ParamVector(-llt.solve(gf))
                                                      : ParamVector(-Gf.ldlt().solve(gf));
  ParamVector step = ParamVector::Zero(d);
  for (int i = 0; i < nf; ++i) step(freeDirs[i]) = sf(i);
  decrease = -0.5 * gf.dot(sf);
  return step;
}

// Backtracking from p.s: accepts the first of step, step/2, ... (at most 30, clamped to the
// domain) that does not increase phi = |r|^2 / 2 (Newton's full step near the solution;
// guards Gauss-Newton far from it); s and e: the point reached and its element, trial the
// surface there. Returns the number of halvings.
int backtrack(const ExtractedSurface& surf, const Eigen::MatrixXd& points, const VectorRef& x,
              const SurfaceProjection& p, const SpaceVector& r, double decrease, ParamVector& step,
              Eigen::VectorXd& s, int& e, SurfacePoint& trial) {
  const Eigen::VectorXd& lo = surf.domainLower();
  const Eigen::VectorXd& hi = surf.domainUpper();
  const double phi = 0.5 * r.squaredNorm();
  s = p.s;
  e = p.element;
  // The full step's trial is evaluated to second order (it is the next iterate when
  // accepted, as near the solution); the halvings only to order 0.
  // A step whose predicted decrease of phi, -1/2 g^T step, is below phi's round-off (a few
  // ulps) cannot be tested by it: the point is a minimum to round-off (seen for points
  // beyond an edge, |r| ~ 0.1 mm, where up to 22 halvings used to end in the same place).
  const bool belowRoundOff = decrease <= 8.0 * std::numeric_limits<double>::epsilon() * phi;
  int k = 0;
  for (; k < 30 && !belowRoundOff; ++k) {
    s = (p.s + step).cwiseMax(lo).cwiseMin(hi);
    e = locate(surf, s, p.element);
    surf.evaluate(e, s.data(), points, k == 0 ? 2 : 0, trial);
    if (0.5 * (trial.x - x).squaredNorm() <= phi) break;
    step *= 0.5;
  }
  return k;
}

// Whether a converged foot point is proper: no direction a in which `bound[a]` says s is at
// the domain boundary has a gradient |g_a| above round-off, edge_tolerance |x_a| |r|.
bool orthogonalAtBounds(const ParamVector& g, const Eigen::MatrixXd& X, const SpaceVector& r,
                        const bool bound[2], int d, const ProjectionOptions& o) {
  bool orthogonal = true;
  for (int a = 0; a < d; ++a) {
    if (bound[a] && std::abs(g(a)) > o.edge_tolerance * X.col(a).norm() * r.norm())
      orthogonal = false;
  }
  return orthogonal;
}

bool newton(const ExtractedSurface& surf, const Eigen::MatrixXd& points, const VectorRef& x,
            const ProjectionOptions& o, SurfaceProjection& p) {
  const int d = surf.dim();
  const Eigen::VectorXd& lo = surf.domainLower();
  const Eigen::VectorXd& hi = surf.domainUpper();
  const double paramScale = (hi - lo).maxCoeff();
  // Per-thread workspaces of the line search (storage reused, no allocation).
  // The trial point of an accepted full step is evaluated with second derivatives and
  // becomes the next iterate's point: a search from a warm start takes two evaluations,
  // not four.
  thread_local SurfacePoint trial;
  thread_local Eigen::VectorXd s;
  bool evaluated = false;  // p.point holds the surface at p.s (order 2)
  for (int it = 0; it < o.max_iterations; ++it) {
    if (!evaluated) {
      p.element = locate(surf, p.s, p.element);
      surf.evaluate(p.element, p.s.data(), points, 2, p.point);
      evaluated = true;
    }
    // phi's gradient g, Gauss-Newton matrix G and Hessian H at p.s (header comment).
    const SpaceVector r = p.point.x - x;
    const Eigen::MatrixXd& X = p.point.dx;
    const ParamVector g = X.transpose() * r;
    ParamMatrix H = X.transpose() * X;
    const ParamMatrix G = H;
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b)
        H(a, b) += r.dot(p.point.ddx.col(secondDerivativeRow(d, a, b) - 1 - d));
    int freeDirs[2];
    bool held[2] = {false, false};
    const int nf = freeDirections(p.s, g, lo, hi, d, freeDirs, held);
    if (gradientVanishes(g, X, r, paramScale, freeDirs, nf, o)) {
      // Eq. (15) holds in the free directions. A direction held at the domain boundary
      // (x_C beyond the surface's edge) makes the foot point improper if the gradient there
      // is more than round-off. Free directions are never tested again: for a point close
      // to the surface, |r| -> 0 and a test relative to |r| would reject converged interior
      // points and switch their contact force off discontinuously.
      p.converged = true;
      p.orthogonal = orthogonalAtBounds(g, X, r, held, d, o);
      return true;
    }
    double decrease = 0.0;
    ParamVector step = newtonStep(g, H, G, freeDirs, nf, d, decrease);
    if (!step.allFinite()) return false;
    int e = p.element;
    const int k = backtrack(surf, points, x, p, r, decrease, step, s, e, trial);
    if ((s - p.s).norm() <= 1e-15 * paramScale) {
      // No progress possible: a (constrained) minimum to round-off.
      bool bound[2] = {false, false};
      for (int a = 0; a < d; ++a) bound[a] = s(a) <= lo(a) || s(a) >= hi(a);
      p.converged = true;
      p.orthogonal = orthogonalAtBounds(g, X, r, bound, d, o);
      return true;
    }
    p.s = s;
    p.element = e;
    if (k == 0) {
      std::swap(p.point, trial);  // the full step, evaluated at s to order 2
    } else {
      evaluated = false;  // a halved step: evaluate at the new s to order 2
    }
  }
  return false;
}

std::vector<SurfaceProjection> nearestSamples(const ExtractedSurface& surf,
                                              const Eigen::MatrixXd& points, const VectorRef& x,
                                              int n, int count) {
  const int d = surf.dim();
  // Best sample of every element, then the `count` nearest of those.
  std::vector<std::pair<double, SurfaceProjection>> perElement;
  SurfacePoint sp;
  Eigen::VectorXd s(d);
  for (int e = 0; e < surf.numElements(); ++e) {
    const Eigen::VectorXd lo = surf.elementLower(e), hi = surf.elementUpper(e);
    const int n1 = d == 2 ? n : 1;
    std::pair<double, SurfaceProjection> best{std::numeric_limits<double>::infinity(), {}};
    for (int j = 0; j < n1; ++j) {
      for (int i = 0; i < n; ++i) {
        s(0) = lo(0) + (hi(0) - lo(0)) * (i + 0.5) / n;
        if (d == 2) s(1) = lo(1) + (hi(1) - lo(1)) * (j + 0.5) / n;
        surf.evaluate(e, s.data(), points, 0, sp);
        const double dist = (sp.x - x).squaredNorm();
        if (dist < best.first) {
          best.first = dist;
          best.second.element = e;
          best.second.s = s;
        }
      }
    }
    perElement.push_back(best);
  }
  const int m = std::min<int>(count, static_cast<int>(perElement.size()));
  std::partial_sort(perElement.begin(), perElement.begin() + m, perElement.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<SurfaceProjection> out;
  for (int i = 0; i < m; ++i) out.push_back(perElement[i].second);
  return out;
}

}  // namespace

SurfaceProjection closestPoint(const ExtractedSurface& surface, const Eigen::MatrixXd& points,
                               const VectorRef& x, const SurfaceProjection* start,
                               const ProjectionOptions& options) {
  SurfaceProjection p;
  closestPoint(surface, points, x, start, p, options);
  return p;
}

void closestPoint(const ExtractedSurface& surface, const Eigen::MatrixXd& points,
                  const VectorRef& x, const SurfaceProjection* start, SurfaceProjection& p,
                  const ProjectionOptions& options) {
  FFRIGA_ASSERT(start != &p, "closestPoint: start and result are one object");
  p.converged = false;
  p.orthogonal = false;
  if (start && start->element >= 0 && start->s.size() == surface.dim()) {
    p.element = start->element;
    p.s = start->s;
    if (newton(surface, points, x, options, p)) return;
  }
  // Cold start: Newton from the nearest samples of the few nearest elements (distinct
  // basins of a curved surface), keeping the closest converged foot point.
  const std::vector<SurfaceProjection> starts =
      nearestSamples(surface, points, x, options.samples_per_element, options.restarts);
  SurfaceProjection best;
  double bestDist = std::numeric_limits<double>::infinity();
  for (const SurfaceProjection& start : starts) {
    p = start;
    if (!newton(surface, points, x, options, p)) continue;
    const double dist = (p.point.x - x).squaredNorm();
    if (dist < bestDist) {
      bestDist = dist;
      best = p;
    }
  }
  if (best.converged) {
    p = best;
    return;
  }
  p = starts.front();
  p.converged = false;
  p.orthogonal = false;
  surface.evaluate(p.element, p.s.data(), points, 1, p.point);
}

}  // namespace ffriga
