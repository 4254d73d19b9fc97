// igaprep's pipeline from a checked body file to the reduced flexible body (common/sid/sid.h):
//
//   geometry   exact patch, degree elevation, knot insertion          (body_config)
//   assembly   K, M, Ms on the spline space                           (elasticity_assembly)
//   reduction  Craig-Bampton or modal, Buckens or tangent frame       (craig_bampton)
//   invariants mass properties, Ct, Cr0, Cr1, J1, Oe, Me, Ke, De      (sid_invariants)
//   surface    contact surface (Bezier extraction), markers
//
// Each stage is timed (wall clock) into sid.stage_times_s; progress lines go to `log`
// when it is set (igaprep prints them on stderr unless -q).
#pragma once

#include <functional>
#include <string>

#include "common/sid/sid.h"
#include "preproc/input/body_config.h"

namespace ffriga {

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
