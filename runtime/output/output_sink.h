// The one interface through which a run's outputs receive what the simulation computes
// (DESIGN.md "Output"): the rows of the result file, the sensors, the visualisation frames
// for ParaView, the stresses along lines at the force peak and the restart record are each
// a sink. A sink writes into the result file it was given (runtime/output/result_file.h);
// the result writer (runtime/output/result_writer.h) holds the sinks of a run and hands
// every call on, in the order the sinks were added.
#pragma once

#include <cstdint>
#include <vector>

#include "runtime/output/output_sample.h"

namespace ffriga {

class OutputSink {
 public:
  virtual ~OutputSink() = default;
  // One output row (called in increasing time).
  virtual void write(const OutputSample& sample) = 0;
  // A step ending at `time` (s) has the largest contact force so far (N); the bodies' state
  // there. Sinks that record the peak override it.
  virtual void recordPeak(double time, double force, const std::vector<BodySample>& bodies) {
    (void)time, (void)force, (void)bodies;
  }
  // Whether recordPeak is wanted (the simulation forms the bodies' state only then).
  virtual bool wantsPeaks() const { return false; }
  // Bytes the next flush() adds to the file beyond the result file's own series (reserved on
  // disk before it, runtime/output/disk_reservation.h).
  virtual std::uint64_t pendingBytes() const { return 0; }
  // Moves what is pending into the HDF5 file (before the file is flushed).
  virtual void flush() = 0;
  // After the HDF5 file is flushed: files beside it that refer to what is now on disk.
  virtual void afterFlush() {}
  // At close, after the last flush: what the file's SWMR mode does not allow (removals, new
  // attributes) through the result file, which writes it in its closing phase.
  virtual void finish() {}
  // The file's writes failed: forget the HDF5 handles without closing them (closing would
  // write into the file again; runtime/output/result_file.h).
  virtual void abandon() {}
};

}  // namespace ffriga
