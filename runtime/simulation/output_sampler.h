// The outputs' view of the multibody system (runtime/output/output_sample.h): its layout, and
// its sample at a state, formed here from the bodies, pairs, joints, force elements and
// sensors so that the outputs need nothing of the system.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "runtime/output/output_sample.h"
#include "runtime/system/multibody_system.h"

namespace ffriga {

OutputLayout outputLayout(const MultibodySystem& system);

// The sample at time t (s) and state y. Evaluates the contact pairs (their closest-point
// searches start from the previous evaluation's results) and, with joints, the constrained
// accelerations: call it once per output row, in the order of the rows.
OutputSample outputSample(MultibodySystem& system, double t, const Eigen::VectorXd& y);

// The bodies' part of the sample at y (no contact or joint evaluation).
std::vector<BodySample> bodySamples(const MultibodySystem& system, const Eigen::VectorXd& y);

// Contact pair c's pressure field of its last right-hand side (SurfaceContact::pressureField;
// no evaluation).
PressureSample pressureSample(const MultibodySystem& system, int c);

}  // namespace ffriga
