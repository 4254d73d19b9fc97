#include "runtime/ffrsim_run.h"

#include <cstdio>
#include <filesystem>
#include <utility>

#include "common/base/output_path.h"
#include "common/base/version.h"
#include "common/input/yaml_overrides.h"
#include "common/sid/sid_file.h"
#include "runtime/output/run_attributes.h"
#include "runtime/report/run_summary.h"
#include "runtime/simulation/interrupt.h"
#include "runtime/simulation/output_sampler.h"

namespace ffriga {

namespace {

namespace fs = std::filesystem;

// A restart's scene: as the run had it (its text with its --set, its folder for relative SID
// names, the same SID files), with the new end time and the record's state.
Scene restartScene(const RestartRecord& rec, const FfrsimConfig& config, const SidLoader& load) {
  std::vector<std::string> sid_paths = config.sid_paths;
  for (const std::string& f : rec.sid_files) sid_paths.push_back(fs::path(f).parent_path().string());
  YamlDocument doc = parseYamlText(rec.scene_yaml, rec.scene_path);
  applyOverrides(doc, rec.overrides);  // the run's --set, as it had them
  Scene scene = buildScene(std::move(doc), sid_paths, load);
  for (std::size_t b = 0; b < scene.sid_files.size() && b < rec.sid_files.size(); ++b) {
    std::error_code ec;
    if (!scene.sid_files[b].empty() && !fs::equivalent(scene.sid_files[b], rec.sid_files[b], ec)) {
      throw InputError(Str() << config.output << ": the scene now finds SID file "
                             << scene.sid_files[b] << " where the run used " << rec.sid_files[b]);
    }
  }
  const double end = config.end_time > 0.0 ? config.end_time : rec.end_time;
  if (!(end > rec.time * (1.0 + 1e-12))) {
    throw InputError(Str() << config.output << ": the run is " << rec.status << " and its last "
                           << "row is at t = " << rec.time << " s; nothing to continue up to "
                           << end << " s (give a later --end-time)");
  }
  scene.settings.end_time = end;
  if (rec.state.size() != scene.system->size()) {
    throw InputError(Str() << config.output << ": the restart state has " << rec.state.size()
                           << " entries, the scene's system " << scene.system->size());
  }
  scene.y0 = rec.state;
  return scene;
}

}  // namespace

FfrsimRun::FfrsimRun(FfrsimConfig config) : config_(std::move(config)) {}
FfrsimRun::~FfrsimRun() = default;

int FfrsimRun::run() {
  if (!load()) return 1;
  open();
  attach();
  writer_->startSwmr();  // every object exists: readers may open the file from now on
  return report(integrate());
}

// The output path first (before any work: it can be written and is none of the inputs;
// the SID files are checked as the scene names them, before each is read), then the scene.
// False if a stop was requested while loading.
bool FfrsimRun::load() {
  const char* option = config_.restart ? "--restart" : "-o";
  checkOutputWritable(config_.output, option);
  if (!config_.restart)
    refuseInputAsOutput(config_.output, "-o", config_.scene_file, "the scene file");
  const SidLoader load = [&](const std::string& path, SidContent content) {
    refuseInputAsOutput(config_.output, option, path, "a SID file of the scene");
    return readSid(path, content);
  };
  installInterruptHandler();  // also while loading: a clean stop, exit code 1
  if (config_.restart) {
    record_ = readRestartRecord(config_.output);
    scene_ = restartScene(record_, config_, load);
  } else {
    scene_ = loadScene(config_.scene_file, config_.sid_paths, load, config_.sets);
  }
  if (interruptRequested()) {
    std::fprintf(stderr, "ffrsim: interrupted by %s while loading the scene; %s\n",
                 interruptSignalName().c_str(),
                 config_.restart ? "the result file is unchanged" : "no result written");
    return false;
  }
  scene_.settings.verbosity = config_.verbosity;
  return true;
}

// The result file with the attributes known before the run.
void FfrsimRun::open() {
  writer_ = std::make_unique<ResultWriter>(
      config_.output, outputLayout(*scene_.system), std::string("ffrsim ") + kVersion,
      scene_.doc.text, scene_.flush, config_.restart ? &record_ : nullptr);
  ResultFile& file = writer_->file();
  if (config_.restart) {
    writeRestartCount(file, record_.restarts + 1, scene_.settings.end_time);
  } else {
    writeRunOrigin(file, config_.scene_file, scene_.sid_files, scene_.settings.end_time,
                   overridesText(config_.sets));
    if (config_.verbosity > 0)
      for (const std::string& w : scene_.warnings) std::fprintf(stderr, "ffrsim: warning: %s\n", w.c_str());
    writeWarnings(file, scene_.warnings);
    if (scene_.static_preload)
      writeStaticPreload(file, scene_.preload.iterations, scene_.preload.residual,
                         scene_.preload.elastic_force);
  }
  std::vector<std::string> names;
  for (int b = 0; b < scene_.system->numBodies(); ++b) names.push_back(scene_.system->body(b).name());
  writeProvenance(file, names, scene_.sid_files);
}

// Hertz's prediction for every contact pair of two spheres (attributes of /contacts/<pair>,
// at the root too when the scene has one pair), the stresses along lines with each body's
// Hertz partner, the frames.
void FfrsimRun::attach() {
  const MultibodySystem& sys = *scene_.system;
  hertz_ = hertzReferences(scene_);
  for (int c = 0; c < sys.numContacts(); ++c) {
    if (!hertz_[c]) continue;
    const HertzReference& h = *hertz_[c];
    writeHertzReference(writer_->file(), sys.contact(c).name(), h.impact, h.approach_speed,
                        h.curvatures.A, h.curvatures.B, sys.numContacts() == 1);
  }
  writer_->enablePeakStressLines(hertzPartners(scene_, hertz_));
  if (scene_.visualisation.enabled) writer_->enableFrames(scene_.visualisation);
}

SimulationReport FfrsimRun::integrate() {
  return simulate(*scene_.system, scene_.y0, scene_.settings, *writer_,
                  config_.restart ? &record_ : nullptr);
}

// The comparison with Hertz (one pair with a reference), the file closed, the summary.
int FfrsimRun::report(const SimulationReport& simulation) {
  const RunFigures& figures = simulation.figures;
  if (hertz_.size() == 1 && hertz_[0]) {
    const HertzDifference d = differenceFrom(*hertz_[0], figures);
    writeHertzComparison(writer_->file(), d.force, d.contact_ended, d.duration);
  }
  writer_->close();
  if (config_.verbosity > 0)
    printSummary(scene_, hertz_, figures, writer_->stressLinePeaks(), writer_->frames(),
                 xdmfPathFor(config_.output));
  if (simulation.interrupted) {
    std::fprintf(stderr, "ffrsim: %s; %s holds the results up to then\n", figures.status.c_str(),
                 config_.output.c_str());
    return 1;
  }
  return 0;
}

}  // namespace ffriga
