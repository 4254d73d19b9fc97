#include "common/splines/point_inversion.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

}  // namespace

InversionResult invertPoint(const NurbsPatch& patch, const Eigen::VectorXd& x, double tolerance,
                            int samples) {
  const int d = patch.paramDim();
  InversionResult r;
  // Start: nearest grid sample.
  std::array<std::vector<double>, 3> grid;
  for (int a = 0; a < d; ++a) grid[a] = gridValues(patch.knots(a), samples);
  double best = std::numeric_limits<double>::infinity();
  std::array<std::size_t, 3> n{1, 1, 1};
  for (int a = 0; a < d; ++a) n[a] = grid[a].size();
  double xi[3] = {0, 0, 0};
  for (std::size_t k = 0; k < n[0] * n[1] * n[2]; ++k) {
    std::size_t rest = k;
    for (int a = 0; a < d; ++a) {
      xi[a] = grid[a][rest % n[a]];
      rest /= n[a];
    }
    const double dist = (patch.evaluate(xi, 0).x - x).norm();
    if (dist < best) {
      best = dist;
      for (int a = 0; a < d; ++a) r.xi[a] = xi[a];
    }
  }
  // Clamped Gauss-Newton / Levenberg-Marquardt.
  for (int a = 0; a < d; ++a) xi[a] = r.xi[a];
  double mu = 0.0;
  for (int it = 0; it < 100; ++it) {
    const PatchPoint p = patch.evaluate(xi, 1);
    const Eigen::VectorXd res = x - p.x;
    r.distance = res.norm();
    for (int a = 0; a < d; ++a) r.xi[a] = xi[a];
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
  const PatchPoint p = patch.evaluate(xi, 0);
  r.distance = (x - p.x).norm();
  for (int a = 0; a < d; ++a) r.xi[a] = xi[a];
  r.found = r.distance <= tolerance;
  return r;
}

}  // namespace ffriga
