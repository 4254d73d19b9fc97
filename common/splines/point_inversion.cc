#include "common/splines/point_inversion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace ffriga {

namespace {

// Grid coordinates of one direction: `samples` uniform values plus every knot.
std::vector<double> gridValues(const KnotVector& kv, int samples) {
  const double lo = kv.front(), hi = kv.back();
  std::vector<double> v;
  for (int i = 0; i <= samples; ++i) v.push_back(lo + (hi - lo) * i / samples);
  for (int i = 0; i < kv.size(); ++i) v.push_back(kv[i]);
  for (int i = 0; i + 1 < kv.size(); ++i)
    if (kv[i + 1] > kv[i]) v.push_back(0.5 * (kv[i] + kv[i + 1]));
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// The `count` grid samples nearest to x, nearest first (ties in the order of the grid).
// Several are kept because a closed direction (a sphere's angle, zeta = 0 and 1 the same
// seam) has each seam point twice, and the clamped iteration cannot cross the seam: a point
// just below zeta = 1 whose nearest sample is the seam's copy at zeta = 0 is found from the
// copy at zeta = 1.
std::vector<std::array<double, 3>> nearestSamples(const NurbsPatch& patch, const Eigen::VectorXd& x,
                                                  int samples, std::size_t count) {
  const int d = patch.paramDim();
  std::array<std::vector<double>, 3> grid;
  for (int a = 0; a < d; ++a) grid[a] = gridValues(patch.knots(a), samples);
  std::array<std::size_t, 3> n{1, 1, 1};
  for (int a = 0; a < d; ++a) n[a] = grid[a].size();
  auto at = [&](std::size_t k) {
    std::array<double, 3> xi{0, 0, 0};
    for (int a = 0; a < d; ++a) {
      xi[a] = grid[a][k % n[a]];
      k /= n[a];
    }
    return xi;
  };
  std::vector<std::pair<double, std::size_t>> dist(n[0] * n[1] * n[2]);
  for (std::size_t k = 0; k < dist.size(); ++k)
    dist[k] = {(patch.evaluate(at(k).data(), 0).x - x).norm(), k};
  count = std::min(count, dist.size());
  std::partial_sort(dist.begin(), dist.begin() + count, dist.end());
  std::vector<std::array<double, 3>> starts;
  for (std::size_t i = 0; i < count; ++i) starts.push_back(at(dist[i].second));
  return starts;
}

// Clamped Gauss-Newton / Levenberg-Marquardt from `start`.
InversionResult iterate(const NurbsPatch& patch, const Eigen::VectorXd& x, double tolerance,
                        const std::array<double, 3>& start) {
  const int d = patch.paramDim();
  InversionResult r;
  double xi[3] = {start[0], start[1], start[2]};
  double mu = 0.0;
  for (int it = 0; it < 100; ++it) {
    const PatchPoint p = patch.evaluate(xi, 1);
    const Eigen::VectorXd res = x - p.x;
    r.distance = res.norm();
    if (r.distance <= tolerance) break;
    const Eigen::MatrixXd JtJ = p.dx.transpose() * p.dx;
    const double scale = std::max(JtJ.diagonal().maxCoeff(), 1e-300);
    const Eigen::VectorXd step =
        (JtJ + mu * scale * Eigen::MatrixXd::Identity(d, d)).ldlt().solve(p.dx.transpose() * res);
    double trial[3] = {0, 0, 0};
    for (int a = 0; a < d; ++a) {
      const KnotVector& kv = patch.knots(a);
      trial[a] = std::clamp(xi[a] + step(a), kv.front(), kv.back());
    }
    const double dist = (patch.evaluate(trial, 0).x - x).norm();
    if (dist < r.distance) {
      for (int a = 0; a < d; ++a) xi[a] = trial[a];
      mu = mu * 0.1;
    } else {
      mu = mu == 0.0 ? 1e-6 : mu * 10.0;
      if (mu > 1e6) break;
    }
  }
  r.distance = (x - patch.evaluate(xi, 0).x).norm();
  for (int a = 0; a < d; ++a) r.xi[a] = xi[a];
  r.found = r.distance <= tolerance;
  return r;
}

}  // namespace

InversionResult invertPoint(const NurbsPatch& patch, const Eigen::VectorXd& x, double tolerance,
                            int samples) {
  // The nearest sample first; the next ones only if it does not converge (so that points
  // found from it keep their bits).
  constexpr std::size_t kStarts = 8;
  InversionResult best;
  best.distance = std::numeric_limits<double>::infinity();
  for (const std::array<double, 3>& start : nearestSamples(patch, x, samples, kStarts)) {
    const InversionResult r = iterate(patch, x, tolerance, start);
    if (r.distance < best.distance) best = r;
    if (best.found) break;
  }
  return best;
}

}  // namespace ffriga
