// igaprep's pipeline from a checked body file (preproc/input/body_config.h) to the reduced
// flexible body (common/sid/sid.h), in named phases:
//
//   geometry       the (hierarchically) refined spline space and its DOFs
//   assembly       K, M, Ms on it                                  (preproc/assembly/)
//   interface      the Craig-Bampton interface: the union of the contact regions' control
//                  points and the interface markers' (preproc/geometry/contact_region.h)
//   reduction      Craig-Bampton or modal, Buckens or tangent frame (preproc/reduction/)
//   invariants     the body frame, mass properties, Ct, Cr0, Cr1, J1, Oe, Me, Ke, De
//   surface        one contact surface per region (Bezier extraction, collocation
//                  points), the markers
//   visualisation  material and exact geometry for the runtime, the visualisation mesh and
//                  the stress lines with their sampled modes
//
// Each phase is timed (wall clock) into sid.stage_times_s; progress lines go to `log`
// when it is set (igaprep prints them on stderr unless -q).
#pragma once

#include <functional>
#include <string>

#include "common/sid/sid.h"
#include "preproc/input/body_config.h"

namespace ffriga {

// What igaprep prints about the full model beside the SID's figures.
struct PreprocessSummary {
  int ndof = 0;
  int num_control_points = 0;
  int tied_points = 0;
  int fixed_dofs = 0;
  int interface_control_points = 0;
  int interface_dofs = 0;
  double factor_rcond = 0.0;
  int arpack_iterations = 0;
};

FlexibleBodySid preprocessBody(const BodyConfig& config,
                               const std::function<void(const std::string&)>& log,
                               PreprocessSummary* summary);

}  // namespace ffriga
