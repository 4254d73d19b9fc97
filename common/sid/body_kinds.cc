#include "common/sid/body_kinds.h"

#include "common/base/spelling.h"

namespace ffriga {

namespace {

const Spelling<ModelKind> kModels[] = {{"axisymmetric", ModelKind::kAxisymmetric},
                                       {"solid", ModelKind::kSolid},
                                       {"rigid", ModelKind::kRigid}};
const Spelling<ReductionMethod> kReductions[] = {{"craig_bampton", ReductionMethod::kCraigBampton},
                                                 {"modal", ReductionMethod::kModal},
                                                 {"rigid", ReductionMethod::kRigid},
                                                 {"frozen", ReductionMethod::kFrozen}};
const Spelling<FrameKind> kFrames[] = {{"buckens", FrameKind::kBuckens},
                                       {"tangent", FrameKind::kTangent},
                                       {"centre_of_mass_given", FrameKind::kCentreOfMassGiven}};

}  // namespace

const char* toString(ModelKind model) { return spell(kModels, model); }
const char* toString(ReductionMethod method) { return spell(kReductions, method); }
const char* toString(FrameKind frame) { return spell(kFrames, frame); }
bool parseKind(std::string_view text, ModelKind* model) {
  return parseSpelling(kModels, text, model);
}
bool parseKind(std::string_view text, ReductionMethod* method) {
  return parseSpelling(kReductions, text, method);
}
bool parseKind(std::string_view text, FrameKind* frame) {
  return parseSpelling(kFrames, text, frame);
}

}  // namespace ffriga
