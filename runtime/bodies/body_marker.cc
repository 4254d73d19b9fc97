#include "runtime/bodies/body_marker.h"

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

BodyMarker fixedMarker(const std::string& name, const Eigen::Vector3d& x0) {
  BodyMarker b;
  b.name = name;
  b.x0 = x0;
  b.Phi.resize(3, 0);
  b.Psi.resize(3, 0);
  return b;
}

}  // namespace ffriga
