// igaprep: from a body file to a reduced flexible body.
//
//   igaprep BODY.yaml [-q|-v] [--threads N]
//
// Reads the body file (schemas/body.schema.json), builds the exact NURBS patch, applies
// the global refinement (degree elevation, then uniform and explicit knot insertion) and
// the hierarchical refinement, and prints a summary: degrees, elements and control points
// per direction, per hierarchy level the elements and active functions, coincident
// control points and the displacement DOFs:
//   ndof = s * (active functions - points tied to a coincident one of the same level)
//          - (axisymmetric) distinct control points on the axis (u_r = 0 there).
#include <cstdio>
#include <iostream>

#include "common/cli.h"
#include "common/version.h"
#include "preproc/body_config.h"

namespace {

constexpr const char* kUsage = R"(usage: igaprep BODY.yaml [options]

Builds the exact NURBS model of a flexible body from its body file, refines it
globally (degree elevation, uniform then explicit knot insertion) and hierarchically
(section 'hierarchy'); prints degrees, elements and control points per parametric
direction, elements and active functions per hierarchy level, and the DOFs.

options:
  -q, --quiet        print nothing but errors
  -v, --verbose      print more detail
  --threads N        number of OpenMP threads
  -h, --help         show this help and exit
  --version          show the version and exit

Body files: schemas/body.schema.json; examples in configs/bodies/.
Exit codes: 0 success, 2 bad input or usage, 1 failure while computing.
)";

const char* kDirectionNames[3] = {"xi", "eta", "zeta"};

void printHierarchy(const ffriga::BodyConfig& c, const ffriga::HierarchicalSpace& space) {
  const int s = space.spaceDim();
  if (c.global_reference) {
    std::printf(
        "  global reference of a %d-level hierarchy: knot lines of every level inserted "
        "across the domain\n",
        c.hierarchy.levels);
  }
  std::printf("  hierarchy  %d level(s), %s\n", space.numLevels(),
              space.truncated() ? "truncated (THB)" : "non-truncated (HB)");
  std::printf("  %-6s %9s %18s  %s\n", "level", "elements", "active functions", "region");
  for (int l = 0; l < space.numLevels(); ++l) {
    std::printf("  %-6d %9d %18d  ", l, space.numElementsOnLevel(l), space.numFunctionsOnLevel(l));
    const ffriga::ParamBox box = space.region(l);
    for (int a = 0; a < space.paramDim(); ++a)
      std::printf("%s[%.9g, %.9g]", a ? " x " : "", box.lower[a], box.upper[a]);
    std::printf("\n");
  }
  std::printf("  %-6s %9d %18d\n", "total", space.numElements(), space.numFunctions());
  const ffriga::DofCount n = ffriga::countDofs(space, c.model);
  std::printf("  coincident control points: %d groups (%d points tied to another)\n", n.groups,
              n.tied);
  if (c.model == ffriga::BodyModel::kAxisymmetric) {
    std::printf("  distinct control points on the axis (u_r = 0): %d\n", n.on_axis);
  }
  std::printf("  displacement DOFs: %d x %d functions = %d before tying; ndof = %d\n", s,
              space.numFunctions(), s * space.numFunctions(), n.ndof);
}

void printSummary(const ffriga::BodyConfig& c, const ffriga::NurbsPatch& patch, int verbosity) {
  if (verbosity == 0) return;
  const int d = patch.paramDim();
  std::printf("igaprep %s: body '%s' from %s\n", ffriga::kVersion, c.name.c_str(),
              c.source.path.c_str());
  std::printf("  model      %s, geometry %s\n", ffriga::toString(c.model), c.geometry_type.c_str());
  std::printf("  material   E = %.6g Pa, nu = %.6g, rho = %.6g kg/m^3\n", c.material.youngs_modulus,
              c.material.poisson_ratio, c.material.density);
  std::printf("  %-9s %7s %9s %15s\n", "direction", "degree", "elements", "control points");
  for (int a = 0; a < d; ++a) {
    std::printf("  %-9s %7d %9d %15d\n", kDirectionNames[a], patch.degree(a),
                patch.knots(a).numElements(), patch.numBasis(a));
  }
  std::printf("  %-9s %7s %9d %15d   (level 0)\n", "total", "", patch.numElements(),
              patch.numControlPoints());
  if (verbosity >= 2) {
    for (int a = 0; a < d; ++a) {
      std::printf("  knots %s:", kDirectionNames[a]);
      for (double u : patch.knots(a).knots()) std::printf(" %.6g", u);
      std::printf("\n");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  return ffriga::runProgram("igaprep", [&]() {
    const ffriga::CommonOptions o = ffriga::parseCommonOptions(argc, argv);
    if (o.help) {
      std::cout << kUsage;
      return 0;
    }
    if (o.version) {
      std::cout << "igaprep " << ffriga::kVersion << "\n";
      return 0;
    }
    if (o.positional.size() != 1) {
      throw ffriga::UsageError(ffriga::Str() << "expected one body file, found "
                                             << o.positional.size() << " arguments (see --help)");
    }
    if (!o.output.empty()) {
      throw ffriga::UsageError("-o: writing SID files is not available in this version");
    }
    ffriga::applyThreads(o.threads);
    const ffriga::BodyConfig config = ffriga::loadBodyConfig(o.positional[0]);
    const ffriga::NurbsPatch patch = ffriga::refinedPatch(config);
    printSummary(config, patch, o.verbosity);
    const ffriga::HierarchicalSpace space = ffriga::bodySpace(config);
    if (o.verbosity > 0) printHierarchy(config, space);
    return 0;
  });
}
