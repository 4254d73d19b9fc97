#include "runtime/bodies/quasi_static_modes.h"

#include <algorithm>
#include <cmath>

#include "common/base/error.h"

namespace ffriga {

QuasiStaticModes QuasiStaticModes::select(const Eigen::VectorXd& k, const Eigen::MatrixXd& Phi,
                                          double cutoff_hz) {
  FFRIGA_CHECK(cutoff_hz > 0.0 && std::isfinite(cutoff_hz), "quasi-static cutoff " << cutoff_hz);
  QuasiStaticModes m;
  m.cutoff_hz = cutoff_hz;
  const double omegaCut = 2.0 * M_PI * cutoff_hz;
  m.tau = kRelaxation / omegaCut;
  std::vector<double> stiff;
  for (int i = 0; i < k.size(); ++i) {
    if (k(i) >= omegaCut * omegaCut) {
      m.index.push_back(i);
      stiff.push_back(k(i));
    }
  }
  m.stiffness = Eigen::Map<const Eigen::VectorXd>(stiff.data(), static_cast<Eigen::Index>(stiff.size()));
  m.reach.resize(m.size());
  for (int s = 0; s < m.size(); ++s) m.reach(s) = Phi.col(m.index[s]).cwiseAbs().maxCoeff();
  return m;
}

QuasiStaticModes QuasiStaticModes::without(const std::vector<int>& dynamic) const {
  QuasiStaticModes m;
  m.cutoff_hz = cutoff_hz;
  m.tau = tau;
  m.held_by_joints = held_by_joints;
  std::vector<int> keep;
  for (int s = 0; s < size(); ++s)
    if (std::find(dynamic.begin(), dynamic.end(), index[s]) == dynamic.end()) keep.push_back(s);
  m.stiffness.resize(static_cast<Eigen::Index>(keep.size()));
  m.reach.resize(static_cast<Eigen::Index>(keep.size()));
  for (std::size_t j = 0; j < keep.size(); ++j) {
    m.index.push_back(index[keep[j]]);
    m.stiffness(j) = stiffness(keep[j]);
    m.reach(j) = reach(keep[j]);
  }
  m.held_by_joints += size() - m.size();
  return m;
}

void QuasiStaticModes::apply(int nrp, int nrv, double* spdot, double* accel) const {
  for (int s = 0; s < size(); ++s) {
    const int i = index[s];
    spdot[nrp + i] = accel[nrv + i] / (stiffness(s) * tau);
    accel[nrv + i] = 0.0;
  }
}

}  // namespace ffriga
