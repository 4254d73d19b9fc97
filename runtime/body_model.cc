#include "runtime/body_model.h"

#include "common/error.h"

namespace ffriga {

BodyModel::BodyModel(std::string name, std::shared_ptr<const FlexibleBodySid> sid)
    : name_(std::move(name)), sid_(std::move(sid)) {
  const FlexibleBodySid& s = *sid_;
  const int nq = s.nq();
  auto shape = [&](const Eigen::MatrixXd& M, int r, int c, const char* what) {
    if (M.rows() != r || M.cols() != c) {
      throw InputError(Str() << "body '" << name_ << "': SID matrix " << what << " is " << M.rows()
                             << "x" << M.cols() << ", expected " << r << "x" << c);
    }
  };
  shape(s.Me, nq, nq, "Me");
  shape(s.Ke, nq, nq, "Ke");
  shape(s.De, nq, nq, "De");
  // Ct: nq x 3 (sid.h); axisymmetric SIDs may also store only the meridian columns (nq x 2).
  if (!(s.space_dim == 2 && s.Ct.rows() == nq && s.Ct.cols() == 2)) shape(s.Ct, nq, 3, "Ct");
  shape(s.Phi, s.control_points.rows() * s.space_dim, nq, "Phi");
  if (!(s.mass > 0.0)) throw InputError(Str() << "body '" << name_ << "': mass " << s.mass);
  De_ = s.De;
  if (nq > 0) {
    Me_llt_.compute(s.Me);
    if (Me_llt_.info() != Eigen::Success) {
      throw InputError(Str() << "body '" << name_ << "': Me is not positive definite");
    }
  }
}

double BodyModel::elasticEnergy(const double* sp) const {
  const Eigen::Map<const Eigen::VectorXd> q(sp + numRigidPositions(), nq());
  return 0.5 * q.dot(sid_->Ke * q);
}

}  // namespace ffriga
