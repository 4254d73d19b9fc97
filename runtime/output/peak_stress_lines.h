// The stresses along the bodies' stress lines (SID /stress_lines, e.g. the symmetry axis
// under the contact point) at the time of the maximum contact force, with Hertz's field
// (common/mechanics/hertz.h hertzAxisStress, Johnson eq. 3.72) where the body is a Hertz sphere of a
// contact pair and the line starts on its surface and points at its centre. Recovered from
// the reduced model as sigma = S q (S: the SID's stress modes), so exact for it. Written to
// the result file as /stress_lines/<body>/<line> (schemas/result_format.md) whenever a
// larger force was seen since the last write, at the result file's flushes; a restart keeps
// the peak recorded before it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/mechanics/hertz.h"
#include "common/sid/hdf5_io.h"
#include "runtime/output/output_sink.h"
#include "runtime/output/result_file.h"

namespace ffriga {

// A body as one of Hertz's spheres: itself and the other sphere of its contact pair.
struct HertzPartner {
  HertzSphere self{}, other{};
};

// The subsurface maximum of one line at the recorded peak (for ffrsim's summary).
struct StressLinePeak {
  std::string body, line;
  double von_mises = -1.0, distance = -1.0;              // interior maximum, Pa and m
  bool hertz = false;
  double hertz_von_mises = 0.0, hertz_depth = 0.0;       // Pa, m
};

class PeakStressLines : public OutputSink {
 public:
  // partners[b]: body b's Hertz partner, if any (size of layout.bodies, or empty: none).
  PeakStressLines(ResultFile& file, const OutputLayout& layout,
                  std::vector<std::optional<HertzPartner>> partners);
  bool empty() const { return lines_.empty(); }
  void write(const OutputSample&) override {}
  // The bodies' state at time t has the largest contact force so far (N): recover the
  // stresses.
  void recordPeak(double t, double force, const std::vector<BodySample>& bodies) override;
  bool wantsPeaks() const override { return !lines_.empty(); }
  // Writes /stress_lines if something was recorded since the last write (in place: the
  // group is created with the sink, before the file's SWMR mode).
  void flush() override;
  // Without any peak the group is removed at close.
  void finish() override;
  // Every line's interior maximum at the last recorded peak (empty before any record).
  std::vector<StressLinePeak> peaks() const;

 private:
  struct Line {
    int body = 0;
    std::string body_name;
    const StressLine* source = nullptr;  // in the body's SID
    std::optional<HertzPartner> hertz;
    Eigen::VectorXd distance;      // from the line's start, m
    Eigen::MatrixXd stress;        // n x 6, Pa
    Eigen::VectorXd von_mises;     // Pa
  };
  void create();
  void restore();
  ResultFile& file_;
  std::vector<Line> lines_;
  double time_ = -1.0, force_ = 0.0;
  bool pending_ = false;
};

}  // namespace ffriga
