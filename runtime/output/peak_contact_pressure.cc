#include "runtime/output/peak_contact_pressure.h"

#include "common/base/error.h"

namespace ffriga {

using h5::Handle;

namespace {

void describe(const h5::Context& c, hid_t group, const std::string& name, const std::string& unit,
              const std::string& description) {
  Handle set(c.check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "open " + name), H5Dclose);
  h5::writeAttribute(c, set.id(), "unit", unit);
  h5::writeAttribute(c, set.id(), "description", description);
}

}  // namespace

PeakContactPressure::PeakContactPressure(ResultFile& file, const OutputLayout& layout)
    : file_(file) {
  for (const ConnectionLayout& pair : layout.contacts) {
    Pair p;
    p.group = "contacts/" + pair.name + "/peak_pressure";
    p.role = pair.collocation_role;
    p.weight = pair.collocation_weight;
    p.factor = pair.role_factor;
    p.friction = pair.friction_coefficient > 0.0;
    const Eigen::Index n = p.weight.size();
    FFRIGA_CHECK(static_cast<Eigen::Index>(p.role.size()) == n,
                 "pair " << pair.name << ": " << p.role.size() << " roles, " << n << " weights");
    p.field.position.setZero(n, 3);
    p.field.pressure.setZero(n);
    p.field.normal.setZero(n, 3);
    p.field.traction.setZero(n, 3);
    if (file_.appending() && h5::exists(file_.id(), p.group))
      restore(p);
    else
      create(p);
    pairs_.push_back(std::move(p));
  }
}

void PeakContactPressure::recordPeak(int c, double t, double force, const PressureSample& field) {
  Pair& p = pairs_[c];
  FFRIGA_CHECK(field.pressure.size() == p.weight.size(), p.group << ": " << field.pressure.size()
                                                                 << " points, " << p.weight.size()
                                                                 << " at setup");
  p.time = t;
  p.force = force;
  p.field = field;
  p.pending = true;
}

// The group with every dataset and attribute a flush writes, before any peak (time_s -1):
// in SWMR mode a flush only writes in place (runtime/output/result_file.h).
void PeakContactPressure::create(const Pair& p) {
  const h5::Context c = file_.context();
  Handle g = h5::createGroup(c, file_.id(), p.group);
  h5::writeAttribute(c, g.id(), "time_s", p.time);
  h5::writeAttribute(c, g.id(), "normal_force_N", p.force);
  h5::writeAttribute(c, g.id(), "role_factor", p.factor);
  h5::writeAttribute(c, g.id(), "description",
                     std::string("penalty pressure c_p max(0, -g_n) at every collocation point of "
                                 "each role at the end of the step with the pair's largest "
                                 "normal force; force on body_a = role_factor (sum over role 0 - "
                                 "sum over role 1) of pressure * weight * normal"));
  h5::writeMatrix(c, g.id(), "position", p.field.position, "");
  describe(c, g.id(), "position", "m", "collocation point, world (axisymmetric: x radius, y axis)");
  h5::writeVector(c, g.id(), "pressure", p.field.pressure, "");
  describe(c, g.id(), "pressure", "Pa", "penalty pressure c_p max(0, -g_n)");
  h5::writeMatrix(c, g.id(), "normal", p.field.normal, "");
  describe(c, g.id(), "normal", "1",
           "target's unit outward normal at the foot point (0: no pressure)");
  if (p.friction) {
    h5::writeMatrix(c, g.id(), "traction", p.field.traction, "");
    describe(c, g.id(), "traction", "Pa",
             "tangential (friction) traction on the point's body, world; force on body_a adds "
             "role_factor (sum over role 0 - sum over role 1) of traction * weight");
  }
  h5::writeVector(c, g.id(), "weight", p.weight, "");
  describe(c, g.id(), "weight", "m^2", "collocation weight w_i (axisymmetric: times 2 pi r_i)");
  h5::writeInts(c, g.id(), "role", p.role);
  describe(c, g.id(), "role", "1",
           "0: body_a's points against body_b, 1: body_b's points against body_a");
}

// A restart: the peak the run had recorded before (time_s -1: none).
void PeakContactPressure::restore(Pair& p) {
  const h5::Context c = file_.context();
  Handle g = h5::openGroup(c, file_.id(), p.group);
  p.time = h5::readDoubleAttribute(c, g.id(), "time_s");
  p.force = h5::readDoubleAttribute(c, g.id(), "normal_force_N");
  PressureSample f;
  f.position = h5::readMatrix(c, g.id(), "position");
  f.pressure = h5::readVector(c, g.id(), "pressure");
  f.normal = h5::readMatrix(c, g.id(), "normal");
  const Eigen::Index n = p.weight.size();
  f.traction = p.friction ? h5::readMatrix(c, g.id(), "traction") : Eigen::MatrixXd::Zero(n, 3);
  if (f.position.rows() != n || f.position.cols() != 3 || f.pressure.size() != n ||
      f.normal.rows() != n || f.normal.cols() != 3 || f.traction.rows() != n ||
      f.traction.cols() != 3)
    c.fail("/" + p.group + " has another number of collocation points than the scene's pair");
  p.field = std::move(f);
}

void PeakContactPressure::flush() {
  const h5::Context c = file_.context();
  for (Pair& p : pairs_) {
    if (!p.pending) continue;
    p.pending = false;
    Handle g = h5::openGroup(c, file_.id(), p.group);
    h5::writeAttribute(c, g.id(), "time_s", p.time);
    h5::writeAttribute(c, g.id(), "normal_force_N", p.force);
    file_.rewrite(g.id(), "position", p.field.position);
    file_.rewrite(g.id(), "pressure", p.field.pressure);
    file_.rewrite(g.id(), "normal", p.field.normal);
    if (p.friction) file_.rewrite(g.id(), "traction", p.field.traction);
  }
}

void PeakContactPressure::finish() {
  for (const Pair& p : pairs_)
    if (p.time < 0.0) file_.removeObject("/" + p.group);  // never touched: no group
}

}  // namespace ffriga
