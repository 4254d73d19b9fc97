#include "preproc/assembly/dof_map.h"

#include <algorithm>
#include <numeric>

namespace ffriga {

DofMap::DofMap(const SplineSpace& space, bool axisymmetric, double tolerance)
    : DofMap(space, axisymmetric,
             coincidentPoints(space.controlPoints(),
                              tolerance >= 0.0 ? tolerance : defaultTolerance(space)),
             tolerance) {}

double DofMap::defaultTolerance(const SplineSpace& space) {
  const Eigen::MatrixXd& P = space.controlPoints();
  return 1e-12 * (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
}

DofMap::DofMap(const SplineSpace& space, bool axisymmetric,
               const std::vector<std::vector<int>>& tied, double tolerance) {
  const Eigen::MatrixXd& P = space.controlPoints();
  const int n = static_cast<int>(P.rows());
  components_ = static_cast<int>(P.cols());
  if (tolerance < 0.0) tolerance = defaultTolerance(space);
  node_.resize(n);
  std::iota(node_.begin(), node_.end(), 0);
  for (const auto& g : tied) {
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
