#include "runtime/bodies/rigid_body.h"

#include <cmath>

#include "common/base/error.h"

namespace ffriga {

namespace {

// Empty elastic part of a SID whose rigid invariants are set.
void clearElasticPart(FlexibleBodySid& s, int ncp) {
  s.frequencies_hz.resize(0);
  s.damping_ratio.resize(0);
  s.Me.resize(0, 0);
  s.Ke.resize(0, 0);
  s.De.resize(0, 0);
  s.Ct.resize(0, 3);
  s.Cr0.resize(0, 3);
  s.Cr1.clear();
  s.J1.clear();
  s.Oe.resize(0, 6);
  s.Phi.resize(ncp * s.space_dim, 0);
}

}  // namespace

FlexibleBodySid rigidBodySid(const std::string& name, const RigidBodyProperties& p) {
  if (!(p.mass > 0.0) || !std::isfinite(p.mass))
    throw InputError(Str() << "expected a mass > 0 kg, found " << p.mass);
  const Eigen::Matrix3d& I = p.inertia;
  const double scale = I.cwiseAbs().maxCoeff();
  if (!I.allFinite() || (I - I.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale)
    throw InputError("expected a symmetric inertia tensor (kg m^2)");
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
  const Eigen::Vector3d l = eig.eigenvalues();
  if (!(l(0) > 0.0))
    throw InputError(Str() << "expected a positive definite inertia tensor, found principal "
                           << "moments " << l(0) << ", " << l(1) << ", " << l(2) << " kg m^2");
  // Principal moments of a real mass distribution: I3 <= I1 + I2 (l ascending).
  if (l(2) > (l(0) + l(1)) * (1.0 + 1e-12))
    throw InputError(Str() << "principal moments " << l(0) << ", " << l(1) << ", " << l(2)
                           << " kg m^2 violate the triangle inequality I3 <= I1 + I2 of any "
                           << "mass distribution");
  FlexibleBodySid s;
  s.name = name;
  s.model = ModelKind::kRigid;
  s.space_dim = 3;
  s.frame = FrameKind::kCentreOfMassGiven;
  s.reduction = ReductionMethod::kRigid;
  s.created_by = "scene";
  s.mass = p.mass;
  const Eigen::Vector3d& c = p.centre_of_mass;
  s.first_moment = p.mass * c;
  s.inertia = I + p.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  s.control_points.resize(0, 3);
  s.weights.resize(0);
  clearElasticPart(s, 0);
  return s;
}

FlexibleBodySid frozenSid(const FlexibleBodySid& sid) {
  FlexibleBodySid s = sid;
  clearElasticPart(s, static_cast<int>(sid.control_points.rows()));
  s.reduction = ReductionMethod::kFrozen;
  return s;
}

}  // namespace ffriga
