#include "runtime/multibody_system.h"

#include "common/error.h"

namespace ffriga {

int MultibodySystem::addBody(std::unique_ptr<BodyModel> body) {
  bodies_.push_back(std::move(body));
  layout();
  return numBodies() - 1;
}

void MultibodySystem::addContact(std::unique_ptr<ContactPair> pair) {
  FFRIGA_CHECK(pair->bodyA() < numBodies() && pair->bodyB() < numBodies(), "contact body index");
  contacts_.push_back(std::move(pair));
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
  size_ = n;
  h_.resize(bodies_.size());
}

void MultibodySystem::contactForces(const double* y, std::vector<Eigen::VectorXd>& h,
                                    std::vector<ContactState>* states) {
  h.resize(bodies_.size());
  std::vector<BodyPose> poses(bodies_.size());
  for (int b = 0; b < numBodies(); ++b) {
    h[b].setZero(bodies_[b]->numVelocities());
    if (!contacts_.empty()) poses[b] = bodies_[b]->pose(y + pos_offset_[b]);
  }
  if (states) states->assign(contacts_.size(), ContactState());
  for (std::size_t c = 0; c < contacts_.size(); ++c) {
    ContactPair& pair = *contacts_[c];
    const int a = pair.bodyA(), b = pair.bodyB();
    pair.evaluate(*bodies_[a], poses[a], *bodies_[b], poses[b], h[a].data(), h[b].data(),
                  states ? &(*states)[c] : nullptr);
  }
}

void MultibodySystem::rhs(double, const double* y, double* ydot) {
  contactForces(y, h_, nullptr);
  for (int b = 0; b < numBodies(); ++b) {
    const BodyModel& body = *bodies_[b];
    const double* sp = y + pos_offset_[b];
    const double* sv = y + vel_offset_[b];
    body.positionRates(sp, sv, ydot + pos_offset_[b]);
    body.accelerations(sp, sv, h_[b].data(), gravity_, ydot + vel_offset_[b]);
  }
}

void MultibodySystem::normalize(double* y) const {
  for (int b = 0; b < numBodies(); ++b) bodies_[b]->normalize(y + pos_offset_[b]);
}

SystemEnergies MultibodySystem::energies(const double* y) {
  SystemEnergies e;
  for (int b = 0; b < numBodies(); ++b) {
    const double* sp = y + pos_offset_[b];
    e.kinetic += bodies_[b]->kineticEnergy(sp, y + vel_offset_[b]);
    e.elastic += bodies_[b]->elasticEnergy(sp);
    e.gravity += bodies_[b]->gravityEnergy(sp, gravity_);
  }
  if (!contacts_.empty()) {
    std::vector<ContactState> states;
    std::vector<Eigen::VectorXd> h;
    contactForces(y, h, &states);
    for (const ContactState& s : states) e.contact += s.energy;
  }
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
