// The kinds a body is described by, from the body file through the SID to the result file:
// its model, the reduction that made its modes and the body frame it uses. Each has one
// spelling table (common/base/spelling.h) in body_kinds.cc; input, SID and result files use
// those words ("axisymmetric", "craig_bampton", "buckens", schemas/sid_format.md).
#pragma once

#include <string_view>

namespace ffriga {

// Elasticity model: axisymmetric (2D meridian section, Sect. 5), solid (3D), or a rigid
// body (scene-defined mass and inertia: no elastic coordinates).
enum class ModelKind { kAxisymmetric, kSolid, kRigid };
// How the elastic modes were made: Craig-Bampton (fixed-interface normal modes and
// constraint modes, Sect. 3.2), free-free normal modes, or none (a rigid body; a SID body
// frozen in the scene).
enum class ReductionMethod { kCraigBampton, kModal, kRigid, kFrozen };
// The body frame: Buckens (mean axes at the centre of mass, Eq. 13), tangent (attached at
// a marker), or a rigid body's frame at its given centre of mass.
enum class FrameKind { kBuckens, kTangent, kCentreOfMassGiven };

const char* toString(ModelKind model);
const char* toString(ReductionMethod method);
const char* toString(FrameKind frame);
// The value spelled `text`; false for a word that names none.
bool parseKind(std::string_view text, ModelKind* model);
bool parseKind(std::string_view text, ReductionMethod* method);
bool parseKind(std::string_view text, FrameKind* frame);

}  // namespace ffriga
