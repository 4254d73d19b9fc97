#include "runtime/contact/coulomb_friction.h"

#include <algorithm>
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

// A term of the same bodies as the point's normal term, of the given kind and k.
StiffnessTerm termBeside(const StiffnessTerm& normal, StiffnessTerm::Kind kind, double k) {
  StiffnessTerm t;
  t.body_c = normal.body_c;
  t.body_t = normal.body_t;
  t.kind = kind;
  t.k = k;
  return t;
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
    StiffnessTerm t = termBeside(normal, kind, k);
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

AnchoredFriction anchoredFriction(const FrictionLaw& law, double normal_force, double k_t,
                                  const Eigen::VectorXd& r, const Eigen::VectorXd& n,
                                  FrictionBranch branch, const Eigen::VectorXd* e1) {
  AnchoredFriction f;
  const double limit = law.coefficient * normal_force / k_t;  // d_lim (m)
  f.rate = Eigen::VectorXd::Zero(r.size());
  const bool follow = branch == FrictionBranch::kFollow;
  const Eigen::VectorXd d = r - r.dot(n) * n;
  f.d = follow ? limit : d.norm();
  f.e1 = follow ? *e1 : f.d > 0.0 ? Eigen::VectorXd(d / f.d) : anyTangent(n);
  if (n.size() == 3) f.e2 = Eigen::Vector3d(n).cross(Eigen::Vector3d(f.e1));
  if (follow) {
    f.sticking = false;
    f.following = true;
    f.force = (-law.coefficient * normal_force) * f.e1;
    f.energy = 0.5 * k_t * limit * limit;
    return f;
  }
  if (branch == FrictionBranch::kStick || (branch == FrictionBranch::kDecide && f.d <= limit)) {
    f.force = -k_t * d;
    f.energy = 0.5 * k_t * f.d * f.d;
    return f;
  }
  f.sticking = false;
  f.force = (-law.coefficient * normal_force) * f.e1;
  f.rate = ((f.d - limit) / law.relaxation_time) * f.e1;
  f.power = std::max(0.0, law.coefficient * normal_force * (f.d - limit) / law.relaxation_time);
  f.energy = 0.5 * k_t * limit * limit;
  return f;
}

void appendAnchoredTerms(
    const FrictionLaw& law, const AnchoredFriction& f, double normal_force, double k_t, int anchor,
    const StiffnessTerm& normal,
    const std::function<void(const Eigen::VectorXd& e, StiffnessTerm& t)>& gradients,
    std::vector<StiffnessTerm>& terms) {
  const int dim = static_cast<int>(f.e1.size());
  // One term along the tangent e: stiffness k on the bodies, the anchor's rows aU, its
  // columns -e (the term's variable is e . (x - z)).
  const auto add = [&](StiffnessTerm::Kind kind, double k, const Eigen::VectorXd& e,
                       const Eigen::VectorXd& aU) {
    StiffnessTerm t = termBeside(normal, kind, k);
    gradients(e, t);
    t.anchor = anchor;
    t.aU = aU;
    t.aV = -e;
    terms.push_back(std::move(t));
  };
  const Eigen::VectorXd none = Eigen::VectorXd::Zero(dim);
  const double eta = law.relaxation_time, mu = law.coefficient;
  // Through the normal force, f_t = -mu f_n e1: d f_n / d s_p = -k bp_n^T (the normal term's
  // k and bp).
  const auto load = [&]() {
    StiffnessTerm t = termBeside(normal, StiffnessTerm::Kind::kFrictionLoad, normal.k);
    gradients(-mu * f.e1, t);
    t.bpC = normal.bpC;
    t.bpT = normal.bpT;
    return t;
  };
  if (f.following) {  // the normal force's share only (the anchor moves with the point)
    terms.push_back(load());
    return;
  }
  if (f.sticking) {
    add(StiffnessTerm::Kind::kNormal, k_t, f.e1, none);
    if (dim == 3) add(StiffnessTerm::Kind::kNormal, k_t, f.e2, none);
    return;
  }
  const double beta = mu * normal_force / (k_t * f.d);
  add(StiffnessTerm::Kind::kNormal, 0.0, f.e1, f.e1 / eta);
  if (dim == 3)
    add(StiffnessTerm::Kind::kNormal, mu * normal_force / f.d, f.e2, (1.0 - beta) / eta * f.e2);
  StiffnessTerm t = load();
  t.anchor = anchor;
  t.aU = (normal.k * mu / (k_t * eta)) * f.e1;  // -k d zdot / d f_n
  t.aV = none;
  terms.push_back(std::move(t));
}

}  // namespace ffriga
