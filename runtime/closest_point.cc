#include "runtime/closest_point.h"

#include <cmath>
#include <limits>

#include "common/rational_basis.h"

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

bool newton(const ExtractedSurface& surf, const Eigen::MatrixXd& points, const Eigen::VectorXd& x,
            const ProjectionOptions& o, SurfaceProjection& p) {
  const int d = surf.dim();
  const Eigen::VectorXd lo = surf.domainLower(), hi = surf.domainUpper();
  const double paramScale = (hi - lo).maxCoeff();
  for (int it = 0; it < o.max_iterations; ++it) {
    p.element = locate(surf, p.s, p.element);
    surf.evaluate(p.element, p.s.data(), points, 2, p.point);
    const Eigen::VectorXd r = p.point.x - x;
    const Eigen::MatrixXd& X = p.point.dx;
    const Eigen::VectorXd g = X.transpose() * r;
    Eigen::MatrixXd H = X.transpose() * X;
    const Eigen::MatrixXd G = H;
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b)
        H(a, b) += r.dot(p.point.ddx.col(secondDerivativeRow(d, a, b) - 1 - d));
    Eigen::LLT<Eigen::MatrixXd> llt(H);
    Eigen::VectorXd step = llt.info() == Eigen::Success ? Eigen::VectorXd(-llt.solve(g))
                                                        : Eigen::VectorXd(-G.ldlt().solve(g));
    // Converged if the gradient vanishes in every free direction (Eq. 15); at the domain
    // boundary a gradient pushing outward is allowed (the constrained minimum).
    const double length = (X.colwise().norm().maxCoeff()) * paramScale;
    bool small = true;
    for (int a = 0; a < d; ++a) {
      const bool atLo = p.s(a) <= lo(a) && g(a) > 0.0;
      const bool atHi = p.s(a) >= hi(a) && g(a) < 0.0;
      if (atLo || atHi) {
        step(a) = 0.0;
        continue;
      }
      if (std::abs(g(a)) > o.tolerance * X.col(a).norm() * (r.norm() + length)) small = false;
    }
    if (small) {
      p.converged = true;
      p.orthogonal = true;
      for (int a = 0; a < d; ++a) {
        if (std::abs(g(a)) > o.edge_tolerance * X.col(a).norm() * r.norm() + 1e-300)
          p.orthogonal = false;
      }
      surf.evaluate(p.element, p.s.data(), points, 1, p.point);
      return true;
    }
    if (!step.allFinite()) return false;
    p.s = (p.s + step).cwiseMax(lo).cwiseMin(hi);
  }
  return false;
}

SurfaceProjection nearestSample(const ExtractedSurface& surf, const Eigen::MatrixXd& points,
                                const Eigen::VectorXd& x, int n) {
  const int d = surf.dim();
  SurfaceProjection best;
  double bestDist = std::numeric_limits<double>::infinity();
  SurfacePoint sp;
  Eigen::VectorXd s(d);
  for (int e = 0; e < surf.numElements(); ++e) {
    const Eigen::VectorXd lo = surf.elementLower(e), hi = surf.elementUpper(e);
    const int n1 = d == 2 ? n : 1;
    for (int j = 0; j < n1; ++j) {
      for (int i = 0; i < n; ++i) {
        s(0) = lo(0) + (hi(0) - lo(0)) * (i + 0.5) / n;
        if (d == 2) s(1) = lo(1) + (hi(1) - lo(1)) * (j + 0.5) / n;
        surf.evaluate(e, s.data(), points, 0, sp);
        const double dist = (sp.x - x).squaredNorm();
        if (dist < bestDist) {
          bestDist = dist;
          best.element = e;
          best.s = s;
        }
      }
    }
  }
  return best;
}

}  // namespace

SurfaceProjection closestPoint(const ExtractedSurface& surface, const Eigen::MatrixXd& points,
                               const Eigen::VectorXd& x, const SurfaceProjection* start,
                               const ProjectionOptions& options) {
  SurfaceProjection p;
  if (start && start->element >= 0 && start->s.size() == surface.dim()) {
    p.element = start->element;
    p.s = start->s;
    if (newton(surface, points, x, options, p)) return p;
  }
  p = nearestSample(surface, points, x, options.samples_per_element);
  const SurfaceProjection sample = p;
  if (newton(surface, points, x, options, p)) return p;
  p = sample;
  p.converged = false;
  p.orthogonal = false;
  surface.evaluate(p.element, p.s.data(), points, 1, p.point);
  return p;
}

}  // namespace ffriga
