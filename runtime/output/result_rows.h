// The rows of the result file (schemas/result_format.md "Datasets"): at every output time
// the time, each body's frame position, orientation, velocities and elastic coordinates,
// each contact pair's force, penetration and active points, the energies, each joint's
// reaction and violation and each force element's state, with the groups' attributes
// (`/bodies/<body>@model`, `/contacts/<pair>@penalty_factor`, `/joints/<joint>@type`, ...).
#pragma once

#include <vector>

#include "runtime/output/output_sink.h"
#include "runtime/output/result_file.h"

namespace ffriga {

class ResultRows : public OutputSink {
 public:
  // Creates the groups and series of `layout` in `file` (or opens them for a restart).
  ResultRows(ResultFile& file, const OutputLayout& layout);
  void write(const OutputSample& sample) override;
  void flush() override {}  // the file writes every series' rows (ResultFile::writeRows)

 private:
  using Series = ResultFile::Series;
  void createBodies(const OutputLayout& layout);
  void createContacts(const OutputLayout& layout);
  void createEnergies();
  void createJoints(const OutputLayout& layout);
  void createForceElements(const OutputLayout& layout);
  ResultFile& file_;
  Series* time_ = nullptr;
  struct BodySeries {
    Series *position, *orientation, *velocity, *angular_velocity, *q, *qdot;
  };
  std::vector<BodySeries> bodies_;
  struct ContactSeries {
    Series *normal_force, *force, *max_penetration, *active_points, *projection_failures;
    // Pairs with friction only (else null).
    Series *tangential_force = nullptr, *sticking_points = nullptr, *slipping_points = nullptr;
  };
  std::vector<ContactSeries> contacts_;
  struct JointSeries {
    Series *force, *moment, *violation, *quasi_static_offset;
  };
  std::vector<JointSeries> joints_;
  struct ForceElementSeries {
    Series *length, *rate, *tension, *energy;
  };
  std::vector<ForceElementSeries> force_elements_;
  Series *kinetic_ = nullptr, *elastic_ = nullptr, *contact_ = nullptr, *gravity_ = nullptr,
         *force_energy_ = nullptr, *dissipated_ = nullptr;
};

}  // namespace ffriga
