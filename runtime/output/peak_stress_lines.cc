#include "runtime/output/peak_stress_lines.h"

#include <cmath>

#include "common/base/error.h"
#include "common/mechanics/von_mises.h"

namespace ffriga {

using h5::Handle;

namespace {

// Whether the line starts on the sphere's surface and points at its centre (1e-6 of the
// radius): then its distances are Hertz's depths z.
bool alongRadius(const StressLine& line, const SidGeometry& g) {
  const int s = static_cast<int>(line.from.size());
  const Eigen::VectorXd c = g.centre.head(s);
  const Eigen::VectorXd toCentre = c - line.from;
  const Eigen::VectorXd dir = line.to - line.from;
  if (!(g.radius > 0.0) || dir.norm() == 0.0) return false;
  if (std::abs(toCentre.norm() - g.radius) > 1e-6 * g.radius) return false;
  return (toCentre.normalized() - dir.normalized()).norm() <= 1e-6;
}

// Index of the largest entry.
Eigen::Index argMax(const Eigen::VectorXd& v) {
  Eigen::Index i = 0;
  v.maxCoeff(&i);
  return i;
}

// Index of the largest local maximum strictly inside the line (-1: none): the subsurface
// maximum of a line that starts at the contact point, apart from the surface value.
Eigen::Index argInteriorMax(const Eigen::VectorXd& v) {
  Eigen::Index best = -1;
  for (Eigen::Index i = 1; i + 1 < v.size(); ++i) {
    if (v(i) >= v(i - 1) && v(i) >= v(i + 1) && (best < 0 || v(i) > v(best))) best = i;
  }
  return best;
}

}  // namespace

PeakStressLines::PeakStressLines(ResultFile& file, const OutputLayout& layout,
                                 std::vector<std::optional<HertzPartner>> partners)
    : file_(file) {
  for (int b = 0; b < static_cast<int>(layout.bodies.size()); ++b) {
    if (layout.bodies[b].nq == 0) continue;  // rigid or frozen: no stresses
    const FlexibleBodySid& sid = *layout.bodies[b].sid;
    for (const StressLine& sl : sid.stress_lines) {
      Line line;
      line.body = b;
      line.body_name = layout.bodies[b].name;
      line.source = &sl;
      if (b < static_cast<int>(partners.size()) && partners[b] && alongRadius(sl, sid.geometry))
        line.hertz = partners[b];
      const Eigen::MatrixXd& P = sl.samples.points;
      line.distance.resize(P.rows());
      for (Eigen::Index i = 0; i < P.rows(); ++i)
        line.distance(i) = (P.row(i).transpose() - sl.from).norm();
      line.stress.setZero(P.rows(), 6);
      line.von_mises.setZero(P.rows());
      lines_.push_back(std::move(line));
    }
  }
  if (lines_.empty()) return;
  if (file_.appending() && h5::exists(file_.id(), "stress_lines"))
    restore();
  else
    create();
}

void PeakStressLines::recordPeak(double t, double force, const std::vector<BodySample>& bodies) {
  if (lines_.empty()) return;
  time_ = t;
  force_ = force;
  pending_ = true;
  for (Line& line : lines_) {
    const Eigen::VectorXd& q = bodies[line.body].pose_q;
    const SampledModes& S = (*line.source).samples;
    const Eigen::Index n = S.points.rows();
    line.stress.setZero(n, 6);
    line.von_mises.setZero(n);
    if (q.size() == 0 || q.size() != S.stress.cols()) continue;  // frozen: no stress
    const Eigen::VectorXd sigma = S.stress * q;
    for (Eigen::Index i = 0; i < n; ++i) {
      line.stress.row(i) = sigma.segment(6 * i, 6).transpose();
      line.von_mises(i) = vonMises(sigma.data() + 6 * i);
    }
  }
}

// /stress_lines with every dataset and attribute a flush writes, before any peak (time_s
// -1): in SWMR mode a flush only writes in place (runtime/output/result_file.h).
void PeakStressLines::create() {
  const h5::Context c = file_.context();
  Handle root = h5::createGroup(c, file_.id(), "stress_lines");
  h5::writeAttribute(c, root.id(), "time_s", -1.0);
  h5::writeAttribute(c, root.id(), "contact_force_N", 0.0);
  h5::writeAttribute(c, root.id(), "description",
                     std::string("stresses along the SIDs' stress lines at the step of the "
                                 "largest contact force"));
  const double nan = std::nan("");
  for (const Line& line : lines_) {
    const StressLine& sl = *line.source;
    Handle bg = h5::exists(root.id(), line.body_name) ? h5::openGroup(c, root.id(), line.body_name)
                                                       : h5::createGroup(c, root.id(), line.body_name);
    Handle g = h5::createGroup(c, bg.id(), sl.name);
    h5::writeVector(c, g.id(), "from", sl.from, "m");
    h5::writeVector(c, g.id(), "to", sl.to, "m");
    h5::writeMatrix(c, g.id(), "points", sl.samples.points, "m");
    h5::writeVector(c, g.id(), "distance", line.distance, "m");
    h5::writeMatrix(c, g.id(), "stress", line.stress, "Pa");
    h5::writeVector(c, g.id(), "von_mises", line.von_mises, "Pa");
    for (const char* a : {"von_mises_max_Pa", "von_mises_max_distance_m",
                          "von_mises_interior_max_Pa", "von_mises_interior_max_distance_m"})
      h5::writeAttribute(c, g.id(), a, nan);
    if (!line.hertz) continue;
    const Eigen::VectorXd none = Eigen::VectorXd::Constant(line.distance.size(), nan);
    for (const char* d : {"hertz_von_mises", "hertz_sigma_radial", "hertz_sigma_axial"})
      h5::writeVector(c, g.id(), d, none, "Pa");
    for (const char* a : {"hertz_contact_radius_m", "hertz_max_pressure_Pa",
                          "hertz_von_mises_max_Pa", "hertz_von_mises_max_depth_m"})
      h5::writeAttribute(c, g.id(), a, nan);
  }
}

// A restart: the peak the run had recorded before (time_s -1: none).
void PeakStressLines::restore() {
  const h5::Context c = file_.context();
  Handle root = h5::openGroup(c, file_.id(), "stress_lines");
  time_ = h5::readDoubleAttribute(c, root.id(), "time_s");
  force_ = h5::readDoubleAttribute(c, root.id(), "contact_force_N");
  for (Line& line : lines_) {
    Handle g = h5::openGroup(c, root.id(), line.body_name + "/" + line.source->name);
    const Eigen::MatrixXd stress = h5::readMatrix(c, g.id(), "stress");
    const Eigen::VectorXd von_mises = h5::readVector(c, g.id(), "von_mises");
    if (stress.rows() != line.stress.rows() || von_mises.size() != line.von_mises.size())
      c.fail("/stress_lines/" + line.body_name + "/" + line.source->name + " has another size");
    line.stress = stress;
    line.von_mises = von_mises;
  }
}

void PeakStressLines::flush() {
  if (!pending_) return;
  pending_ = false;
  const h5::Context c = file_.context();
  Handle root = h5::openGroup(c, file_.id(), "stress_lines");
  h5::writeAttribute(c, root.id(), "time_s", time_);
  h5::writeAttribute(c, root.id(), "contact_force_N", force_);
  const std::vector<StressLinePeak> summary = peaks();
  for (std::size_t k = 0; k < lines_.size(); ++k) {
    const Line& line = lines_[k];
    const StressLinePeak& peak = summary[k];
    Handle g = h5::openGroup(c, root.id(), line.body_name + "/" + line.source->name);
    file_.rewrite(g.id(), "stress", line.stress);
    file_.rewrite(g.id(), "von_mises", line.von_mises);
    const Eigen::Index at = argMax(line.von_mises);
    h5::writeAttribute(c, g.id(), "von_mises_max_Pa", line.von_mises(at));
    h5::writeAttribute(c, g.id(), "von_mises_max_distance_m", line.distance(at));
    h5::writeAttribute(c, g.id(), "von_mises_interior_max_Pa", peak.von_mises);
    h5::writeAttribute(c, g.id(), "von_mises_interior_max_distance_m", peak.distance);
    if (!line.hertz) continue;
    const HertzContactPatch patch = hertzContactPatch(line.hertz->self, line.hertz->other, force_);
    const double nu = line.hertz->self.poisson_ratio;
    const Eigen::Index n = line.distance.size();
    Eigen::VectorXd vm(n), sr(n), sz(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const HertzAxisStress h =
          hertzAxisStress(line.distance(i), patch.radius, patch.max_pressure, nu);
      vm(i) = h.von_mises, sr(i) = h.sigma_r, sz(i) = h.sigma_z;
    }
    file_.rewrite(g.id(), "hertz_von_mises", vm);
    file_.rewrite(g.id(), "hertz_sigma_radial", sr);
    file_.rewrite(g.id(), "hertz_sigma_axial", sz);
    h5::writeAttribute(c, g.id(), "hertz_contact_radius_m", patch.radius);
    h5::writeAttribute(c, g.id(), "hertz_max_pressure_Pa", patch.max_pressure);
    h5::writeAttribute(c, g.id(), "hertz_von_mises_max_Pa", peak.hertz_von_mises);
    h5::writeAttribute(c, g.id(), "hertz_von_mises_max_depth_m", peak.hertz_depth);
  }
}

void PeakStressLines::finish() {
  if (time_ < 0.0) file_.removeObject("/stress_lines");  // no contact: no group, as documented
}

std::vector<StressLinePeak> PeakStressLines::peaks() const {
  std::vector<StressLinePeak> out;
  if (time_ < 0.0) return out;
  for (const Line& line : lines_) {
    StressLinePeak p;
    p.body = line.body_name;
    p.line = line.source->name;
    const Eigen::Index in = argInteriorMax(line.von_mises);
    if (in >= 0) p.von_mises = line.von_mises(in), p.distance = line.distance(in);
    if (line.hertz) {
      const HertzContactPatch patch = hertzContactPatch(line.hertz->self, line.hertz->other, force_);
      const HertzAxisMaximum hm = hertzAxisMaximum(line.hertz->self.poisson_ratio);
      p.hertz = true;
      p.hertz_von_mises = hm.von_mises_over_p0 * patch.max_pressure;
      p.hertz_depth = hm.depth_over_a * patch.radius;
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace ffriga
