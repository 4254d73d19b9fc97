// The root and group attributes of a result file that describe the run rather than its rows
// (schemas/result_format.md): where it came from (for a restart), its provenance, warnings
// about the model and the static preload, and Hertz's reference with the comparison.
#pragma once

#include <string>
#include <vector>

#include "common/mechanics/hertz.h"
#include "runtime/output/result_file.h"

namespace ffriga {

// scene_path, sid_files (absolute, one line per body, "" for rigid bodies), end_time_s and
// overrides (one KEY=VALUE per line): what `ffrsim --restart` reads back.
void writeRunOrigin(ResultFile& file, const std::string& scene_path,
                    const std::vector<std::string>& sid_files, double end_time,
                    const std::string& overrides);
// A restarted run: `restarts` so far and the end time it goes to now.
void writeRestartCount(ResultFile& file, long restarts, double end_time);

// program_version, git_revision, dependency_versions, threads and the SID files with their
// SHA-256 (root `sid_sha256` in sha256sum's format; per body /bodies/<body>@sid_file,
// @sid_sha256). sid_files[b]: body b's SID ("" for rigid bodies); a file shared by several
// bodies is hashed once.
void writeProvenance(ResultFile& file, const std::vector<std::string>& body_names,
                     const std::vector<std::string>& sid_files);

// `warnings` (one per line; absent without any).
void writeWarnings(ResultFile& file, const std::vector<std::string>& warnings);
// static_preload_iterations, _residual, _elastic_force (runtime/system/static_preload.h).
void writeStaticPreload(ResultFile& file, long iterations, double residual, double elastic_force);

// Hertz's prediction for a contact pair (attributes hertz_* of /contacts/<pair>, and of the
// root with `at_root`), with the relative curvatures A <= B of its gap (1/m; A = B for
// spheres, A < B an elliptical contact).
void writeHertzReference(ResultFile& file, const std::string& pair, const HertzImpact& impact,
                         double approach_speed, double curvature_A, double curvature_B,
                         bool at_root);
// Root attributes force_vs_hertz and, once the contact ended, duration_vs_hertz (relative).
void writeHertzComparison(ResultFile& file, double force_vs_hertz, bool contact_ended,
                          double duration_vs_hertz);

}  // namespace ffriga
