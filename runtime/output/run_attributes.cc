#include "runtime/output/run_attributes.h"

#include <filesystem>
#include <map>

#include "common/base/provenance.h"
#include "common/base/sha256.h"
#include "common/base/version.h"

namespace ffriga {

namespace fs = std::filesystem;

namespace {

std::string absolutePath(const std::string& path) {
  return fs::absolute(path).lexically_normal().string();
}

}  // namespace

void writeRunOrigin(ResultFile& file, const std::string& scene_path,
                    const std::vector<std::string>& sid_files, double end_time,
                    const std::string& overrides) {
  std::string sids;
  for (const std::string& f : sid_files) sids += (f.empty() ? std::string() : absolutePath(f)) + "\n";
  file.setAttribute("scene_path", absolutePath(scene_path));
  file.setAttribute("sid_files", sids);
  file.setAttribute("end_time_s", end_time);
  file.setAttribute("overrides", overrides);
}

void writeRestartCount(ResultFile& file, long restarts, double end_time) {
  file.setAttribute("restarts", restarts);
  file.setAttribute("end_time_s", end_time);
}

void writeProvenance(ResultFile& file, const std::vector<std::string>& body_names,
                     const std::vector<std::string>& sid_files) {
  file.setAttribute("program_version", std::string(kVersion));
  file.setAttribute("git_revision", gitRevision());
  file.setAttribute("dependency_versions", dependencyVersionsText());
  file.setAttribute("threads", static_cast<long>(ompThreads()));
  std::string sums;  // sha256sum's format: `sha256sum -c` checks the SIDs
  std::map<std::string, std::string> hashed;
  for (std::size_t b = 0; b < body_names.size(); ++b) {
    const std::string& f = b < sid_files.size() ? sid_files[b] : "";
    if (f.empty()) continue;
    const std::string path = absolutePath(f);
    auto known = hashed.find(path);  // bodies of one SID file: hashed once
    if (known == hashed.end()) known = hashed.emplace(path, sha256OfFile(f)).first;
    const std::string& sum = known->second;
    const std::string group = "/bodies/" + body_names[b];
    file.setObjectAttribute(group, "sid_file", path);
    file.setObjectAttribute(group, "sid_sha256", sum);
    sums += sum + "  " + path + "\n";
  }
  file.setAttribute("sid_sha256", sums);
}

void writeWarnings(ResultFile& file, const std::vector<std::string>& warnings) {
  if (warnings.empty()) return;
  std::string all;
  for (const std::string& w : warnings) all += (all.empty() ? "" : "\n") + w;
  file.setAttribute("warnings", all);
}

void writeStaticPreload(ResultFile& file, long iterations, double residual, double elastic_force) {
  file.setAttribute("static_preload_iterations", iterations);
  file.setAttribute("static_preload_residual", residual);
  file.setAttribute("static_preload_elastic_force", elastic_force);
}

void writeHertzReference(ResultFile& file, const std::string& pair, const HertzImpact& impact,
                         double approach_speed, double curvature_A, double curvature_B,
                         bool at_root) {
  const std::string group = "/contacts/" + pair;
  const std::pair<const char*, double> values[] = {
      {"hertz_max_force_N", impact.max_force},
      {"hertz_duration_s", impact.duration},
      {"hertz_time_of_max_s", impact.time_of_max},
      {"hertz_approach_speed_m_s", approach_speed},
      {"hertz_max_approach_m", impact.max_approach},
      {"hertz_stiffness_N_m1_5", impact.stiffness},
      {"hertz_effective_mass_kg", impact.effective_mass},
      {"hertz_steady_load_N", impact.preload},
      {"hertz_curvature_A_1_m", curvature_A},
      {"hertz_curvature_B_1_m", curvature_B}};
  for (const auto& [name, v] : values) {
    file.setObjectAttribute(group, name, v);
    if (at_root) file.setAttribute(name, v);
  }
}

void writeHertzComparison(ResultFile& file, double force_vs_hertz, bool contact_ended,
                          double duration_vs_hertz) {
  file.setAttribute("force_vs_hertz", force_vs_hertz);
  if (contact_ended) file.setAttribute("duration_vs_hertz", duration_vs_hertz);
}

}  // namespace ffriga
