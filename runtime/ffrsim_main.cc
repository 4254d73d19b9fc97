// ffrsim: flexible bodies in the floating frame of reference with NURBS penalty contact.
//
//   ffrsim SCENE.yaml -o RESULT.h5 [--sid-path DIR]... [-q|-v] [--threads N]
//   ffrsim --restart RESULT.h5 [--end-time T] [--sid-path DIR]...
//
// Loads the scene (schemas/scene.schema.json) and the bodies' SID files, integrates the
// equations of motion (paper Eq. 1) with penalty contact (Sect. 4) by CVODE's BDF method and
// writes the result file (schemas/result_format.md) as the run goes. Ctrl-C, SIGTERM and
// SIGHUP stop the run between steps and leave a complete, readable file whose `status`
// says so.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <iostream>

#include "common/base/cli.h"
#include "common/base/output_path.h"
#include "common/base/provenance.h"
#include "common/base/sha256.h"
#include "common/input/yaml_overrides.h"
#include "common/base/version.h"
#include "runtime/report/hertz_reference.h"
#include "runtime/output/restart_record.h"
#include "runtime/output/result_writer.h"
#include "runtime/scene/scene.h"
#include "runtime/simulation/simulation.h"

#if __has_include("common/sid/sid_file.h")
#include "common/sid/sid_file.h"
#define FFRIGA_HAVE_SID_FILE 1
#endif

namespace {

constexpr const char* kUsage = R"(usage: ffrsim SCENE.yaml -o RESULT.h5 [options]
       ffrsim --restart RESULT.h5 [--end-time T] [options]

Simulates impacts between reduced flexible bodies (SID files written by igaprep) in the
floating frame of reference with penalty contact between NURBS surfaces.

options:
  -o, --output FILE  result file (HDF5, schemas/result_format.md); with the scene key
                     outputs.visualisation, RESULT.h5 gets RESULT.xdmf beside it: the
                     bodies' frames for ParaView (its "XDMF Reader")
  --sid-path DIR     folder to search for SID files named in the scene (repeatable);
                     relative names are tried in the scene's folder first
  --restart FILE     continue the run of result FILE from its last complete row (an
                     interrupted, failed or finished run), appending to FILE; the scene and
                     the SID files are the ones the run used
  --end-time T       with --restart: continue up to T seconds (default: the run's end time)
  --set KEY=VALUE    override a key of the scene file (repeatable), e.g.
                     --set contacts.0.penalty_factor=3e17 --set integrator.end_time=5e-5:
                     dotted path, list items by index, a YAML value; checked against the
                     schema like the file, recorded in the result (attribute overrides)
  -q, --quiet        print nothing but errors
  -v, --verbose      print more detail
  --threads N        number of OpenMP threads
  -h, --help         show this help and exit
  --version          show the version and exit

Scene files: schemas/scene.schema.json. Ctrl-C, SIGTERM or SIGHUP stop the run and keep
the result file (flushed at least every outputs.flush_interval seconds, default 2 s).
Exit codes: 0 success, 2 bad input or usage, 1 failure while computing (or interrupted).
)";

// The SID reader: common/sid/sid_file.h (issue 4) when this source tree has it.
ffriga::FlexibleBodySid loadSid(const std::string& path, ffriga::SidContent content) {
#ifdef FFRIGA_HAVE_SID_FILE
  return ffriga::readSid(path, content);
#else
  throw ffriga::InputError(ffriga::Str() << path << ": this build of ffrsim cannot read SID files "
                                         << "(common/sid/sid_file.h is missing from the source tree)");
#endif
}

// Hertz's prediction for each contact pair of the scene (empty where it has none),
// computed once for the result file and the summary.
using HertzReferences = std::vector<std::optional<ffriga::HertzReference>>;
HertzReferences hertzReferences(const ffriga::Scene& scene) {
  HertzReferences out;
  for (int c = 0; c < scene.system->numContacts(); ++c)
    out.push_back(ffriga::hertzReference(scene, c));
  return out;
}

// The run against Hertz: relative differences of the force peak and, once the contact has
// ended, of its duration.
struct HertzDifference {
  double force = 0.0;
  bool contact_ended = false;
  double duration = 0.0;
};
HertzDifference differenceFrom(const ffriga::HertzReference& h, const ffriga::SimulationReport& r) {
  HertzDifference d;
  d.force = r.max_normal_force / h.impact.max_force - 1.0;
  d.contact_ended = r.contact_begin >= 0.0 && r.contact_end >= 0.0;
  if (d.contact_ended) d.duration = (r.contact_end - r.contact_begin) / h.impact.duration - 1.0;
  return d;
}

void printSummary(const ffriga::Scene& scene, const HertzReferences& hertz,
                  const ffriga::SimulationReport& r) {
  const ffriga::IntegratorStats& s = r.stats;
  std::printf("ffrsim %s: scene '%s': %s\n", ffriga::kVersion, scene.name.c_str(),
              r.status.c_str());
  std::printf("  simulated %.6g s in %.3f s of wall time\n", r.final_time, r.wall_time_s);
  std::printf(
      "  steps %ld, right-hand sides %ld (+%ld for Jacobians), Jacobians %ld,\n"
      "  Newton iterations %ld, error test failures %ld, convergence failures %ld\n",
      s.steps, s.rhs_evals, s.jacobian_rhs_evals, s.jacobian_evals, s.nonlinear_iterations,
      s.error_test_failures, s.convergence_failures);
  std::printf("  %-16s %10s %8s %10s\n", "phase", "wall [s]", "steps", "rhs");
  const ffriga::PhaseStats* p[3] = {&r.before, &r.during, &r.after};
  const char* names[3] = {"before contact", "during contact", "after contact"};
  for (int i = 0; i < 3; ++i)
    std::printf("  %-16s %10.3f %8ld %10ld\n", names[i], p[i]->wall_s, p[i]->steps,
                p[i]->rhs_evals);
  bool hertzPoints = false;
  for (int f = 0; f < scene.system->numLineForces(); ++f)
    hertzPoints = hertzPoints || scene.system->lineForce(f).isContact();
  if (scene.system->numContacts() > 0 || hertzPoints) {
    std::printf("  maximum contact force %.6g N (over the steps and pairs)\n", r.max_normal_force);
  }
  if (r.contact_begin >= 0.0) {
    const double end = r.contact_end >= 0.0 ? r.contact_end : r.final_time;
    std::printf("  contact from %.4g us to %.4g us%s: duration %.4g us\n", 1e6 * r.contact_begin,
                1e6 * end, r.contact_end >= 0.0 ? "" : " (still in contact)",
                1e6 * (end - r.contact_begin));
  }
  for (int c = 0; c < scene.system->numContacts(); ++c) {
    const auto& h = hertz[c];
    if (!h) continue;
    std::printf("  Hertz (approach speed %.4g m/s): maximum force %.6g N, duration %.4g us\n",
                h->approach_speed, h->impact.max_force, 1e6 * h->impact.duration);
    if (scene.system->numContacts() == 1) {
      const HertzDifference d = differenceFrom(*h, r);
      std::printf("  simulation / Hertz: force %+.2f %%", 100.0 * d.force);
      if (d.contact_ended) std::printf(", duration %+.2f %%", 100.0 * d.duration);
      std::printf("\n");
    }
  }
}

// The stresses along the SIDs' lines at the force peak (result file: /stress_lines).
void printStressLinePeaks(const std::vector<ffriga::StressLinePeak>& peaks) {
  for (const ffriga::StressLinePeak& p : peaks) {
    if (p.von_mises < 0.0) continue;
    std::printf("  von Mises on %s/%s at the force peak: %.4g MPa at %.4g um", p.body.c_str(),
                p.line.c_str(), 1e-6 * p.von_mises, 1e6 * p.distance);
    if (p.hertz) {
      std::printf(" (Hertz %.4g MPa at %.4g um: %+.2f %%, %+.2f %%)", 1e-6 * p.hertz_von_mises,
                  1e6 * p.hertz_depth, 100.0 * (p.von_mises / p.hertz_von_mises - 1.0),
                  100.0 * (p.distance / p.hertz_depth - 1.0));
    }
    std::printf("\n");
  }
}

// Command-line options of ffrsim beyond the common ones.
struct RunOptions {
  std::vector<std::string> sid_paths;
  std::string restart;     // --restart RESULT.h5
  double end_time = -1.0;  // --end-time T (s), with --restart
};

double parseEndTime(const std::string& v) {
  char* end = nullptr;
  const double t = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !(t > 0.0) || !std::isfinite(t))
    throw ffriga::UsageError(ffriga::Str() << "--end-time expects a time > 0 s, found '" << v << "'");
  return t;
}

// Phase 1 of a restart: the record, the scene as the run had it (its text, its folder for
// relative SID names, the same SID files) and the new end time.
ffriga::Scene loadRestartScene(const ffriga::RestartRecord& rec, const RunOptions& ro,
                               std::vector<std::string> sid_paths,
                               const ffriga::SidLoader& load) {
  namespace fs = std::filesystem;
  for (const std::string& f : rec.sid_files) sid_paths.push_back(fs::path(f).parent_path().string());
  ffriga::YamlDocument doc = ffriga::parseYamlText(rec.scene_yaml, rec.scene_path);
  ffriga::applyOverrides(doc, rec.overrides);  // the run's --set, as it had them
  ffriga::Scene scene = ffriga::buildScene(std::move(doc), sid_paths, load);
  for (std::size_t b = 0; b < scene.sid_files.size() && b < rec.sid_files.size(); ++b) {
    std::error_code ec;
    if (!scene.sid_files[b].empty() && !fs::equivalent(scene.sid_files[b], rec.sid_files[b], ec)) {
      throw ffriga::InputError(ffriga::Str() << ro.restart << ": the scene now finds SID file "
                                             << scene.sid_files[b] << " where the run used "
                                             << rec.sid_files[b]);
    }
  }
  const double end = ro.end_time > 0.0 ? ro.end_time : rec.end_time;
  if (!(end > rec.time * (1.0 + 1e-12))) {
    throw ffriga::InputError(ffriga::Str()
                             << ro.restart << ": the run is " << rec.status << " and its last row "
                             << "is at t = " << rec.time << " s; nothing to continue up to "
                             << end << " s (give a later --end-time)");
  }
  scene.settings.end_time = end;
  if (rec.state.size() != scene.system->size()) {
    throw ffriga::InputError(ffriga::Str() << ro.restart << ": the restart state has "
                                           << rec.state.size() << " entries, the scene's system "
                                           << scene.system->size());
  }
  scene.y0 = rec.state;
  return scene;
}

// Root attributes a later restart needs: where the scene was, which SIDs, the end time.
void writeRunAttributes(ffriga::ResultWriter& writer, const ffriga::Scene& scene,
                        const std::string& scene_path, const std::vector<std::string>& sets) {
  namespace fs = std::filesystem;
  std::string sids;
  for (const std::string& f : scene.sid_files)
    sids += (f.empty() ? std::string() : fs::absolute(f).lexically_normal().string()) + "\n";
  writer.setAttribute("scene_path", fs::absolute(scene_path).lexically_normal().string());
  writer.setAttribute("sid_files", sids);
  writer.setAttribute("end_time_s", scene.settings.end_time);
  writer.setAttribute("overrides", ffriga::overridesText(sets));
}

// Provenance (schemas/result_format.md): the program, its source revision and libraries,
// the threads, and each SID file with its SHA-256 (rewritten by a restart: the program
// that continued the run).
void writeProvenance(ffriga::ResultWriter& writer, const ffriga::Scene& scene) {
  namespace fs = std::filesystem;
  writer.setAttribute("program_version", std::string(ffriga::kVersion));
  writer.setAttribute("git_revision", ffriga::gitRevision());
  writer.setAttribute("dependency_versions", ffriga::dependencyVersionsText());
  writer.setAttribute("threads", static_cast<long>(ffriga::ompThreads()));
  std::string sums;  // sha256sum's format: `sha256sum -c` checks the SIDs
  std::map<std::string, std::string> hashed;
  for (int b = 0; b < scene.system->numBodies(); ++b) {
    const std::string& f = b < static_cast<int>(scene.sid_files.size()) ? scene.sid_files[b] : "";
    if (f.empty()) continue;
    const std::string path = fs::absolute(f).lexically_normal().string();
    auto known = hashed.find(path);  // bodies of one SID file: hashed once
    if (known == hashed.end()) known = hashed.emplace(path, ffriga::sha256OfFile(f)).first;
    const std::string& sum = known->second;
    const std::string group = "/bodies/" + scene.system->body(b).name();
    writer.setObjectAttribute(group, "sid_file", path);
    writer.setObjectAttribute(group, "sid_sha256", sum);
    sums += sum + "  " + path + "\n";
  }
  writer.setAttribute("sid_sha256", sums);
}

// Hertz's prediction for every contact pair of two spheres (attributes of
// /contacts/<pair>), at the root too when the scene has one pair; each body's Hertz
// partner for the stresses along its lines.
std::vector<std::optional<ffriga::HertzPartner>> writeHertzReferences(ffriga::ResultWriter& writer,
                                                                      const ffriga::Scene& scene,
                                                                      const HertzReferences& hertz) {
  const ffriga::MultibodySystem& sys = *scene.system;
  std::vector<std::optional<ffriga::HertzPartner>> partners(sys.numBodies());
  for (int c = 0; c < sys.numContacts(); ++c) {
    const auto& h = hertz[c];
    if (!h) continue;
    const std::string group = "/contacts/" + sys.contact(c).name();
    const std::pair<const char*, double> values[] = {
        {"hertz_max_force_N", h->impact.max_force},
        {"hertz_duration_s", h->impact.duration},
        {"hertz_time_of_max_s", h->impact.time_of_max},
        {"hertz_approach_speed_m_s", h->approach_speed},
        {"hertz_max_approach_m", h->impact.max_approach},
        {"hertz_stiffness_N_m1_5", h->impact.stiffness},
        {"hertz_effective_mass_kg", h->impact.effective_mass}};
    for (const auto& [name, v] : values) {
      writer.setObjectAttribute(group, name, v);
      if (sys.numContacts() == 1) writer.setAttribute(name, v);
    }
    const int a = sys.contact(c).bodyA(), b = sys.contact(c).bodyB();
    if (!partners[a]) partners[a] = ffriga::HertzPartner{h->sphere_a, h->sphere_b};
    if (!partners[b]) partners[b] = ffriga::HertzPartner{h->sphere_b, h->sphere_a};
  }
  return partners;
}

// Root attributes force_vs_hertz and duration_vs_hertz (one contact pair with a Hertz
// reference).
void writeHertzComparison(ffriga::ResultWriter& writer, const HertzReferences& hertz,
                          const ffriga::SimulationReport& r) {
  if (hertz.size() != 1 || !hertz[0]) return;
  const HertzDifference d = differenceFrom(*hertz[0], r);
  writer.setAttribute("force_vs_hertz", d.force);
  if (d.contact_ended) writer.setAttribute("duration_vs_hertz", d.duration);
}

void writeModelAttributes(ffriga::ResultWriter& writer, const ffriga::Scene& scene, int verbosity) {
  if (!scene.warnings.empty()) {
    std::string all;
    for (const std::string& w : scene.warnings) {
      if (verbosity > 0) std::fprintf(stderr, "ffrsim: warning: %s\n", w.c_str());
      all += (all.empty() ? "" : "\n") + w;
    }
    writer.setAttribute("warnings", all);
  }
  if (scene.static_preload) {
    writer.setAttribute("static_preload_iterations", static_cast<long>(scene.preload.iterations));
    writer.setAttribute("static_preload_residual", scene.preload.residual);
    writer.setAttribute("static_preload_elastic_force", scene.preload.elastic_force);
  }
}

}  // namespace

int main(int argc, char** argv) {
  return ffriga::runProgram("ffrsim", [&]() {
    RunOptions ro;
    const ffriga::CommonOptions o =
        ffriga::parseCommonOptions(argc, argv, [&](char** av, int i, int ac) -> int {
          const std::string a = av[i];
          if (a != "--sid-path" && a != "--restart" && a != "--end-time") return 0;
          if (i + 1 >= ac) throw ffriga::UsageError("option " + a + " needs a value");
          if (a == "--sid-path") ro.sid_paths.push_back(av[i + 1]);
          if (a == "--restart") ro.restart = av[i + 1];
          if (a == "--end-time") ro.end_time = parseEndTime(av[i + 1]);
          return 2;
        });
    ffriga::applyThreads(o.threads);
    if (o.help) {
      std::cout << kUsage;
      return 0;
    }
    if (o.version) {
      std::cout << ffriga::versionLine("ffrsim") << "\n";
      return 0;
    }
    const bool restart = !ro.restart.empty();
    if (restart) {
      if (!o.positional.empty() || !o.output.empty())
        throw ffriga::UsageError("--restart takes the result file only: no scene file, no -o");
      if (!o.sets.empty())
        throw ffriga::UsageError("--set goes with a scene file: a restart continues the run with "
                                 "the overrides it had");
    } else {
      if (o.positional.size() != 1) throw ffriga::UsageError("expected one scene file (see --help)");
      if (o.output.empty()) throw ffriga::UsageError("missing -o RESULT.h5 (see --help)");
      if (ro.end_time > 0.0) throw ffriga::UsageError("--end-time goes with --restart");
    }
    const std::string output = restart ? ro.restart : o.output;
    // Before any work: the result can be written, and it is none of the inputs (the SID
    // files are checked as the scene names them, before each is read).
    ffriga::checkOutputWritable(output, restart ? "--restart" : "-o");
    if (!restart) ffriga::refuseInputAsOutput(output, "-o", o.positional[0], "the scene file");
    auto guardedLoadSid = [&](const std::string& path, ffriga::SidContent content) {
      ffriga::refuseInputAsOutput(output, restart ? "--restart" : "-o", path,
                                  "a SID file of the scene");
      return loadSid(path, content);
    };
    ffriga::installInterruptHandler();  // also while loading: a clean stop, exit code 1
    ffriga::RestartRecord record;
    if (restart) record = ffriga::readRestartRecord(output);
    ffriga::Scene scene = restart ? loadRestartScene(record, ro, ro.sid_paths, guardedLoadSid)
                                  : ffriga::loadScene(o.positional[0], ro.sid_paths, guardedLoadSid,
                                                      o.sets);
    if (ffriga::interruptRequested()) {
      std::fprintf(stderr, "ffrsim: interrupted by %s while loading the scene; %s\n",
                   ffriga::interruptSignalName().c_str(),
                   restart ? "the result file is unchanged" : "no result written");
      return 1;
    }
    scene.settings.verbosity = o.verbosity;
    ffriga::ResultWriter writer(output, *scene.system, std::string("ffrsim ") + ffriga::kVersion,
                                scene.doc.text, scene.flush_rows, scene.flush_interval,
                                restart ? &record : nullptr);
    if (restart) {
      writer.setAttribute("restarts", record.restarts + 1);
      writer.setAttribute("end_time_s", scene.settings.end_time);
    } else {
      writeRunAttributes(writer, scene, o.positional[0], o.sets);
      writeModelAttributes(writer, scene, o.verbosity);
    }
    writeProvenance(writer, scene);
    const HertzReferences hertz = hertzReferences(scene);
    writer.enablePeakStressLines(*scene.system, writeHertzReferences(writer, scene, hertz));
    if (scene.visualisation.enabled) writer.enableFrames(scene.visualisation, *scene.system);
    const ffriga::SimulationReport r = ffriga::simulate(*scene.system, scene.y0, scene.settings,
                                                        writer, restart ? &record : nullptr);
    writeHertzComparison(writer, hertz, r);
    writer.close();
    if (o.verbosity > 0) printSummary(scene, hertz, r);
    if (o.verbosity > 0) printStressLinePeaks(writer.stressLinePeaks());
    if (o.verbosity > 0 && writer.frames() > 0) {
      std::printf("  %ld visualisation frames: open %s in ParaView\n", writer.frames(),
                  ffriga::xdmfPathFor(output).c_str());
    }
    if (r.interrupted) {
      std::fprintf(stderr, "ffrsim: %s; %s holds the results up to then\n", r.status.c_str(),
                   output.c_str());
      return 1;
    }
    return 0;
  });
}
