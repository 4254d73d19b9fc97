#include "preproc/dof_map.h"

#include <algorithm>
#include <numeric>

namespace ffriga {

std::vector<std::vector<int>> coincidentPoints(const Eigen::MatrixXd& P, double tol) {
  const int n = static_cast<int>(P.rows());
  // Sort by the first coordinate, then compare neighbours within tol (union-find).
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return P(a, 0) < P(b, 0); });
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n && P(order[b], 0) - P(order[a], 0) <= tol; ++b) {
      if ((P.row(order[a]) - P.row(order[b])).lpNorm<Eigen::Infinity>() <= tol) {
        const int ra = find(order[a]);
        const int rb = find(order[b]);
        parent[std::max(ra, rb)] = std::min(ra, rb);
      }
    }
  }
  std::vector<std::vector<int>> groups(n);
  for (int k = 0; k < n; ++k) groups[find(k)].push_back(k);
  std::vector<std::vector<int>> result;
  for (auto& g : groups) {
    if (g.size() >= 2) result.push_back(std::move(g));
  }
  return result;
}

DofMap::DofMap(const SplineSpace& space, bool axisymmetric, double tolerance) {
  const Eigen::MatrixXd& P = space.controlPoints();
  const int n = static_cast<int>(P.rows());
  components_ = static_cast<int>(P.cols());
  if (tolerance < 0.0) {
    tolerance = 1e-12 * (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
  }
  node_.resize(n);
  std::iota(node_.begin(), node_.end(), 0);
  for (const auto& g : coincidentPoints(P, tolerance)) {
    for (int k : g) node_[k] = g.front();
    num_tied_ += static_cast<int>(g.size()) - 1;
  }
  dof_.assign(static_cast<std::size_t>(n) * components_, -1);
  for (int k = 0; k < n; ++k) {
    if (node_[k] != k) continue;
    for (int c = 0; c < components_; ++c) {
      if (axisymmetric && c == 0 && P(k, 0) <= tolerance) {
        ++num_fixed_;
        continue;
      }
      dof_[k * components_ + c] = num_dofs_++;
    }
  }
  for (int k = 0; k < n; ++k) {
    for (int c = 0; c < components_; ++c)
      dof_[k * components_ + c] = dof_[node_[k] * components_ + c];
  }
}

Eigen::MatrixXd DofMap::expand(const Eigen::MatrixXd& x) const {
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(dof_.size()), x.cols());
  for (std::size_t r = 0; r < dof_.size(); ++r) {
    if (dof_[r] >= 0) u.row(r) = x.row(dof_[r]);
  }
  return u;
}

Eigen::MatrixXd DofMap::restrict(const Eigen::MatrixXd& u) const {
  Eigen::MatrixXd x(num_dofs_, u.cols());
  for (std::size_t r = 0; r < dof_.size(); ++r) {
    if (dof_[r] >= 0) x.row(dof_[r]) = u.row(r);
  }
  return x;
}

}  // namespace ffriga
