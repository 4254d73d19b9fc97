// The contact pressure field of a contact pair (paper Sect. 4, Eq. 17) at the collocation
// points of one evaluation: a point i of the contact side of role r (0: body A's points
// against B, 1: B's points against A; an obstacle pair has role 0 only) with normal gap
// g_n,i carries the penalty pressure
//   p_i = c_p max(0, -g_n,i)   (Pa; c_p in N/m^3),
// and the force f_i = factor p_i w_i n_i on its body, n_i the target's unit outward normal
// at the foot point and w_i the collocation weight (m^2; axisymmetric: the meridian weight
// times 2 pi r_i), factor 1/2 where both roles are averaged, else 1. So the resultant on
// body A is factor (sum_{role 0} p_i w_i n_i - sum_{role 1} p_i w_i n_i).
// With friction (runtime/contact/coulomb_friction.h) a point also carries the tangential
// traction t_i = f_t,i / (factor w_i) (Pa, world: the friction force on its body per unit
// area), so that factor sum p_i w_i n_i + factor sum t_i w_i (role 1 with minus signs) is the
// resultant; 0 without friction or contact.
// Rows: the points of role 0 in collocation order, then those of role 1. Positions and
// normals are world coordinates (axisymmetric: (x, y, 0), x the radius and y the axis, as
// the result file's points).
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace ffriga {

struct ContactPressure {
  std::vector<int> role;     // n: 0 or 1
  Eigen::VectorXd weight;    // n, w_i (m^2), fixed at setup
  double factor = 1.0;       // 1/2 (both roles averaged) or 1
  Eigen::MatrixXd position;  // n x 3, m
  Eigen::VectorXd pressure;  // n, Pa (0 where g_n >= 0 or the point is not near the target)
  Eigen::MatrixXd normal;    // n x 3, unit, 0 where p_i = 0
  Eigen::MatrixXd traction;  // n x 3, Pa, 0 without friction

  // Role r's rows begin here (offset(numRoles()) = n).
  int numRoles() const { return role.empty() ? 0 : role.back() + 1; }
  int offset(int r) const { return first_[r]; }
  // Appends role r with these weights (setup, roles in order), every point at rest.
  void addRole(const Eigen::VectorXd& w) {
    const int r = numRoles();
    first_.resize(r + 2);
    first_[r] = static_cast<int>(role.size());
    role.resize(role.size() + w.size(), r);
    first_[r + 1] = static_cast<int>(role.size());
    weight.conservativeResize(role.size());
    weight.tail(w.size()) = w;
    position.setZero(role.size(), 3);
    pressure.setZero(role.size());
    normal.setZero(role.size(), 3);
    traction.setZero(role.size(), 3);
  }
  // No point carries pressure (the surfaces are apart; positions are left as they were).
  void clear() {
    pressure.setZero();
    normal.setZero();
    traction.setZero();
  }
  // Point i of role r at world position x (d entries), without pressure.
  void set(int r, int i, const Eigen::Ref<const Eigen::VectorXd>& x) {
    const int row = first_[r] + i;
    position.row(row).head(x.size()) = x.transpose();
    pressure(row) = 0.0;
    normal.row(row).setZero();
    traction.row(row).setZero();
  }
  // Point i of role r at x with pressure p > 0 (Pa) along the unit normal n (d entries).
  void set(int r, int i, const Eigen::Ref<const Eigen::VectorXd>& x, double p,
           const Eigen::Ref<const Eigen::VectorXd>& n) {
    const int row = first_[r] + i;
    position.row(row).head(x.size()) = x.transpose();
    pressure(row) = p;
    normal.row(row).head(n.size()) = n.transpose();
    traction.row(row).setZero();
  }
  // Point i of role r's tangential force f_t (N, d entries; role factor included): its
  // traction f_t / (factor w_i), set after its pressure (0 on a point of weight 0, the axis).
  void setTraction(int r, int i, const Eigen::Ref<const Eigen::VectorXd>& force) {
    const int row = first_[r] + i;
    if (weight(row) > 0.0)
      traction.row(row).head(force.size()) = force.transpose() / (factor * weight(row));
  }

 private:
  std::vector<int> first_;  // role r's first row
};

}  // namespace ffriga
