#include "runtime/bodies/body_model.h"

#include "common/base/error.h"

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
  checkDiagonal();
}

void BodyModel::setDamping(const Eigen::MatrixXd& De) {
  De_ = De;
  checkDiagonal();
}

void BodyModel::setQuasiStatic(double cutoff_hz) {
  if (!diagonal_) {
    throw InputError(Str() << "body '" << name_ << "': quasi-static modes need a SID with Me = E "
                           << "and diagonal Ke (igaprep's modal form, Eq. 13)");
  }
  qs_ = QuasiStaticModes::select(k_, sid_->Phi, cutoff_hz);
}

void BodyModel::checkDiagonal() {
  // Off-diagonal parts below 1e-8 of the largest diagonal entry only perturb the Newton
  // matrix, which needs to be approximate only (modified Newton iteration); the right-hand
  // side takes the diagonal shortcut only when the off-diagonal parts are exactly zero.
  const FlexibleBodySid& s = *sid_;
  const int nq = s.nq();
  auto offDiagonal = [](const Eigen::MatrixXd& A) {
    return (A - Eigen::MatrixXd(A.diagonal().asDiagonal())).cwiseAbs().maxCoeff();
  };
  auto scale = [](const Eigen::MatrixXd& A) { return A.diagonal().cwiseAbs().maxCoeff(); };
  const double offK = nq ? offDiagonal(s.Ke) : 0.0, offD = nq ? offDiagonal(De_) : 0.0;
  const double offM = nq ? (s.Me - Eigen::MatrixXd::Identity(nq, nq)).cwiseAbs().maxCoeff() : 0.0;
  diagonal_ = nq == 0 || (offK <= 1e-8 * scale(s.Ke) && offD <= 1e-8 * scale(De_) && offM <= 1e-8);
  exactly_diagonal_ = nq == 0 || (offK == 0.0 && offD == 0.0 && offM == 0.0);
  k_ = s.Ke.diagonal();
  c_ = De_.diagonal();
}

double BodyModel::elasticEnergy(const double* sp) const {
  const Eigen::Map<const Eigen::VectorXd> q(sp + numRigidPositions(), nq());
  return 0.5 * q.dot(sid_->Ke * q);
}

}  // namespace ffriga
