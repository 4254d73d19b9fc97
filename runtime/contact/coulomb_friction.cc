#include "runtime/contact/coulomb_friction.h"

#include <cmath>

namespace ffriga {

namespace {

// A unit vector orthogonal to the unit n (d = 2: n turned by 90 degrees; d = 3: along the
// axis n is least aligned with, made orthogonal).
Eigen::VectorXd anyTangent(const Eigen::VectorXd& n) {
  Eigen::VectorXd t = Eigen::VectorXd::Zero(n.size());
  if (n.size() == 2) {
    t << -n(1), n(0);
    return t;
  }
  Eigen::Index k = 0;
  n.cwiseAbs().minCoeff(&k);
  t(k) = 1.0;
  t -= t.dot(n) * n;
  return t.normalized();
}

}  // namespace

PointFriction coulombFriction(const FrictionLaw& law, double normal_force, const Eigen::VectorXd& v,
                              const Eigen::VectorXd& n) {
  PointFriction p;
  const double mu = law.coefficient, eps = law.slip_velocity;
  const Eigen::VectorXd vt = v - v.dot(n) * n;
  const double speed = vt.norm();
  const double s = std::sqrt(speed * speed + eps * eps);
  p.load = (-mu / s) * vt;
  p.force = normal_force * p.load;
  p.power = mu * normal_force * speed * speed / s;
  p.sticking = speed < eps;
  p.e1 = speed > 0.0 ? Eigen::VectorXd(vt / speed) : anyTangent(n);
  p.c1 = mu * normal_force * eps * eps / (s * s * s);
  if (n.size() == 3) {
    p.e2 = Eigen::Vector3d(n).cross(Eigen::Vector3d(p.e1));
    p.c2 = mu * normal_force / s;
  }
  return p;
}

void appendFrictionTerms(
    const PointFriction& f, const StiffnessTerm& normal,
    const std::function<void(const Eigen::VectorXd& e, StiffnessTerm& t)>& gradients,
    std::vector<StiffnessTerm>& terms) {
  const auto add = [&](StiffnessTerm::Kind kind, double k, const Eigen::VectorXd& e) {
    StiffnessTerm t;
    t.body_c = normal.body_c;
    t.body_t = normal.body_t;
    t.kind = kind;
    t.k = k;
    gradients(e, t);
    t.bpC = t.onVelocities() ? t.bvC : normal.bpC;
    t.bpT = t.onVelocities() ? t.bvT : normal.bpT;
    terms.push_back(std::move(t));
  };
  if (!negligibleDamping(f, f.c1)) add(StiffnessTerm::Kind::kFrictionDamping, f.c1, f.e1);
  if (f.e2.size() > 0 && !negligibleDamping(f, f.c2))
    add(StiffnessTerm::Kind::kFrictionDamping, f.c2, f.e2);
  add(StiffnessTerm::Kind::kFrictionLoad, normal.k, f.load);
}

}  // namespace ffriga
