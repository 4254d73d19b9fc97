#include "runtime/bodies/body_marker.h"

#include <algorithm>

#include "common/base/error.h"

namespace ffriga {

BodyMarker markerFromSid(const FlexibleBodySid& sid, const Marker& m, int nq) {
  const int d = sid.space_dim;
  FFRIGA_CHECK(d == 2 || d == 3, "markerFromSid: SID space_dim " << d);
  BodyMarker b;
  b.name = m.name;
  b.x0.head(d) = m.position.head(d);
  b.Phi = Eigen::MatrixXd::Zero(3, nq);
  for (std::size_t j = 0; j < m.functions.size() && nq > 0; ++j)
    b.Phi.topRows(d) += m.values(static_cast<int>(j)) * sid.Phi.middleRows(d * m.functions[j], d);
  b.rotation_modes = nq == 0 || m.Psi.rows() == 3;
  b.Psi = b.rotation_modes && nq > 0 ? m.Psi : Eigen::MatrixXd::Zero(3, nq);
  return b;
}

namespace {

// The coordinates of `qs` with the largest shares share(i) until the rest sum to at most
// kJointOmittedFlexibility of the total over all coordinates (appended to `held`).
void largestShares(const Eigen::VectorXd& share, const std::vector<int>& qs,
                   std::vector<int>& held) {
  const double total = share.sum();
  if (!(total > 0.0)) return;
  std::vector<int> order(qs);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return share(a) > share(b); });
  double left = 0.0;
  for (const int i : order) left += share(i);
  for (const int i : order) {
    if (left <= kJointOmittedFlexibility * total) break;
    left -= share(i);
    if (std::find(held.begin(), held.end(), i) == held.end()) held.push_back(i);
  }
}

}  // namespace

std::vector<int> jointHeldCoordinates(const BodyMarker& marker, const Eigen::VectorXd& k,
                                      const std::vector<int>& qs, bool rotations) {
  std::vector<int> held;
  if (qs.empty() || marker.Phi.cols() != k.size()) return held;
  Eigen::VectorXd translation = Eigen::VectorXd::Zero(k.size());
  Eigen::VectorXd rotation = Eigen::VectorXd::Zero(k.size());
  for (int i = 0; i < k.size(); ++i) {
    if (!(k(i) > 0.0)) continue;
    translation(i) = marker.Phi.col(i).squaredNorm() / k(i);
    if (rotations && marker.Psi.cols() == k.size())
      rotation(i) = marker.Psi.col(i).squaredNorm() / k(i);
  }
  largestShares(translation, qs, held);
  if (rotations) largestShares(rotation, qs, held);
  std::sort(held.begin(), held.end());
  return held;
}

void detachQuasiStatic(MarkerEnd& end, const std::vector<int>& index) {
  if (index.empty()) return;
  BodyMarker& m = end.marker;
  end.quasi_static_Phi = Eigen::MatrixXd::Zero(3, m.Phi.cols());
  for (const int i : index) {
    end.quasi_static_Phi.col(i) = m.Phi.col(i);
    m.Phi.col(i).setZero();
    if (m.Psi.cols() > i) m.Psi.col(i).setZero();
  }
}

BodyMarker fixedMarker(const std::string& name, const Eigen::Vector3d& x0) {
  BodyMarker b;
  b.name = name;
  b.x0 = x0;
  b.Phi.resize(3, 0);
  b.Psi.resize(3, 0);
  return b;
}

}  // namespace ffriga
