#include "preproc/igaprep_run.h"

#include <cstdio>
#include <iostream>
#include <utility>

#include "common/base/output_path.h"
#include "common/sid/sid_file.h"
#include "preproc/body_preprocessor.h"
#include "preproc/geometry/size_estimate.h"
#include "preproc/igaprep_report.h"
#include "preproc/input/body_config.h"

namespace ffriga {

namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

// -v: the size estimate against the limit, on stderr.
void logSizeEstimate(const BodyConfig& config, double limit) {
  const SizeEstimate size =
      config.global_reference
          ? estimateGlobalReferenceSize(refinedPatch(config), config.hierarchy)
          : estimateSize(exactPatch(config.geometry), config.refinement);
  std::fprintf(stderr,
               "igaprep: size estimate: %.4g control points, %.4g DOFs, %.4g entries of K, "
               "at least %.4g GiB (limit %.4g GiB)\n",
               size.control_points, size.dofs, size.nonzeros, size.bytes / kGiB, limit / kGiB);
}

}  // namespace

IgaprepRun::IgaprepRun(IgaprepConfig config)
    : config_(std::move(config)), start_(std::chrono::steady_clock::now()) {}

int IgaprepRun::run() {
  if (!config_.info.empty()) {
    printSidSummary(readSid(config_.info), config_.info);
    return 0;
  }
  if (!config_.output.empty()) {  // before any work
    checkOutputWritable(config_.output, "-o");
    refuseInputAsOutput(config_.output, "-o", config_.body_file, "the body file");
  }
  const double limit =
      config_.max_memory_gib > 0.0 ? config_.max_memory_gib * kGiB : physicalMemoryBytes();
  // The size estimate is checked while loading, before the refinement allocates.
  const BodyConfig config = loadBodyConfig(config_.body_file, limit, config_.sets);
  if (config_.verbosity > 1) logSizeEstimate(config, limit);
  if (config_.output.empty()) {
    printGeometry(config, refinedPatch(config), config_.verbosity);
    if (config_.verbosity > 0 && config.design) printDesign(*config.design);
    if (config_.verbosity > 0) printHierarchy(config, bodySpace(config));
    return 0;
  }
  auto log = [&](const std::string& line) {
    if (config_.verbosity > 0) std::cerr << "igaprep: " << line << std::endl;
  };
  auto elapsed = [&]() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  };
  PreprocessSummary summary;
  FlexibleBodySid sid = preprocessBody(config, log, &summary);
  sid.preprocessing_time_s = elapsed();
  const double beforeWrite = elapsed();
  writeSid(sid, config_.output);
  const double writeTime = elapsed() - beforeWrite;
  log(Str() << "write: " << config_.output << " (" << writeTime << " s)");
  if (config_.verbosity > 0)
    printPreprocessSummary(config, sid, summary, config_.output, writeTime, elapsed());
  return 0;
}

}  // namespace ffriga
