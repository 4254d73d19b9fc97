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
           states.contacts ? &(*states.contacts)[slot()] : nullptr, at.velocities(a),
           at.anchors(slot()));
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

int ObstacleContact::numAnchors() const {
  return anchored() ? side_.numPoints() * dim_ : 0;
}

void ObstacleContact::placeAnchors(const ForceContext& at, double* z, bool outOnly) const {
  const BodyPose& pa = at.pose(bodyA());
  const Eigen::VectorXd u =
      at.body(bodyA()).nq() > 0 ? side_.displacements(pa.q) : Eigen::VectorXd();
  for (int i = 0; i < side_.numPoints(); ++i) {
    const Eigen::Vector3d x = world(pa, side_.bodyPoint(i, u));
    if (outOnly) {
      const ObstaclePoint p = obstacle_.nearest(x);
      if (p.covered && p.gap < 0.0) continue;
    }
    for (int a = 0; a < dim_; ++a) z[i * dim_ + a] = x(a);  // (an Eigen block copy here
    // made GCC 12 warn of a 32-byte read from the 24-byte x)
  }
}

bool ObstacleContact::releaseExceeded() {
  bool any = false;
  for (HeldBranch& b : branches_) {
    if (b != HeldBranch::kStickExceeded) continue;
    b = HeldBranch::kSlip;  // its direction was kept when it exceeded
    any = true;
  }
  return any;
}

void ObstacleContact::settleAnchors(const ForceContext& at, double* z) const {
  if (!anchored()) return;
  const BodyPose& pa = at.pose(bodyA());
  const Eigen::VectorXd u =
      at.body(bodyA()).nq() > 0 ? side_.displacements(pa.q) : Eigen::VectorXd();
  for (std::size_t i = 0; i < branches_.size(); ++i) {
    if (branches_[i] != HeldBranch::kSlip) continue;
    const Eigen::Vector3d x = world(pa, side_.bodyPoint(static_cast<int>(i), u));
    const ObstaclePoint p = obstacle_.nearest(x);
    if (!p.covered || p.gap >= 0.0) continue;  // left the contact: followAnchors places it
    const Eigen::VectorXd n = p.normal.head(dim_);
    Eigen::Map<Eigen::VectorXd> zi(z + i * dim_, dim_);
    const Eigen::VectorXd r = x.head(dim_) - zi, d = r - r.dot(n) * n;
    const double limit = options_.friction.coefficient * (-p.gap);  // d_lim (c_t = c_p)
    // d = d_lim e1 with the held direction e1 (z's normal part kept): stick and slip agree
    // there, and the force is the one the iteration held, -mu f_n e1. Keeping a trail
    // beyond the limit instead (d = max(|d|, d_lim) e1) took 7,445 steps at 2 degrees
    // where this takes 1,873 (5,371 against 9,412 at 50).
    zi += d - limit * held_directions_.segment(i * dim_, dim_);
  }
}

void ObstacleContact::initialAnchors(const ForceContext& at, double* z) const {
  placeAnchors(at, z, false);
}

void ObstacleContact::followAnchors(const ForceContext& at, double* z) const {
  placeAnchors(at, z, true);
}

void ObstacleContact::addAnchoredFriction(const Eigen::Vector3d& x, const double* z, double fn,
                                          Eigen::VectorXd& f, ContactState& s, ActivePoint& point) {
  const Eigen::Map<const Eigen::VectorXd> zi(z + point.i * dim_, dim_);
  point.fn = fn;
  if (!(point.k > 0.0)) return;  // weight 0 (an axisymmetric body's axis point): no force
  FrictionBranch branch = FrictionBranch::kDecide;
  Eigen::VectorXd e1;
  HeldBranch* held = nullptr;
  if (hold_branches_) {
    if (branches_.empty()) {
      branches_.assign(side_.numPoints(), HeldBranch::kUnset);
      held_directions_.setZero(side_.numPoints() * dim_);
    }
    held = &branches_[point.i];
    if (*held == HeldBranch::kSlip) {
      branch = FrictionBranch::kFollow;
      e1 = held_directions_.segment(point.i * dim_, dim_);
    } else if (*held != HeldBranch::kUnset) {
      branch = FrictionBranch::kStick;
    }
  }
  point.anchored =
      anchoredFriction(options_.friction, fn, point.k, x.head(dim_) - zi, point.n, branch, &e1);
  if (held && *held == HeldBranch::kUnset)
    *held = point.anchored.sticking ? HeldBranch::kStick : HeldBranch::kSlip;
  if (held && (*held == HeldBranch::kStick || *held == HeldBranch::kStickExceeded))
    *held = point.anchored.d > options_.friction.coefficient * fn / point.k  // to be released
                ? HeldBranch::kStickExceeded
                : HeldBranch::kStick;
  if (held && *held != HeldBranch::kStick)  // the direction it slips (or will) along
    held_directions_.segment(point.i * dim_, dim_) = point.anchored.e1;
  const AnchoredFriction& a = point.anchored;
  f += a.force;
  s.tangential_force.head(dim_) += a.force;
  s.friction_power += a.power;
  s.energy += a.energy;
  ++(a.sticking ? s.sticking_points : s.slipping_points);
  anchor_rates_.segment(point.i * dim_, dim_) = a.rate;
}

void ObstacleContact::evaluate(const BodyModel& A, const BodyPose& pa, double* hA,
                               ContactState* state, const double* sv, const double* z) {
  terms_.clear();
  active_.clear();
  terms_formed_ = false;
  body_ = &A;
  pose_ = pa;
  // The surface's control points' displacements, once: for the box and for the points.
  const Eigen::VectorXd u = side_.displacements(pa.q);
  Eigen::Vector3d lo, hi;
  worldBox(pa, u, lo, hi);
  const bool withAnchors = anchored();
  FFRIGA_CHECK(!withAnchors || z != nullptr, "anchored friction needs the anchors");
  if (withAnchors) anchor_rates_.setZero(numAnchors());  // out of contact: at rest
  if (obstacle_.boxGap(lo, hi) > margin_) {  // apart: no work
    if (state) pressure_.clear();
    return;
  }
  const int nc = side_.numPoints();
  searches_ += nc;
  const bool friction = options_.friction.active() && !withAnchors;
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
    active_.push_back({i, k, xb, n, {}, {}, 0.0});
    if (friction) {
      addFriction(A, pa, sv, udot, -k * p.gap, f, s, active_.back());
      if (state) pressure_.setTraction(0, i, active_.back().friction.force);
    }
    if (withAnchors) {
      addAnchoredFriction(x, z, -k * p.gap, f, s, active_.back());
      if (state) pressure_.setTraction(0, i, active_.back().anchored.force);
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
    if (anchored()) {  // G e and G_p e of the body's point along the tangents
      if (a.k > 0.0)   // (weight 0: no force)
        appendAnchoredTerms(
            options_.friction, a.anchored, a.fn, a.k, a.i * dim_, term,
            [&](const Eigen::VectorXd& e, StiffnessTerm& t) {
              body_->pointGradients(pose_, a.xb, Phi, e, t.bvC, t.bpC);
            },
            terms_);
    } else if (options_.friction.active()) {  // G e of the body's point (coulomb_friction.h)
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
