// igaprep: from a body file to a reduced flexible body.
//
//   igaprep BODY.yaml [-q|-v] [--threads N]
//
// Reads the body file (schemas/body.schema.json), builds the exact NURBS patch, applies
// the global refinement (degree elevation, then uniform knot insertion) and prints a
// summary: degrees, elements and control points per direction, coincident control points.
#include <cstdio>
#include <iostream>

#include "common/cli.h"
#include "common/version.h"
#include "preproc/body_config.h"

namespace {

constexpr const char* kUsage = R"(usage: igaprep BODY.yaml [options]

Builds the exact NURBS model of a flexible body from its body file and refines it
globally (degree elevation, then uniform knot insertion); prints degrees, elements and
control points per parametric direction.

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
  std::printf("  %-9s %7s %9d %15d\n", "total", "", patch.numElements(), patch.numControlPoints());
  // Coincident control points: absolute tolerance relative to the patch size.
  const double size =
      (patch.points().colwise().maxCoeff() - patch.points().colwise().minCoeff()).maxCoeff();
  const auto groups = ffriga::coincidentControlPoints(patch, 1e-12 * size);
  int tied = 0;
  for (const auto& g : groups) tied += static_cast<int>(g.size()) - 1;
  std::printf("  coincident control points: %zu groups (%d points tied to another)\n",
              groups.size(), tied);
  if (c.model == ffriga::BodyModel::kAxisymmetric) {
    int onAxis = 0;
    for (int k = 0; k < patch.numControlPoints(); ++k)
      onAxis += patch.points()(k, 0) <= 1e-12 * size;
    std::printf("  control points on the axis (u_r = 0): %d\n", onAxis);
  }
  std::printf("  displacement DOFs before tying: %d\n",
              patch.numControlPoints() * patch.spaceDim());
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
    return 0;
  });
}
