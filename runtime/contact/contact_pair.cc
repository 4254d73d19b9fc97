#include "runtime/contact/contact_pair.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/base/error.h"

namespace ffriga {

namespace {
// Below this many collocation points the loop runs serially: thread start-up and spinning
// cost more than the projections (measured: ~60 points of a 2D model take ~0.1 ms).
constexpr int kParallelPoints = 128;
}  // namespace

ContactPair::ContactPair(std::string name, int a, const BodyModel& A, int surfaceA, int b,
                         const BodyModel& B, int surfaceB, const ContactOptions& options)
    : SurfaceContact(std::move(name), a, b, options) {
  if (A.spaceDim() != B.spaceDim()) {
    throw InputError(Str() << "contact '" << this->name() << "': bodies '" << A.name() << "' ("
                           << toString(A.sid().model) << ") and '" << B.name() << "' ("
                           << toString(B.sid().model)
                           << ") are of different kinds");
  }
  FFRIGA_CHECK(options_.penalty > 0.0, "penalty factor " << options_.penalty);
  dim_ = A.spaceDim();
  side_[0].setup(A, surfaceA);
  side_[1].setup(B, surfaceB);
  for (Side& s : side_) {
    s.cache.assign(s.numPoints(), SurfaceProjection());
    s.clearance.assign(s.numPoints(), Side::Clearance());
    size_ = std::max(size_, s.size());
  }
  margin_ = options_.search_margin >= 0.0 ? options_.search_margin : 0.1 * size_;
  for (Side& s : side_) s.edge_reach = s.planar() ? edgeReach() : 0.0;
  pressure_.addRole(side_[0].weight);
  if (options_.both_roles) pressure_.addRole(side_[1].weight);
  pressure_.factor = roleFactor();
}

void ContactPair::addForces(const ForceContext& at, std::vector<Eigen::VectorXd>& h,
                            const ForceStates& states) {
  const int a = bodyA(), b = bodyB();
  evaluate(at.body(a), at.pose(a), at.body(b), at.pose(b), h[a].data(), h[b].data(),
           states.contacts ? &(*states.contacts)[slot()] : nullptr, at.velocities(a),
           at.velocities(b));
}

double ContactPair::boxGap(const ForceContext& at) const {
  const int a = bodyA(), b = bodyB();
  return boxGap(at.body(a), at.pose(a), at.body(b), at.pose(b));
}

Penetration ContactPair::deepestPenetration(const ForceContext& at) const {
  const int a = bodyA(), b = bodyB();
  return deepestPenetration(at.body(a), at.pose(a), at.body(b), at.pose(b));
}

double ContactPair::boxGap(const BodyModel& A, const BodyPose& pa, const BodyModel& B,
                           const BodyPose& pb) const {
  (void)A;
  (void)B;
  const World wa = worldPoints(side_[0], pa), wb = worldPoints(side_[1], pb);
  double gap = -std::numeric_limits<double>::infinity();
  for (int c = 0; c < dim_; ++c) gap = std::max({gap, wa.lo(c) - wb.hi(c), wb.lo(c) - wa.hi(c)});
  return gap;
}

ContactPair::World ContactPair::worldPoints(const Side& side, const BodyPose& pose) const {
  World w;
  worldPoints(side, pose, w);
  return w;
}

void ContactPair::worldPoints(const Side& side, const BodyPose& pose, World& w) const {
  const int d = dim_;
  w.points.resize(side.P0.rows(), d);
  w.u.noalias() = side.PhiSt.transpose() * pose.q;
  const Eigen::VectorXd& u = w.u;
  w.lo.setConstant(d, std::numeric_limits<double>::infinity());
  w.hi = -w.lo;
  SpaceVector xb, x;
  for (std::size_t i = 0; i < side.cps.size(); ++i) {
    const int k = side.cps[i];
    xb = side.P0.row(k).transpose() + u.segment(i * d, d);
    x.noalias() = pose.A * dynamic(xb);  // origin + A xb (GEMV, as for dynamic vectors)
    x += pose.origin;
    w.points.row(k) = x.transpose();
    w.lo = w.lo.cwiseMin(x);
    w.hi = w.hi.cwiseMax(x);
  }
  thread_local SurfacePoint sp;
  side.centre(w.points, sp);
  w.mid_x = sp.x;
  side.surface.normal(sp.dx, w.mid_n);
  w.mid_n *= pose.A.determinant() < 0.0 ? -1.0 : 1.0;
}

double ContactPair::beyondEdgeDepth(const World& wt, const Eigen::VectorXd& n_edge,
                                    const VectorRef& x, const SurfaceProjection& p) const {
  // Axisymmetric: the end of the meridian on the axis (r = 0) is a point of symmetry, not
  // an edge (there the collocation weight 2 pi r w is zero anyway).
  if (dim_ == 2 && std::abs(p.point.x(0)) <= 1e-9 * size_) return 0.0;
  const double edge = -n_edge.dot(x - p.point.x);
  const double centre = -wt.mid_n.dot(x - wt.mid_x);
  return std::max(0.0, std::min(edge, centre));
}

bool ContactPair::withinEdgeReach(const Side& st, const Eigen::VectorXd& n_edge, const VectorRef& x,
                                  const SurfaceProjection& p) {
  if (!(st.edge_reach > 0.0)) return false;
  const SpaceVector d = x - p.point.x;
  return (d - n_edge.dot(d) * n_edge).norm() <= st.edge_reach;
}

void ContactPair::targetMotion(Side& target, const Eigen::VectorXd& u, double renew,
                               TargetMotion& tm) {
  auto changeAgainst = [&](const Eigen::VectorXd& r) {
    double m = 0.0;
    for (Eigen::Index k = 0; k < u.size(); k += dim_)
      m = std::max(m, (u.segment(k, dim_) - r.segment(k, dim_)).norm());
    return m;
  };
  tm.change.clear();
  if (target.snapshots.empty() || changeAgainst(target.snapshots.back().u) > renew) {
    const double moves = target.snapshots.empty()
                             ? 0.0
                             : target.snapshots.back().moves +
                                   changeAgainst(target.snapshots.back().u);
    target.snapshots.push_back({target.next_snapshot++, u, moves});
    if (static_cast<int>(target.snapshots.size()) > kSnapshots) target.snapshots.pop_front();
  }
  tm.first = target.snapshots.front().id;
  for (const Side::Snapshot& r : target.snapshots) tm.change.push_back(changeAgainst(r.u));
  tm.moves = target.snapshots.back().moves;
}

double ContactPair::TargetMotion::since(const Side::Clearance& cl) const {
  const long j = cl.snapshot - first;
  // Kept snapshot s: |u - u_s| + |u_e - u_s|; older: through the newest snapshot and the
  // moves between, |u - u_n| + (D_n - D_s) + |u_e - u_s|.
  if (j >= 0) return change[j] + cl.motion;
  return change.back() + (moves - cl.snapshot_moves) + cl.motion;
}

void ContactPair::evaluate(const BodyModel& A, const BodyPose& pa, const BodyModel& B,
                           const BodyPose& pb, double* hA, double* hB, ContactState* state,
                           const double* svA, const double* svB) {
  FFRIGA_CHECK(!options_.friction.active() || (svA != nullptr && svB != nullptr),
               "friction needs the bodies' velocities");
  active_.clear();
  active_basis_.clear();
  terms_formed_ = false;
  bodies_[0] = &A;
  bodies_[1] = &B;
  poses_[0] = pa;
  poses_[1] = pb;
  World& wa = world_[0];
  World& wb = world_[1];
  worldPoints(side_[0], pa, wa);
  worldPoints(side_[1], pb, wb);
  // Bounding-box pre-check: apart means no work.
  for (int c = 0; c < dim_; ++c) {
    if (wa.lo(c) > wb.hi(c) + margin_ || wb.lo(c) > wa.hi(c) + margin_) {
      if (state) pressure_.clear();
      return;
    }
  }
  // Target motion of each side (header comment). A new snapshot is taken once the newest
  // is a penetration tolerance away: records then hold d_T,e below that size.
  const double renew = penetrationTolerance();
  targetMotion(side_[0], wa.u, renew, motion_[0]);
  targetMotion(side_[1], wb.u, renew, motion_[1]);
  const TargetMotion* motion = motion_;
  const double factor = roleFactor();
  if (options_.friction.active()) {
    wa.udot = elasticVelocities(side_[0], A, svA);
    wb.udot = elasticVelocities(side_[1], B, svB);
  }
  ContactState s0, s1;
  collocate(0, A, pa, wa, B, pb, wb, hA, hB, factor, motion[1], &s0, state != nullptr, svA, svB);
  if (options_.both_roles)
    collocate(1, B, pb, wb, A, pa, wa, hB, hA, factor, motion[0], &s1, state != nullptr, svB, svA);
  if (state) {
    // s1 holds forces on B: the force on A is minus that.
    state->force = s0.force - s1.force;
    if (dim_ == 2) state->force = Eigen::Vector3d(0.0, state->force(1), 0.0);
    state->normal_force = state->force.norm();
    state->max_penetration = std::max(s0.max_penetration, s1.max_penetration);
    state->beyond_edge_penetration =
        std::max(s0.beyond_edge_penetration, s1.beyond_edge_penetration);
    state->active_points = s0.active_points + s1.active_points;
    state->energy = s0.energy + s1.energy;
    state->projection_failures = s0.projection_failures + s1.projection_failures;
    if (options_.friction.active()) {
      state->tangential_force = s0.tangential_force - s1.tangential_force;
      if (dim_ == 2)
        state->tangential_force = Eigen::Vector3d(0.0, state->tangential_force(1), 0.0);
      state->normal_force = (state->force - state->tangential_force).norm();
      state->friction_power = s0.friction_power + s1.friction_power;
      state->sticking_points = s0.sticking_points + s1.sticking_points;
      state->slipping_points = s0.slipping_points + s1.slipping_points;
    }
  }
}

bool ContactPair::needsSearch(const Side& sc, int i, const BodyModel& C, const BodyPose& pc,
                              const World& wc, const BodyPose& pt, const World& wt,
                              const TargetMotion& motion, PointResult& r) {
  const int d = dim_;
  if (C.nq() > 0) {
    sc.bodyPoint(i, wc.u, r.xb);
  } else {
    r.xb = sc.xc0.row(i).transpose();
  }
  r.x.noalias() = pc.A * dynamic(r.xb);  // origin + A xb
  r.x += pc.origin;
  bool near = true;
  for (int a = 0; a < d; ++a)
    near = near && r.x(a) >= wt.lo(a) - margin_ && r.x(a) <= wt.hi(a) + margin_;
  if (!near) return false;
  const SpaceVector rel = r.x - pt.origin;
  r.y.noalias() = pt.A.transpose() * dynamic(rel);
  const Side::Clearance& cl = sc.clearance[i];
  if (cl.valid && cl.gap - (r.y - cl.y.head(d)).norm() - motion.since(cl) > 0.0) {
    ++avoided_;
    return false;
  }
  return true;
}

void ContactPair::searchPoint(Side& sc, const Side& st, int i, const BodyPose& pt, const World& wt,
                              double orientT, double factor, const TargetMotion& motion,
                              PointResult& r) const {
  const SpaceVector& x = r.x;
  Side::Clearance& cl = sc.clearance[i];
  cl.valid = false;
  // Per-thread workspaces (the searches run in parallel): storage reused, no allocation.
  thread_local SurfaceProjection p;
  thread_local Eigen::VectorXd n;
  closestPoint(st.surface, wt.points, x, &sc.cache[i], p);
  r.failed = !p.converged;
  if (!p.converged) return;
  sc.cache[i] = p;  // warm start of the next evaluation, also for points beyond the edge
  // World normal: the body's rule applied to world tangents, turned back if the body's
  // map is a reflection (an axisymmetric body turned about a radial axis: y -> -y).
  st.surface.normal(p.point.dx, n);
  n *= orientT;
  if (!p.orthogonal && !withinEdgeReach(st, n, x, p)) {
    r.beyond_edge = beyondEdgeDepth(wt, n, x, p);
    return;
  }
  r.gap = n.dot(x - p.point.x);
  if (r.gap >= 0.0) {
    cl.valid = true;
    cl.gap = r.gap;
    cl.y.head(dim_) = r.y;
    cl.snapshot = st.snapshots.back().id;
    cl.snapshot_moves = motion.moves;
    cl.motion = motion.change.back();
    return;
  }
  r.active = true;
  r.n = n;
  r.f = (-options_.penalty * r.gap * sc.weight(i) * factor) * n;
  const SpaceVector rel = p.point.x - pt.origin;
  r.xt.noalias() = pt.A.transpose() * dynamic(rel);
  r.element = p.element;
  r.s = p.s;
}

void ContactPair::addDiagnostics(const PointResult& r, double weight, double factor,
                                 ContactState& state) const {
  if (r.failed) ++state.projection_failures;
  state.beyond_edge_penetration = std::max(state.beyond_edge_penetration, r.beyond_edge);
  if (!r.active) return;
  state.force.head(dim_) += r.f;
  state.max_penetration = std::max(state.max_penetration, -r.gap);
  ++state.active_points;
  state.energy += 0.5 * options_.penalty * r.gap * r.gap * weight * factor;
  if (!options_.friction.active()) return;
  state.tangential_force.head(dim_) += r.friction.force;
  state.friction_power += r.friction.power;
  ++(r.friction.sticking ? state.sticking_points : state.slipping_points);
}

void ContactPair::addPointForces(int c, int i, const PointResult& r, double factor,
                                 const BodyModel& C, const BodyPose& pc, const BodyModel& T,
                                 const BodyPose& pt, double* hC, double* hT, ForceSums& sums) {
  const Side& sc = side_[c];
  const Side& st = side_[1 - c];
  const int d = dim_;
  // Contact body: rigid and elastic parts at the collocation point.
  C.addRigidPointForce(pc, r.xb, r.f, hC);
  SpaceVector fbC;
  fbC.noalias() = pc.A.transpose() * dynamic(r.f);
  sums.fbSum.noalias() += sc.PhiCt.middleCols(i * d, d) * dynamic(fbC);
  // Target body: -f at x_T, elastic part through the basis at s (sums.R).
  const SpaceVector minus = -r.f;
  T.addRigidPointForce(pt, r.xt, minus, hT);
  SpaceVector fbT;
  fbT.noalias() = pt.A.transpose() * dynamic(minus);
  const int nf = st.surface.numFunctions(r.element);
  for (int k = 0; k < nf; ++k) {
    const int f = st.surface.functions(r.element)[k];
    sums.FT.row(st.local[f]) += sums.R(0, k) * fbT.transpose();
    sums.touched[st.local[f]] = 1;
  }
  active_.push_back({c, i, r.element, options_.penalty * sc.weight(i) * factor,
                     active_basis_.size(), r.xb, r.xt, r.n, r.friction});
  for (int k = 0; k < nf; ++k) active_basis_.push_back(sums.R(0, k));
}

void ContactPair::footModes(const Side& st, const BodyModel& T, int element, const double* basis,
                            Eigen::MatrixXd& PhiTt) const {
  const int d = dim_;
  PhiTt.setZero(T.nq(), d);
  if (T.nq() == 0) return;
  for (int k = 0; k < st.surface.numFunctions(element); ++k) {
    const int f = st.surface.functions(element)[k];
    PhiTt += basis[k] * st.PhiSt.middleCols(st.local[f] * d, d);
  }
}

Eigen::VectorXd ContactPair::elasticVelocities(const Side& side, const BodyModel& body,
                                               const double* sv) const {
  if (body.nq() == 0) return Eigen::VectorXd();
  return side.displacements(
      Eigen::Map<const Eigen::VectorXd>(sv + body.numRigidVelocities(), body.nq()));
}

void ContactPair::addFriction(int c, int i, PointResult& r, const BodyModel& C, const BodyPose& pc,
                              const World& wc, const BodyModel& T, const BodyPose& pt,
                              const World& wt, const Eigen::MatrixXd& R, const double* svC,
                              const double* svT) const {
  const Side& sc = side_[c];
  const Side& st = side_[1 - c];
  const int d = dim_;
  // The foot point's elastic velocity: the target surface's basis at s over its control
  // points' velocities.
  SpaceVector udotT = SpaceVector::Zero(d);
  if (wt.udot.size() > 0) {
    for (int k = 0; k < st.surface.numFunctions(r.element); ++k) {
      const int f = st.surface.functions(r.element)[k];
      udotT += R(0, k) * wt.udot.segment(st.local[f] * d, d);
    }
  }
  const Eigen::VectorXd v = C.pointVelocity(pc, svC, r.xb, sc.pointDisplacement(i, wc.udot)) -
                            T.pointVelocity(pt, svT, r.xt, udotT);
  r.friction = coulombFriction(options_.friction, r.f.norm(), v, r.n);
  r.f += r.friction.force;
}

void ContactPair::addElasticForces(const Side& st, const BodyModel& C, const BodyModel& T,
                                   double* hC, double* hT, const ForceSums& sums) const {
  const int d = dim_;
  const int nrC = C.numRigidVelocities(), nrT = T.numRigidVelocities();
  if (C.nq() > 0) Eigen::Map<Eigen::VectorXd>(hC + nrC, C.nq()) += sums.fbSum;
  if (T.nq() > 0) {  // only the control points that carry force (O(nq) each)
    Eigen::Map<Eigen::VectorXd> hTe(hT + nrT, T.nq());
    for (std::size_t k = 0; k < st.cps.size(); ++k) {
      if (sums.touched[k])
        hTe.noalias() += st.PhiSt.middleCols(k * d, d) * sums.FT.row(k).transpose();
    }
  }
}

void ContactPair::collocate(int c, const BodyModel& C, const BodyPose& pc, const World& wc,
                            const BodyModel& T, const BodyPose& pt, const World& wt, double* hC,
                            double* hT, double factor, const TargetMotion& motion,
                            ContactState* state, bool record, const double* svC,
                            const double* svT) {
  Side& sc = side_[c];
  const Side& st = side_[1 - c];
  const int d = dim_, nc = static_cast<int>(sc.xc0.rows());
  std::vector<PointResult>& res = results_[c];
  res.assign(nc, PointResult());
  const double orientT = pt.A.determinant() < 0.0 ? -1.0 : 1.0;
  // Phase 1 (serial): the points, and which of them need a search.
  std::vector<int>& search = search_;
  search.clear();
  for (int i = 0; i < nc; ++i) {
    if (needsSearch(sc, i, C, pc, wc, pt, wt, motion, res[i])) search.push_back(i);
  }
  searches_ += static_cast<long long>(search.size());
  // Phase 2: closest points of the candidates.
  const int ns = static_cast<int>(search.size());
#pragma omp parallel for schedule(dynamic, 8) if (ns >= kParallelPoints)
  for (int k = 0; k < ns; ++k) {
    const int i = search[k];
    searchPoint(sc, st, i, pt, wt, orientT, factor, motion, res[i]);
  }
  // Phase 3: serial sums in point order (independent of the thread count).
  ForceSums& sums = sums_[c];
  sums.fbSum.setZero(C.nq());
  sums.FT.setZero(st.cps.size(), d);
  sums.touched.assign(st.cps.size(), 0);
  const bool friction = options_.friction.active();
  for (int i = 0; i < nc; ++i) {
    PointResult& r = res[i];
    if (r.active) st.surface.basis(r.element, r.s.data(), 0, sums.R);  // at the foot point
    if (r.active && friction) addFriction(c, i, r, C, pc, wc, T, pt, wt, sums.R, svC, svT);
    if (state) addDiagnostics(r, sc.weight(i), factor, *state);
    if (r.active) addPointForces(c, i, r, factor, C, pc, T, pt, hC, hT, sums);
    if (record) {
      if (r.active)
        pressure_.set(c, i, r.x, -options_.penalty * r.gap, r.n);
      else
        pressure_.set(c, i, r.x);
      if (r.active && friction) pressure_.setTraction(c, i, r.friction.force);
    }
  }
  addElasticForces(st, C, T, hC, hT, sums);
}

StiffnessTerm ContactPair::spareTerm() const {
  // A new term (every field at its default) holding the gradients' storage of a spare one:
  // pointGradients overwrites bv and bp whole. A field added to StiffnessTerm later starts
  // at its default here without being named.
  StiffnessTerm term;
  if (spare_terms_.empty()) return term;
  StiffnessTerm& spare = spare_terms_.back();
  term.bvC.swap(spare.bvC);
  term.bpC.swap(spare.bpC);
  term.bvT.swap(spare.bvT);
  term.bpT.swap(spare.bpT);
  spare_terms_.pop_back();
  return term;
}

const std::vector<StiffnessTerm>& ContactPair::stiffnessTerms() const {
  if (terms_formed_) return terms_;
  // The last formation's terms become spares: their vectors' storage is reused.
  for (StiffnessTerm& t : terms_) spare_terms_.push_back(std::move(t));
  terms_.clear();
  terms_.reserve(active_.size());
  const int d = dim_;
  for (const ActivePoint& a : active_) {
    const Side& sc = side_[a.c];
    const Side& st = side_[1 - a.c];
    const BodyModel& C = *bodies_[a.c];
    const BodyModel& T = *bodies_[1 - a.c];
    // Phi at the foot point x_T, transposed: the surface basis at s over T's control points.
    footModes(st, T, a.element, active_basis_.data() + a.basis, PhiTt_);
    StiffnessTerm term = spareTerm();
    term.body_c = a.c == 0 ? bodyA() : bodyB();
    term.body_t = a.c == 0 ? bodyB() : bodyA();
    term.k = a.k;
    PhiC_ = sc.PhiCt.middleCols(a.i * d, d).transpose();
    PhiT_ = PhiTt_.transpose();
    C.pointGradients(poses_[a.c], a.xb, PhiC_, a.n, term.bvC, term.bpC);
    T.pointGradients(poses_[1 - a.c], a.xt, PhiT_, a.n, term.bvT, term.bpT);
    // Friction with the relative velocity G_C^T s_vC - G_T^T s_vT (coulomb_friction.h).
    if (options_.friction.active()) {
      appendFrictionTerms(
          a.friction, term,
          [&](const Eigen::VectorXd& e, StiffnessTerm& t) {
            Eigen::VectorXd unused;
            C.pointGradients(poses_[a.c], a.xb, PhiC_, e, t.bvC, unused);
            T.pointGradients(poses_[1 - a.c], a.xt, PhiT_, e, t.bvT, unused);
          },
          terms_);
    }
    terms_.push_back(std::move(term));
  }
  terms_formed_ = true;
  return terms_;
}

Penetration ContactPair::deepestPenetration(const BodyModel& A, const BodyPose& pa,
                                            const BodyModel& B, const BodyPose& pb) const {
  (void)A;
  (void)B;
  const World w[2] = {worldPoints(side_[0], pa), worldPoints(side_[1], pb)};
  const BodyPose* pose[2] = {&pa, &pb};
  Penetration deepest;
  for (int c = 0; c < (options_.both_roles ? 2 : 1); ++c) {
    const Side& sc = side_[c];
    const Side& st = side_[1 - c];
    const BodyPose& pc = *pose[c];
    const BodyPose& pt = *pose[1 - c];
    const double orientT = pt.A.determinant() < 0.0 ? -1.0 : 1.0;
    const int nc = static_cast<int>(sc.xc0.rows());
    std::vector<double> depth(nc, 0.0);
#pragma omp parallel for schedule(dynamic, 8) if (nc >= kParallelPoints)
    for (int i = 0; i < nc; ++i) {
      const Eigen::VectorXd x = pc.origin + pc.A * (sc.xc0.row(i).transpose() + sc.PhiCt.middleCols(i * dim_, dim_).transpose() * pc.q);
      const SurfaceProjection p = closestPoint(st.surface, w[1 - c].points, x, nullptr);
      if (!p.converged) continue;
      const Eigen::VectorXd n = orientT * st.surface.normal(p.point.dx);
      depth[i] = p.orthogonal || withinEdgeReach(st, n, x, p)
                     ? std::max(0.0, -n.dot(x - p.point.x))
                     : beyondEdgeDepth(w[1 - c], n, x, p);
    }
    for (int i = 0; i < nc; ++i) {  // in point order: the same answer on any thread count
      if (depth[i] <= deepest.depth) continue;
      deepest.depth = depth[i];
      deepest.contact_body = c == 0 ? bodyA() : bodyB();
      const Eigen::VectorXd x = pc.origin + pc.A * (sc.xc0.row(i).transpose() + sc.PhiCt.middleCols(i * dim_, dim_).transpose() * pc.q);
      deepest.point.setZero();
      deepest.point.head(dim_) = x;
    }
  }
  return deepest;
}

}  // namespace ffriga
