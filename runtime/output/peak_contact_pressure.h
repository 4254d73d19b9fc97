// The contact pressure field of every contact pair at that pair's own force peak: at the end
// of the step with the pair's largest normal force (over the steps so far, each pair on its
// own), the penalty pressure p_i = c_p max(0, -g_n,i) (Pa, paper Eq. 17) at every collocation
// point of each role, with the point's world position, the target's normal there, its
// collocation weight w_i (m^2) and role (runtime/contact/contact_pressure.h), so that
//   sum_i role_factor p_i w_i n_i   (role 1 with a minus sign)
// is the pair's resultant normal force on body A at that step; a pair with friction also
// gets the tangential traction t_i (Pa) there, which adds sum_i role_factor t_i w_i. Written to the
// result file as /contacts/<pair>/peak_pressure (schemas/result_format.md): created with the sink,
// before the file's SWMR mode (the number of points is fixed at setup), and rewritten in place at
// the flushes after a larger force was seen; a restart keeps the peak recorded before it;
// a pair that never touched has no group at close.
#pragma once

#include <string>
#include <vector>

#include "runtime/output/output_sink.h"
#include "runtime/output/result_file.h"

namespace ffriga {

class PeakContactPressure : public OutputSink {
 public:
  PeakContactPressure(ResultFile& file, const OutputLayout& layout);
  void write(const OutputSample&) override {}
  // The largest force recorded for pair c (N; 0 before any): only a step with a larger one
  // needs its field formed (recordPeak).
  double peakForce(int c) const { return pairs_[c].force; }
  // Pair c's field at the end of a step at time t (s) with normal force `force` (N), larger
  // than peakForce(c).
  void recordPeak(int c, double t, double force, const PressureSample& field);
  // Writes the groups of the pairs recorded since the last write (in place).
  void flush() override;
  // The group of a pair without any peak is removed at close.
  void finish() override;

 private:
  struct Pair {
    std::string group;  // /contacts/<pair>/peak_pressure
    std::vector<int> role;
    Eigen::VectorXd weight;
    double factor = 1.0;
    bool friction = false;            // the traction dataset too
    double time = -1.0, force = 0.0;  // s, N; -1: none yet
    PressureSample field;
    bool pending = false;
  };
  void create(const Pair& p);
  void restore(Pair& p);
  ResultFile& file_;
  std::vector<Pair> pairs_;  // layout order
};

}  // namespace ffriga
