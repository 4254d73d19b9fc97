// The sensors of a scene in the result file: `/sensors/<sensor>/position` and `velocity`
// (inertial, m and m/s) at every output time, with the group attribute `marker`
// (BODY.MARKER). Sensors are markers the scene names (schemas/multibody.md).
#pragma once

#include <vector>

#include "runtime/output/output_sink.h"
#include "runtime/output/result_file.h"

namespace ffriga {

class SensorRows : public OutputSink {
 public:
  SensorRows(ResultFile& file, const OutputLayout& layout);
  void write(const OutputSample& sample) override;
  void flush() override {}  // the file writes every series' rows (ResultFile::writeRows)

 private:
  struct Series {
    ResultFile::Series *position, *velocity;
  };
  std::vector<Series> sensors_;
};

}  // namespace ffriga
