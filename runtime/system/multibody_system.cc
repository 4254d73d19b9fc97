#include "runtime/system/multibody_system.h"

#include <cmath>
#include <limits>

#include "common/base/error.h"
#include "runtime/system/system_state.h"

namespace ffriga {

int MultibodySystem::addBody(std::unique_ptr<BodyModel> body) {
  bodies_.push_back(std::move(body));
  layout();
  return numBodies() - 1;
}

void MultibodySystem::addForceElement(std::unique_ptr<ForceElement> element) {
  FFRIGA_CHECK(element->bodyA() < numBodies() && element->bodyB() < numBodies(),
               "force element '" << element->name() << "': body index");
  if (auto* pair = dynamic_cast<SurfaceContact*>(element.get())) {
    pair->setSlot(numContacts());
    contacts_.push_back(pair);
  } else if (auto* line = dynamic_cast<LineForce*>(element.get())) {
    line->setSlot(numLineForces());
    line_forces_.push_back(line);
  } else {
    FFRIGA_CHECK(false, "force element '" << element->name() << "' of an unknown kind");
  }
  forces_.push_back(std::move(element));
  layout();  // a contact pair's anchors
}

bool MultibodySystem::hasQuotientForces() const {
  for (const auto& e : forces_)
    if (!e->hasStiffnessTerms()) return true;
  return false;
}

void MultibodySystem::addJoint(std::unique_ptr<Joint> joint) {
  for (int i = 0; i < 2; ++i) FFRIGA_CHECK(joint->end(i).body < numBodies(), "joint body index");
  num_constraints_ += joint->numEquations();
  joints_.push_back(std::move(joint));
}

void MultibodySystem::layout() {
  pos_offset_.clear();
  vel_offset_.clear();
  int n = 0;
  for (const auto& b : bodies_) {
    pos_offset_.push_back(n);
    n += b->numPositions();
  }
  for (const auto& b : bodies_) {
    vel_offset_.push_back(n);
    n += b->numVelocities();
  }
  num_velocities_ = n - (bodies_.empty() ? 0 : vel_offset_[0]);
  anchor_offset_.clear();
  for (const SurfaceContact* c : contacts_) {
    anchor_offset_.push_back(n);
    n += c->numAnchors();
  }
  size_ = n;
  h_.resize(bodies_.size());
}

void MultibodySystem::contactForces(const double* y, std::vector<Eigen::VectorXd>& h,
                                    std::vector<ContactState>* states) {
  h.resize(bodies_.size());
  for (int b = 0; b < numBodies(); ++b) h[b].setZero(bodies_[b]->numVelocities());
  if (states) states->assign(contacts_.size(), ContactState());
  const SystemState at(*this, y);
  ForceStates out;
  out.contacts = states;
  for (const auto& e : forces_)
    if (e->hasStiffnessTerms()) e->addForces(at, h, out);
}

void MultibodySystem::placeEachPairsAnchors(double* y,
                                            void (SurfaceContact::*place)(const ForceContext&,
                                                                          double*) const) const {
  const SystemState at(*this, y);
  for (int c = 0; c < numContacts(); ++c)
    if (contacts_[c]->numAnchors() > 0) (contacts_[c]->*place)(at, y + anchor_offset_[c]);
}

void MultibodySystem::placeAnchors(double* y) const {
  placeEachPairsAnchors(y, &SurfaceContact::initialAnchors);
}

void MultibodySystem::anchorRates(double* ydot) const {
  for (int c = 0; c < numContacts(); ++c)
    if (contacts_[c]->numAnchors() > 0)
      Eigen::Map<Eigen::VectorXd>(ydot + anchor_offset_[c], contacts_[c]->numAnchors()) =
          contacts_[c]->anchorRates();
}

void MultibodySystem::rhs(double, const double* y, double* ydot) {
  evaluateRates(y, ydot, &rhs_states_, &rhs_line_states_);
}

void MultibodySystem::evaluateRates(const double* y, double* ydot,
                                    std::vector<ContactState>* states,
                                    std::vector<LineForceState>* lineStates) {
  constrainedAccelerations(y, ydot, states, lineStates);
  for (int b = 0; b < numBodies(); ++b)
    bodies_[b]->applyQuasiStatic(ydot + pos_offset_[b], ydot + vel_offset_[b]);
}

void MultibodySystem::constrainedAccelerations(const double* y, double* ydot,
                                               std::vector<ContactState>* states,
                                               std::vector<LineForceState>* lineStates) {
  contactForces(y, h_, states);
  anchorRates(ydot);
  addLineForces(y, h_, lineStates);
  for (int b = 0; b < numBodies(); ++b) {
    const BodyModel& body = *bodies_[b];
    const double* sp = y + pos_offset_[b];
    const double* sv = y + vel_offset_[b];
    body.positionRates(sp, sv, ydot + pos_offset_[b]);
    body.accelerations(sp, sv, h_[b].data(), gravity_, ydot + vel_offset_[b]);
  }
  if (!joints_.empty()) applyConstraints(y, ydot);
}

void MultibodySystem::rateQuotients(
    int b, int npCols, int nvCols, Eigen::VectorXd& yy, const double* scale,
    const std::function<void(int, const Eigen::VectorXd&, const Eigen::VectorXd&)>& column) const {
  const BodyModel& body = *bodies_[b];
  const int np = body.numPositions(), nv = body.numVelocities();
  const int po = pos_offset_[b], vo = vel_offset_[b];
  const double sqrtEps = std::sqrt(std::numeric_limits<double>::epsilon());
  Eigen::VectorXd pr0(np), a0(nv), pr(np), a(nv);
  body.positionRates(yy.data() + po, yy.data() + vo, pr0.data());
  body.accelerations(yy.data() + po, yy.data() + vo, h_[b].data(), gravity_, a0.data());
  for (int k = 0; k < npCols + nvCols; ++k) {
    const int j = k < npCols ? po + k : vo + (k - npCols);
    const double saved = yy(j);
    const double delta = sqrtEps * std::max(std::abs(saved), scale[j]);
    yy(j) = saved + delta;
    body.positionRates(yy.data() + po, yy.data() + vo, pr.data());
    body.accelerations(yy.data() + po, yy.data() + vo, h_[b].data(), gravity_, a.data());
    yy(j) = saved;
    column(j, (pr - pr0) / delta, (a - a0) / delta);
  }
}

bool MultibodySystem::jacobian(double, const double* y, const double*, const double* scale,
                               double* Jdata) {
  // Joints and force elements couple the bodies in ways the per-body quotients below do
  // not see: the integrator's own difference quotients of the whole rhs() then serve.
  if (!joints_.empty() || hasQuotientForces()) return false;
  const int n = size_;
  Eigen::Map<Eigen::MatrixXd> J(Jdata, n, n);
  contactForces(y, h_, nullptr);
  Eigen::VectorXd yy = Eigen::Map<const Eigen::VectorXd>(y, n);
  for (int b = 0; b < numBodies(); ++b) {
    const BodyModel& body = *bodies_[b];
    const int np = body.numPositions(), nv = body.numVelocities();
    const int po = pos_offset_[b], vo = vel_offset_[b];
    rateQuotients(b, np, nv, yy, scale,
                  [&](int j, const Eigen::VectorXd& dpr, const Eigen::VectorXd& da) {
                    J.block(po, j, np, 1) = dpr;
                    J.block(vo, j, nv, 1) = da;
                  });
  }
  // Contact stiffness: dh_X/ds_p(Y) = -k bv_X bp_Y^T (signs of the target side folded in).
  bool any = false;
  std::vector<Eigen::MatrixXd> dh(numBodies());
  for (const auto& element : forces_) {
    for (const StiffnessTerm& t : element->stiffnessTerms()) {
      const int bodiesOf[2] = {t.body_c, t.body_t};
      const Eigen::VectorXd* bv[2] = {&t.bvC, &t.bvT};
      const Eigen::VectorXd* bp[2] = {&t.bpC, &t.bpT};
      for (int X = 0; X < 2; ++X) {
        if (bodiesOf[X] < 0) continue;  // a target fixed in space
        Eigen::MatrixXd& D = dh[bodiesOf[X]];
        if (D.size() == 0) D.setZero(bodies_[bodiesOf[X]]->numVelocities(), n);
        for (int Y = 0; Y < 2; ++Y) {
          if (bodiesOf[Y] < 0) continue;
          const double sign = (X == Y) ? -1.0 : 1.0;
          const int po = t.onVelocities() ? vel_offset_[bodiesOf[Y]] : pos_offset_[bodiesOf[Y]];
          D.middleCols(po, bp[Y]->size()) += (sign * t.k) * (*bv[X]) * bp[Y]->transpose();
        }
      }
      any = true;
    }
  }
  if (any) {
    for (int b = 0; b < numBodies(); ++b) {
      if (dh[b].size() == 0) continue;
      bodies_[b]->solveMass(y + pos_offset_[b], dh[b]);
      J.middleRows(vel_offset_[b], dh[b].rows()) += dh[b];
    }
  }
  denseAnchorTerms(y, J);
  for (int b = 0; b < numBodies(); ++b)
    bodies_[b]->quasiStatic().applyToRows(pos_offset_[b] + bodies_[b]->numRigidPositions(),
                                          vel_offset_[b] + bodies_[b]->numRigidVelocities(), J);
  return true;
}

void MultibodySystem::denseAnchorTerms(const double* y, Eigen::Map<Eigen::MatrixXd>& J) {
  for (int c = 0; c < numContacts(); ++c) {
    const SurfaceContact& pair = *contacts_[c];
    if (pair.numAnchors() == 0) continue;
    const int a0 = anchor_offset_[c];
    for (const StiffnessTerm& t : pair.stiffnessTerms()) {
      if (t.anchor < 0) continue;
      const int d = static_cast<int>(t.aV.size()), za = a0 + t.anchor;
      // The bodies' rows on the anchor's columns: -k M^-1 [bvC; -bvT] aV^T.
      const int bodiesOf[2] = {t.body_c, t.body_t};
      const Eigen::VectorXd* bv[2] = {&t.bvC, &t.bvT};
      const Eigen::VectorXd* bp[2] = {&t.bpC, &t.bpT};
      for (int X = 0; X < 2; ++X) {
        const int b = bodiesOf[X];
        if (b < 0) continue;
        Eigen::MatrixXd col = (X == 0 ? -t.k : t.k) * (*bv[X]);
        bodies_[b]->solveMass(y + pos_offset_[b], col);
        J.block(vel_offset_[b], za, col.rows(), d) += col * t.aV.transpose();
        // The anchor's rows on the bodies' positions: aU [bpC; -bpT]^T.
        J.block(za, pos_offset_[b], d, bp[X]->size()) +=
            (X == 0 ? 1.0 : -1.0) * t.aU * bp[X]->transpose();
      }
      J.block(za, za, d, d) += t.aU * t.aV.transpose();
    }
  }
}

namespace {

// M^-1 x for a body with Me = E from its mass blocks (C, S^-1 = (Mrr - C^T C)^-1, nrv rigid
// velocities): z_r = S^-1 (x_r - C^T x_e), z_e = x_e - C z_r.
Eigen::VectorXd solveMassBlocks(const Eigen::MatrixXd& C, const Eigen::MatrixXd& Sinv, int nrv,
                                const Eigen::VectorXd& x) {
  const Eigen::VectorXd xr = x.head(nrv), xe = x.tail(x.size() - nrv);
  Eigen::VectorXd z(x.size());
  z.head(nrv) = Sinv * (xr - C.transpose() * xe);
  z.tail(xe.size()) = xe - C * z.head(nrv);
  return z;
}

}  // namespace

int MultibodySystem::structuredRank() const {
  int r = 0;
  for (const auto& b : bodies_) r += b->numRigidPositions() + 2 * b->numRigidVelocities();
  for (const auto& element : forces_) r += static_cast<int>(element->stiffnessTerms().size());
  r += num_constraints_;  // the joints' projection of the elastic columns (below)
  return r;
}

void MultibodySystem::elasticPairs(int b, StructuredJacobian& J, std::vector<double>& fRate) const {
  const BodyModel& body = *bodies_[b];
  const int nq = body.nq(), nrp = body.numRigidPositions(), nrv = body.numRigidVelocities();
  const int po = pos_offset_[b], vo = vel_offset_[b];
  const QuasiStaticModes& qs = body.quasiStatic();
  for (int s = 0, i = 0; i < nq; ++i) {
    if (s < qs.size() && qs.index[s] == i) {
      J.f_index.push_back(po + nrp + i);
      fRate.push_back(1.0 / qs.tau);
      ++s;
      continue;
    }
    J.k(J.q_index.size()) = body.stiffnessDiagonal()(i);
    J.c(J.q_index.size()) = body.dampingDiagonal()(i);
    J.q_index.push_back(po + nrp + i);
    J.v_index.push_back(vo + nrv + i);
  }
}

void MultibodySystem::rigidColumns(int b, Eigen::VectorXd& yy, const double* scale,
                                   StructuredJacobian& J, int& col) {
  const BodyModel& body = *bodies_[b];
  const int np = body.numPositions(), nv = body.numVelocities();
  const int nrp = body.numRigidPositions(), nrv = body.numRigidVelocities();
  const int po = pos_offset_[b], vo = vel_offset_[b];
  if (joints_.empty()) {
    rateQuotients(b, nrp, nrv, yy, scale,
                  [&](int j, const Eigen::VectorXd& dpr, const Eigen::VectorXd& da) {
                    J.U.col(col).segment(po, np) = dpr;
                    J.U.col(col).segment(vo, nv) = da;
                    J.V(j, col++) = 1.0;
                  });
  } else {
    constrainedQuotients(b, nrp, nrv, yy, scale, [&](int j, const Eigen::VectorXd& df) {
      J.U.col(col) = df;
      J.V(j, col++) = 1.0;
    });
  }
}

void MultibodySystem::inertialCouplingColumns(int b, const double* y, StructuredJacobian& J,
                                              Eigen::MatrixXd& C, Eigen::MatrixXd& Sinv,
                                              int& col) const {
  const BodyModel& body = *bodies_[b];
  const int nq = body.nq(), nrp = body.numRigidPositions(), nrv = body.numRigidVelocities();
  const int po = pos_offset_[b], vo = vel_offset_[b];
  Eigen::MatrixXd Mrr;
  body.massBlocks(y + po, C, Mrr);
  Sinv = (Mrr - C.transpose() * C).inverse();
  const Eigen::MatrixXd SCt = Sinv * C.transpose();
  for (int k = 0; k < nrv; ++k, ++col) {
    J.U(vo + k, col) = 1.0;
    J.U.col(col).segment(vo + nrv, nq) = -C.col(k);
    J.V.col(col).segment(po + nrp, nq) =
        SCt.row(k).transpose().cwiseProduct(body.stiffnessDiagonal());
    J.V.col(col).segment(vo + nrv, nq) =
        SCt.row(k).transpose().cwiseProduct(body.dampingDiagonal());
  }
}

void MultibodySystem::contactColumns(const std::vector<Eigen::MatrixXd>& C,
                                     const std::vector<Eigen::MatrixXd>& Sinv,
                                     StructuredJacobian& J, int& col) const {
  auto solveMass = [&](int b, const Eigen::VectorXd& x) {
    return solveMassBlocks(C[b], Sinv[b], bodies_[b]->numRigidVelocities(), x);
  };
  for (const auto& element : forces_) {
    for (const StiffnessTerm& t : element->stiffnessTerms()) {
      const int bc = t.body_c, bt = t.body_t;
      const std::vector<int>& of = t.onVelocities() ? vel_offset_ : pos_offset_;
      J.U.col(col).segment(vel_offset_[bc], t.bvC.size()) += -t.k * solveMass(bc, t.bvC);
      J.V.col(col).segment(of[bc], t.bpC.size()) += t.bpC;
      if (t.anchor >= 0) {  // the pair's stick anchors (coulomb_friction.h)
        const int za = anchor_offset_[element->slot()] + t.anchor;
        J.U.col(col).segment(za, t.aU.size()) += t.aU;
        J.V.col(col).segment(za, t.aV.size()) += t.aV;
      }
      if (bt >= 0) {  // else a target fixed in space
        J.U.col(col).segment(vel_offset_[bt], t.bvT.size()) += t.k * solveMass(bt, t.bvT);
        J.V.col(col).segment(of[bt], t.bpT.size()) -= t.bpT;
      }
      ++col;
    }
  }
}

bool MultibodySystem::structuredJacobian(double, const double* y, const double* scale,
                                         StructuredJacobian& J) {
  // Force elements without joints: as jacobian() (their stiffness is not in the terms).
  if (joints_.empty() && hasQuotientForces()) return false;
  for (const auto& b : bodies_)
    if (!b->diagonalElasticity()) return false;
  const int n = size_;
  contactForces(y, h_, nullptr);
  const int r = structuredRank();
  // Woodbury costs O(n r^2 + r^3): with as many low-rank columns as half the state (rigid
  // bodies only, few elastic coordinates) the dense LU is the cheaper Newton matrix.
  if (!joints_.empty() && 2 * r > n) return false;
  J.n = n;
  J.q_index.clear();
  J.v_index.clear();
  J.f_index.clear();
  std::vector<double> fRate;
  J.U.setZero(n, r);
  J.V.setZero(n, r);
  int pairs = 0;
  for (const auto& b : bodies_) pairs += b->nq();
  J.k.resize(pairs);
  J.c.resize(pairs);
  std::vector<Eigen::MatrixXd> C(numBodies()), Sinv(numBodies());
  Eigen::VectorXd yy = Eigen::Map<const Eigen::VectorXd>(y, n);
  int col = 0;
  for (int b = 0; b < numBodies(); ++b) {
    elasticPairs(b, J, fRate);
    rigidColumns(b, yy, scale, J, col);
    inertialCouplingColumns(b, y, J, C[b], Sinv[b], col);
  }
  contactColumns(C, Sinv, J, col);
  J.k.conservativeResize(static_cast<Eigen::Index>(J.q_index.size()));
  J.c.conservativeResize(static_cast<Eigen::Index>(J.q_index.size()));
  J.f_rate = Eigen::Map<const Eigen::VectorXd>(fRate.data(), static_cast<Eigen::Index>(fRate.size()));
  // With joints the rates are the constrained accelerations (projectJacobian), and a
  // quasi-static coordinate's rate is its constrained acceleration / (k tau)
  // (evaluateRates): the projection first, then the quasi-static rows, position row <-
  // acceleration row / (k tau), of every column (the joints' included).
  if (!joints_.empty()) projectJacobian(y, J, col);
  for (int b = 0; b < numBodies(); ++b)
    bodies_[b]->quasiStatic().applyToRows(pos_offset_[b] + bodies_[b]->numRigidPositions(),
                                          vel_offset_[b] + bodies_[b]->numRigidVelocities(), J.U);
  FFRIGA_ASSERT(col == r, "structured Jacobian: " << col << " of " << r << " columns");
  return true;
}

void MultibodySystem::constrainedQuotients(
    int b, int npCols, int nvCols, Eigen::VectorXd& yy, const double* scale,
    const std::function<void(int, const Eigen::VectorXd&)>& column) {
  // h_ holds the contact forces at yy (frozen); the force elements and the joints are
  // evaluated at every perturbed state.
  const std::vector<Eigen::VectorXd> contact = h_;
  auto rates = [&](Eigen::VectorXd& f) {
    std::vector<Eigen::VectorXd> h = contact;
    addLineForces(yy.data(), h, nullptr);
    for (int c = 0; c < numBodies(); ++c) {
      const double* sp = yy.data() + pos_offset_[c];
      const double* sv = yy.data() + vel_offset_[c];
      bodies_[c]->positionRates(sp, sv, f.data() + pos_offset_[c]);
      bodies_[c]->accelerations(sp, sv, h[c].data(), gravity_, f.data() + vel_offset_[c]);
    }
    applyConstraints(yy.data(), f.data());
  };
  const double sqrtEps = std::sqrt(std::numeric_limits<double>::epsilon());
  Eigen::VectorXd f0(size_), f(size_);
  rates(f0);
  for (int k = 0; k < npCols + nvCols; ++k) {
    const int j = k < npCols ? pos_offset_[b] + k : vel_offset_[b] + (k - npCols);
    const double saved = yy(j);
    const double delta = sqrtEps * std::max(std::abs(saved), scale[j]);
    yy(j) = saved + delta;
    rates(f);
    yy(j) = saved;
    column(j, (f - f0) / delta);
  }
}

void MultibodySystem::projectJacobian(const double* y, StructuredJacobian& J, int& col) const {
  // The constrained accelerations are P a with P = I - X S^-1 J_c on the velocity rows
  // (header comment; the q-dependence of J_c, X and the bias neglected like that of M(q)):
  //   P (D + U V^T) = D + (P U) V^T - X (S^-1 J_c D),
  // so U <- P U, and m columns U = -X, V = (S^-1 J_c D)^T with J_c D over the elastic
  // pairs: d/dq_i (velocity row of qdot_i) = -k_i, d/dqdot_i = -c_i.
  ConstraintRows rows;
  constraintRows(y, rows);
  Eigen::MatrixXd X;
  Eigen::LLT<Eigen::MatrixXd> S;
  constraintMobility(y, rows.J, X, S);
  const int v0 = vel_offset_[0], nv = totalVelocities(), m = num_constraints_;
  auto Uv = J.U.middleRows(v0, nv);
  Uv -= X * S.solve(rows.J * Uv);
  Eigen::MatrixXd JD = Eigen::MatrixXd::Zero(m, size_);
  for (std::size_t i = 0; i < J.q_index.size(); ++i) {
    const int vrow = J.v_index[i] - v0;
    JD.col(J.q_index[i]) = -J.k(static_cast<Eigen::Index>(i)) * rows.J.col(vrow);
    JD.col(J.v_index[i]) = -J.c(static_cast<Eigen::Index>(i)) * rows.J.col(vrow);
  }
  const Eigen::MatrixXd W = S.solve(JD);  // m x n
  for (int k = 0; k < m; ++k, ++col) {
    J.U.col(col).setZero();
    J.U.col(col).segment(v0, nv) = -X.col(k);
    J.V.col(col) = W.row(k).transpose();
  }
}

void MultibodySystem::normalize(double* y) const {
  for (int b = 0; b < numBodies(); ++b) bodies_[b]->normalize(y + pos_offset_[b]);
}

double MultibodySystem::contactGap(const double* y, double* size) const {
  double gap = std::numeric_limits<double>::infinity();
  const SystemState at(*this, y);
  for (const auto& pair : contacts_) {
    const double g = pair->boxGap(at);
    if (g < gap) {
      gap = g;
      if (size) *size = pair->surfaceSize();
    }
  }
  return gap;
}

Penetration MultibodySystem::deepestPenetration(const double* y, int c) const {
  return contacts_[c]->deepestPenetration(SystemState(*this, y));
}

const std::string& MultibodySystem::contactSideName(int c, int side) const {
  const SurfaceContact& pair = *contacts_[c];
  const int b = side == 0 ? pair.bodyA() : pair.bodyB();
  return b >= 0 ? bodies_[b]->name() : pair.obstacleName();
}

SystemEnergies MultibodySystem::energies(const double* y) {
  SystemEnergies e;
  for (int b = 0; b < numBodies(); ++b) {
    const double* sp = y + pos_offset_[b];
    e.kinetic += bodies_[b]->kineticEnergy(sp, y + vel_offset_[b]);
    e.elastic += bodies_[b]->elasticEnergy(sp);
    e.gravity += bodies_[b]->gravityEnergy(sp, gravity_);
  }
  if (numContacts() > 0) {
    std::vector<ContactState> states;
    std::vector<Eigen::VectorXd> h;
    contactForces(y, h, &states);
    for (const ContactState& s : states) e.contact += s.energy;
  }
  for (const LineForceState& s : lineForceStates(y)) e.force_elements += s.energy;
  return e;
}

void MultibodySystem::momentum(const double* y, Eigen::Vector3d& linear,
                               Eigen::Vector3d& angular) const {
  linear.setZero();
  angular.setZero();
  for (int b = 0; b < numBodies(); ++b) {
    Eigen::Vector3d l, a;
    bodies_[b]->momentum(y + pos_offset_[b], y + vel_offset_[b], l, a);
    linear += l;
    angular += a;
  }
}

}  // namespace ffriga
