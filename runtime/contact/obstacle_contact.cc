#include "runtime/contact/obstacle_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/base/error.h"

namespace ffriga {

ObstacleContact::ObstacleContact(std::string name, int a, const BodyModel& A, int surface,
                                 RigidObstacle obstacle, const ContactOptions& options)
    : SurfaceContact(std::move(name), a, -1, options), obstacle_(std::move(obstacle)) {
  FFRIGA_CHECK(options_.penalty > 0.0, "penalty factor " << options_.penalty);
  dim_ = A.spaceDim();
  side_.setup(A, surface);
  obstacle_name_ = obstacle_.name();
  size_ = side_.size();
  margin_ = options_.search_margin >= 0.0 ? options_.search_margin : 0.1 * size_;
  pressure_.addRole(side_.weight);
}

Eigen::Vector3d ObstacleContact::world(const BodyPose& pa, const Eigen::VectorXd& xb) const {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  x.head(dim_) = pa.origin + pa.A * xb;
  return x;
}

void ObstacleContact::worldBox(const BodyPose& pa, const Eigen::VectorXd& u, Eigen::Vector3d& lo,
                               Eigen::Vector3d& hi) const {
  lo.setConstant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (std::size_t i = 0; i < side_.cps.size(); ++i) {
    const Eigen::VectorXd xb = side_.P0.row(side_.cps[i]).transpose() + u.segment(i * dim_, dim_);
    const Eigen::Vector3d x = world(pa, xb);
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  if (dim_ == 2) lo(2) = hi(2) = 0.0;
}

void ObstacleContact::addForces(const ForceContext& at, std::vector<Eigen::VectorXd>& h,
                                const ForceStates& states) {
  const int a = bodyA();
  evaluate(at.body(a), at.pose(a), h[a].data(),
           states.contacts ? &(*states.contacts)[slot()] : nullptr, at.velocities(a));
}

double ObstacleContact::boxGap(const ForceContext& at) const {
  const BodyPose& pa = at.pose(bodyA());
  Eigen::Vector3d lo, hi;
  worldBox(pa, side_.displacements(pa.q), lo, hi);  // the surface is inside its points' hull
  return obstacle_.boxGap(lo, hi);
}

void ObstacleContact::addFriction(const BodyModel& A, const BodyPose& pa, const double* sv,
                                  const Eigen::VectorXd& udot, double fn, Eigen::VectorXd& f,
                                  ContactState& s, ActivePoint& point) const {
  const Eigen::VectorXd v =
      A.pointVelocity(pa, sv, point.xb, side_.pointDisplacement(point.i, udot));
  point.friction = coulombFriction(options_.friction, fn, v, point.n);
  f += point.friction.force;
  s.tangential_force.head(dim_) += point.friction.force;
  s.friction_power += point.friction.power;
  ++(point.friction.sticking ? s.sticking_points : s.slipping_points);
}

void ObstacleContact::evaluate(const BodyModel& A, const BodyPose& pa, double* hA,
                               ContactState* state, const double* sv) {
  terms_.clear();
  active_.clear();
  terms_formed_ = false;
  body_ = &A;
  pose_ = pa;
  // The surface's control points' displacements, once: for the box and for the points.
  const Eigen::VectorXd u = side_.displacements(pa.q);
  Eigen::Vector3d lo, hi;
  worldBox(pa, u, lo, hi);
  if (obstacle_.boxGap(lo, hi) > margin_) {  // apart: no work
    if (state) pressure_.clear();
    return;
  }
  const int nc = side_.numPoints();
  searches_ += nc;
  const bool friction = options_.friction.active();
  FFRIGA_CHECK(!friction || sv != nullptr, "friction needs the body's velocities");
  const Eigen::VectorXd udot =  // the surface's elastic velocities (friction)
      friction && A.nq() > 0 ? side_.displacements(Eigen::Map<const Eigen::VectorXd>(
                                   sv + A.numRigidVelocities(), A.nq()))
                             : Eigen::VectorXd();
  Eigen::VectorXd fbSum = Eigen::VectorXd::Zero(A.nq());
  ContactState s;
  for (int i = 0; i < nc; ++i) {  // in point order: the same sums on any thread count
    const Eigen::VectorXd xb = side_.bodyPoint(i, u);
    const Eigen::Vector3d x = world(pa, xb);
    const ObstaclePoint p = obstacle_.nearest(x);
    if (!p.covered || p.gap >= 0.0) {
      if (state) pressure_.set(0, i, x);
      continue;
    }
    const double k = options_.penalty * side_.weight(i);
    const Eigen::VectorXd n = p.normal.head(dim_);
    if (state) pressure_.set(0, i, x, -options_.penalty * p.gap, p.normal);
    Eigen::VectorXd f = (-k * p.gap) * n;
    active_.push_back({i, k, xb, n, {}});
    if (friction) {
      addFriction(A, pa, sv, udot, -k * p.gap, f, s, active_.back());
      if (state) pressure_.setTraction(0, i, active_.back().friction.force);
    }
    A.addRigidPointForce(pa, xb, f, hA);
    if (A.nq() > 0) fbSum += side_.PhiCt.middleCols(i * dim_, dim_) * (pa.A.transpose() * f);
    s.force.head(dim_) += f;
    s.max_penetration = std::max(s.max_penetration, -p.gap);
    ++s.active_points;
    s.energy += 0.5 * k * p.gap * p.gap;
  }
  if (A.nq() > 0) Eigen::Map<Eigen::VectorXd>(hA + A.numRigidVelocities(), A.nq()) += fbSum;
  if (state) {
    if (dim_ == 2) s.force = Eigen::Vector3d(0.0, s.force(1), 0.0);
    if (dim_ == 2) s.tangential_force = Eigen::Vector3d(0.0, s.tangential_force(1), 0.0);
    s.normal_force =
        options_.friction.active() ? (s.force - s.tangential_force).norm() : s.force.norm();
    *state = s;
  }
}

const std::vector<StiffnessTerm>& ObstacleContact::stiffnessTerms() const {
  if (terms_formed_) return terms_;
  terms_.clear();
  terms_.reserve(active_.size());
  for (const ActivePoint& a : active_) {
    StiffnessTerm term;
    term.body_c = bodyA();
    term.body_t = -1;
    term.k = a.k;
    const Eigen::MatrixXd Phi = side_.PhiCt.middleCols(a.i * dim_, dim_).transpose();
    body_->pointGradients(pose_, a.xb, Phi, a.n, term.bvC, term.bpC);
    if (options_.friction.active()) {  // G e of the body's point (coulomb_friction.h)
      appendFrictionTerms(
          a.friction, term,
          [&](const Eigen::VectorXd& e, StiffnessTerm& t) {
            Eigen::VectorXd unused;
            body_->pointGradients(pose_, a.xb, Phi, e, t.bvC, unused);
          },
          terms_);
    }
    terms_.push_back(std::move(term));
  }
  terms_formed_ = true;
  return terms_;
}

Penetration ObstacleContact::deepestPenetration(const ForceContext& at) const {
  const BodyPose& pa = at.pose(bodyA());
  const Eigen::VectorXd u = at.body(bodyA()).nq() > 0 ? side_.displacements(pa.q)
                                                       : Eigen::VectorXd();
  Penetration deepest;
  for (int i = 0; i < side_.numPoints(); ++i) {
    const Eigen::Vector3d x = world(pa, side_.bodyPoint(i, u));
    const ObstaclePoint p = obstacle_.nearest(x);
    if (!p.covered || -p.gap <= deepest.depth) continue;
    deepest.depth = -p.gap;
    deepest.contact_body = bodyA();
    deepest.point = x;
  }
  return deepest;
}

void ObstacleContact::surfaceCentre(const BodyPose& pa, Eigen::Vector3d& x,
                                    Eigen::Vector3d& n) const {
  const SurfacePoint sp = side_.centre(side_.P0);
  x = world(pa, sp.x);
  n.setZero();
  n.head(dim_) = pa.A * side_.surface.normal(sp.dx);  // the body's outward normal, turned
}

}  // namespace ffriga
