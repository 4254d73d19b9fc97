// igaprep: from a body file to a reduced flexible body (SID file).
//
//   igaprep BODY.yaml -o BODY.sid.h5 [-q|-v] [--threads N]
//   igaprep BODY.yaml                  (geometry summary only)
//   igaprep --info FILE.sid.h5         (summary of a SID file)
//
// The phases of a run: preproc/igaprep_run.h; the pipeline: preproc/body_preprocessor.h
// (geometry and global refinement, elasticity assembly, Craig-Bampton or modal reduction in
// a Buckens or tangent frame, SID invariants, contact surfaces and markers), then the SID
// file (common/sid/sid_file.h), written atomically. Without -o: the geometry summary
// (preproc/igaprep_report.h).
#include <cmath>
#include <cstdlib>
#include <string>

#include "common/base/cli.h"
#include "preproc/igaprep_run.h"

namespace {

constexpr const char* kUsage = R"(usage: igaprep BODY.yaml -o BODY.sid.h5 [options]
       igaprep BODY.yaml [options]
       igaprep --info FILE.sid.h5

Builds the reduced flexible body of a body file: exact NURBS geometry, global refinement
(degree elevation, uniform then explicit knot insertion), hierarchical refinement
(section 'hierarchy', THB by default), linear elastic assembly, Craig-Bampton or modal
reduction in a Buckens or tangent floating frame, the SID invariants, the contact surface(s)
with its collocation points and the markers, written to one HDF5 file
(schemas/sid_format.md). Without -o, prints the refined geometry and hierarchy only.

options:
  -o, --output FILE  write the SID file (atomically: nothing is left behind on failure)
  --info FILE        print a summary of a SID file and exit
  --set KEY=VALUE    override a key of the body file (repeatable), e.g.
                     --set material.youngs_modulus=2e11 --set refinement.insert_knots.1=30:
                     dotted path, list items by index, a YAML value; checked against the
                     schema like the file, recorded in the SID (/provenance overrides)
  -q, --quiet        print nothing but errors (no progress, no summary)
  -v, --verbose      print more detail
  --threads N        number of OpenMP threads
  --max-memory GIB   refuse bodies whose estimated matrices and factor need more (default:
                     this machine's physical memory)
  -h, --help         show this help and exit
  --version          show the version and exit

Body files: schemas/body.schema.json; examples in configs/bodies/.
Exit codes: 0 success, 2 bad input or usage, 1 failure while computing.
)";


double parseMaxMemory(const char* v) {
  char* end = nullptr;
  const double gib = std::strtod(v, &end);
  if (*end != '\0' || !(gib > 0.0) || !std::isfinite(gib)) {
    throw ffriga::UsageError(ffriga::Str() << "--max-memory expects a number of GiB > 0, found '"
                                           << v << "'");
  }
  return gib;
}

// The command line's run: --info FILE alone, or one body file with or without -o.
ffriga::IgaprepConfig runConfig(const ffriga::CommandLineConfig& o, ffriga::IgaprepConfig c) {
  c.output = o.output;
  c.sets = o.sets;
  c.verbosity = o.verbosity;
  if (!c.info.empty()) {
    if (!o.positional.empty() || !o.output.empty() || !o.sets.empty())
      throw ffriga::UsageError("--info takes one SID file and no other arguments");
    return c;
  }
  if (o.positional.size() != 1) {
    throw ffriga::UsageError(ffriga::Str() << "expected one body file, found "
                                           << o.positional.size() << " arguments (see --help)");
  }
  c.body_file = o.positional[0];
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  return ffriga::runProgram("igaprep", [&]() {
    ffriga::IgaprepConfig config;
    const ffriga::CommandLineConfig o =
        ffriga::parseCommonOptions(argc, argv, [&](char** av, int i, int ac) -> int {
          const std::string a = av[i];
          if (a != "--info" && a != "--max-memory") return 0;
          if (i + 1 >= ac)
            throw ffriga::UsageError(a == "--info" ? "option --info needs a SID file"
                                                   : "option --max-memory needs a value (GiB)");
          if (a == "--info") config.info = av[i + 1];
          if (a == "--max-memory") config.max_memory_gib = parseMaxMemory(av[i + 1]);
          return 2;
        });
    if (ffriga::printHelpOrVersion(o, "igaprep", kUsage)) return 0;
    const ffriga::IgaprepConfig run = runConfig(o, config);
    if (run.info.empty()) ffriga::applyThreads(o.threads);
    return ffriga::IgaprepRun(run).run();
  });
}
