// What igaprep prints (stdout): the refined geometry and hierarchy of a body file (igaprep
// BODY.yaml), the summary of a SID file (--info) and of a preprocessing run, with its wall
// and CPU time and peak memory.
//
// Geometry summary: degrees, elements and control points per direction, per hierarchy
// level the elements and active functions, and the displacement DOFs
//   ndof = s * (active functions - points tied to a coincident one of the same level)
//          - (axisymmetric) distinct control points on the axis (u_r = 0 there).
#pragma once

#include <string>

#include "common/sid/sid.h"
#include "preproc/body_preprocessor.h"
#include "preproc/input/body_config.h"

namespace ffriga {

void printGeometry(const BodyConfig& config, const NurbsPatch& refined, int verbosity);
void printHierarchy(const BodyConfig& config, const HierarchicalSpace& space);
// A designed body's design: each derived number with its reason.
void printDesign(const ImpactDesign& design);
void printSidSummary(const FlexibleBodySid& sid, const std::string& path);
// After writing `output`: model, DOFs, interface, nq, frequencies, mass, the stages' times
// (write_s: writing the file; total_s: the whole run so far).
void printPreprocessSummary(const BodyConfig& config, const FlexibleBodySid& sid,
                            const PreprocessSummary& summary, const std::string& output,
                            double write_s, double total_s);

}  // namespace ffriga
