// The multibody system's state y as its force elements see it (runtime/forces/force_element.h
// ForceContext): each body's share of y and its pose, formed on first use and kept for the
// evaluation.
#pragma once

#include <optional>
#include <vector>

#include "runtime/system/multibody_system.h"

namespace ffriga {

class SystemState : public ForceContext {
 public:
  SystemState(const MultibodySystem& system, const double* y)
      : system_(system), y_(y), poses_(system.numBodies()) {}
  const BodyModel& body(int b) const override { return system_.body(b); }
  const double* positions(int b) const override { return y_ + system_.positionOffset(b); }
  const double* velocities(int b) const override { return y_ + system_.velocityOffset(b); }
  const BodyPose& pose(int b) const override {
    if (!poses_[b]) poses_[b] = system_.body(b).pose(positions(b));
    return *poses_[b];
  }
  const double* anchors(int slot) const override {
    return system_.contact(slot).numAnchors() > 0 ? y_ + system_.anchorOffset(slot) : nullptr;
  }

 private:
  const MultibodySystem& system_;
  const double* y_;
  mutable std::vector<std::optional<BodyPose>> poses_;
};

}  // namespace ffriga
