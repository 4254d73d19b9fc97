// Visualisation frames of a run (scene key outputs.visualisation): at every multiple of
// `interval` (at the first output row at or after it), every flexible body whose SID has a
// visualisation mesh (common/sid/sid.h VisualisationMesh) is written to the result file as
//
//   /visualisation/time                  [frames]              s
//   /visualisation/<body>/cells          [cells, 4 | 8]        point numbers (VTK order)
//   /visualisation/<body>/points         [frames, points, 3]   deformed, inertial, m
//   /visualisation/<body>/displacement   [frames, points, 3]   elastic, inertial, m
//   /visualisation/<body>/von_mises      [frames, points]      Pa
//
// points = r_R + A (x0 + m Phi q) with the magnification m (displacement and stress are
// never magnified), displacement = A Phi q, von Mises of sigma = S q (SID stress modes).
// Axisymmetric bodies are drawn as their meridian section (the plane z = 0, x the radius)
// or, with revolve = N >= 3, as the solid of revolution in N hexahedral segments about
// the y axis. Frames are single precision (4 bytes: the picture, not the record; the rows
// of /bodies hold the state in double precision).
//
// Beside the result file RESULT.h5 an XDMF file RESULT.xdmf (runtime/output/xdmf_file.h)
// describes the frames on disk; it is rewritten atomically at every flush, so that it
// always refers to frames that exist. On a restart, frames after the restart time are
// dropped like the rows.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/sid/hdf5_io.h"
#include "runtime/output/output_sink.h"
#include "runtime/output/result_file.h"

namespace ffriga {

struct VisualisationFramesConfig {
  bool enabled = false;
  double interval = 0.0;       // s
  double magnification = 1.0;  // of the elastic displacement in `points`
  int revolve = 0;             // axisymmetric bodies: 0 meridian section, N >= 3 segments
};

// RESULT.xdmf for RESULT.h5 (any other name: the name with .xdmf appended).
std::string xdmfPathFor(const std::string& result_path);

class FrameWriter : public OutputSink {
 public:
  // Creates the group /visualisation of `file` (or, with resume_time >= 0, opens it and
  // drops the frames after resume_time). Bodies without a mesh (rigid bodies) are skipped.
  FrameWriter(ResultFile& file, const OutputLayout& layout, const VisualisationFramesConfig& settings,
              double resume_time);
  ~FrameWriter() override;
  // Whether an output row at time t gets a frame.
  bool due(double t) const;
  // A frame of the sample's bodies if one is due.
  void write(const OutputSample& sample) override;
  // Writes pending frames to the HDF5 file.
  void flush() override;
  // Their bytes (one chunk per frame and dataset).
  std::uint64_t pendingBytes() const override;
  void abandon() override;
  // Rewrites the XDMF file for the frames on disk.
  void afterFlush() override { writeXdmf(); }
  void writeXdmf() const;
  long frames() const { return static_cast<long>(times_.size()); }

 private:
  struct Body;
  void createBody(Body& b, hid_t parent);
  void openBody(Body& b, hid_t parent, long keep);
  // The first multiple of the interval after t (frames fall on the rows at or after it).
  double frameAfter(double t) const;
  std::string path_;
  hid_t file_;
  VisualisationFramesConfig settings_;
  h5::Handle group_, time_;
  std::vector<std::unique_ptr<Body>> bodies_;
  std::vector<double> times_;  // every frame's time, on disk and pending
  long written_ = 0;           // frames on disk
  double next_ = 0.0;          // time of the next frame
};

}  // namespace ffriga
