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
#include <cstdlib>
#include <string>

#include "common/base/cli.h"
#include "runtime/ffrsim_run.h"

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


double parseEndTime(const std::string& v) {
  char* end = nullptr;
  const double t = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !(t > 0.0) || !std::isfinite(t))
    throw ffriga::UsageError(ffriga::Str() << "--end-time expects a time > 0 s, found '" << v << "'");
  return t;
}

// The command line's run: a scene with -o, or --restart with the result file only.
ffriga::FfrsimConfig runConfig(const ffriga::CommandLineConfig& o, ffriga::FfrsimConfig c) {
  c.verbosity = o.verbosity;
  c.sets = o.sets;
  if (c.restart) {
    if (!o.positional.empty() || !o.output.empty())
      throw ffriga::UsageError("--restart takes the result file only: no scene file, no -o");
    if (!o.sets.empty())
      throw ffriga::UsageError("--set goes with a scene file: a restart continues the run with "
                               "the overrides it had");
    return c;
  }
  if (o.positional.size() != 1) throw ffriga::UsageError("expected one scene file (see --help)");
  if (o.output.empty()) throw ffriga::UsageError("missing -o RESULT.h5 (see --help)");
  if (c.end_time > 0.0) throw ffriga::UsageError("--end-time goes with --restart");
  c.scene_file = o.positional[0];
  c.output = o.output;
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  return ffriga::runProgram("ffrsim", [&]() {
    ffriga::FfrsimConfig config;
    const ffriga::CommandLineConfig o =
        ffriga::parseCommonOptions(argc, argv, [&](char** av, int i, int ac) -> int {
          const std::string a = av[i];
          if (a != "--sid-path" && a != "--restart" && a != "--end-time") return 0;
          if (i + 1 >= ac) throw ffriga::UsageError("option " + a + " needs a value");
          if (a == "--sid-path") config.sid_paths.push_back(av[i + 1]);
          if (a == "--restart") config.output = av[i + 1], config.restart = !config.output.empty();
          if (a == "--end-time") config.end_time = parseEndTime(av[i + 1]);
          return 2;
        });
    ffriga::applyThreads(o.threads);
    if (ffriga::printHelpOrVersion(o, "ffrsim", kUsage)) return 0;
    return ffriga::FfrsimRun(runConfig(o, config)).run();
  });
}
