// Size and cost of the Cholesky factor of K_ii (the fixed-interface stiffness that the
// Craig-Bampton reduction factorises, preproc/reduction/craig_bampton.h) under CHOLMOD's fill-reducing
// orderings: what one sparse factorisation of a body needs before any solve (issue 10: the
// global reference sphere3d_g5, 161,631 DOFs).
//
//   factor_orderings BODY.yaml
//
// Builds the body's space and stiffness as igaprep does (its elasticity assembly and
// Craig-Bampton interface), then runs CHOLMOD's symbolic analysis only (no numeric
// factorisation) with its default choice and with AMD, METIS and its own nested dissection
// (NESDIS) forced, and prints per ordering the factor's nonzeros (lnz), the entries a
// supernodal factor stores (xsize, what memory it takes) and the flops of one numeric
// factorisation, with the time the analysis took. The last line is the same as JSON.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <cholmod.h>

#include "common/base/error.h"
#include "preproc/input/body_config.h"
#include "preproc/geometry/contact_region.h"
#include "preproc/assembly/dof_map.h"
#include "preproc/assembly/elasticity_assembly.h"

namespace {

using namespace ffriga;

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Pattern of K_ii (upper triangle) in CSC form: the stiffness without the interface DOFs.
struct Pattern {
  int n = 0;
  std::vector<int> outer{0}, inner;
};

Pattern interiorPattern(const SparseMatrix& K, const std::vector<char>& interface) {
  std::vector<int> index(interface.size(), -1);
  Pattern p;
  for (std::size_t j = 0; j < interface.size(); ++j)
    if (!interface[j]) index[j] = p.n++;
  for (int j = 0; j < K.outerSize(); ++j) {
    if (index[j] < 0) continue;
    for (SparseMatrix::InnerIterator it(K, j); it; ++it)
      if (index[it.row()] >= 0) p.inner.push_back(index[it.row()]);
    p.outer.push_back(static_cast<int>(p.inner.size()));
  }
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: factor_orderings BODY.yaml\n");
    return 2;
  }
  try {
    const BodyConfig config = loadBodyConfig(argv[1]);
    if (config.model != ModelKind::kSolid || config.contacts.empty())
      throw InputError(std::string(argv[1]) + ": expected a solid body with a contact region");
    const HierarchicalSpace space = bodySpace(config);
    const DofMap dofs(space, false, tiedControlPoints(space));
    ElasticityModel model;
    model.material = config.material;
    for (int a = 0; a < 3; ++a) model.gauss_points[a] = space.basePatch().degree(a) + 1;
    auto t0 = std::chrono::steady_clock::now();
    const ElasticSystem sys = assembleElasticity(space, dofs, model);
    const double assembly = seconds(t0);
    std::vector<char> interface(dofs.numDofs(), 0);  // every region's points, as igaprep
    for (const ContactConfig& c : config.contacts)
      for (int k : interfaceControlPoints(space, ContactRegion{c.direction, c.upper, c.bounds}))
        for (int d = 0; d < 3; ++d)
          if (dofs.dof(k, d) >= 0) interface[dofs.dof(k, d)] = 1;
    Pattern p = interiorPattern(sys.K, interface);
    std::printf("%s: %d DOFs, K_ii %d x %d with %zu stored entries (upper); assembly %.1f s\n",
                argv[1], dofs.numDofs(), p.n, p.n, p.inner.size(), assembly);
    cholmod_sparse A;
    std::memset(&A, 0, sizeof(A));
    A.nrow = A.ncol = static_cast<std::size_t>(p.n);
    A.nzmax = p.inner.size();
    A.p = p.outer.data();
    A.i = p.inner.data();
    A.stype = 1;
    A.itype = CHOLMOD_INT;
    A.xtype = CHOLMOD_PATTERN;
    A.dtype = CHOLMOD_DOUBLE;
    A.sorted = 1;
    A.packed = 1;
    struct Choice {
      const char* name;
      int ordering;  // -1: CHOLMOD's default strategy
    };
    const Choice choices[] = {{"default", -1},
                              {"AMD", CHOLMOD_AMD},
                              {"METIS", CHOLMOD_METIS},
                              {"NESDIS", CHOLMOD_NESDIS}};
    std::string json = "{\"body\": \"" + std::string(argv[1]) + "\", \"orderings\": [";
    std::printf("%-8s %-8s %12s %12s %12s %10s\n", "asked", "used", "lnz", "xsize", "flops",
                "analysis s");
    for (const Choice& c : choices) {
      cholmod_common common;
      cholmod_start(&common);
      common.print = 0;
      if (c.ordering >= 0) {
        common.nmethods = 1;
        common.method[0].ordering = c.ordering;
      }
      t0 = std::chrono::steady_clock::now();
      cholmod_factor* L = cholmod_analyze(&A, &common);
      const double analysis = seconds(t0);
      if (!L) {  // e.g. CHOLMOD_TOO_LARGE: more entries than its 32-bit indices address
        std::printf("%-8s analysis failed (CHOLMOD status %d%s; lnz %.4g, flops %.4g)\n", c.name,
                    common.status, common.status == CHOLMOD_TOO_LARGE ? ", too large" : "",
                    common.lnz, common.fl);
        cholmod_finish(&common);
        continue;
      }
      const int used = common.method[common.selected].ordering;
      const char* usedName = used == CHOLMOD_AMD      ? "AMD"
                             : used == CHOLMOD_METIS  ? "METIS"
                             : used == CHOLMOD_NESDIS ? "NESDIS"
                                                      : "other";
      const double xsize = L->is_super ? static_cast<double>(L->xsize) : common.lnz;
      std::printf("%-8s %-8s %12.4g %12.4g %12.4g %10.1f\n", c.name, usedName, common.lnz, xsize,
                  common.fl, analysis);
      char row[256];
      std::snprintf(row, sizeof(row),
                    "%s{\"asked\": \"%s\", \"used\": \"%s\", \"lnz\": %.6g, \"xsize\": %.6g, "
                    "\"flops\": %.6g}",
                    json.back() == '[' ? "" : ", ", c.name, usedName, common.lnz, xsize, common.fl);
      json += row;
      cholmod_free_factor(&L, &common);
      cholmod_finish(&common);
    }
    std::printf("%s]}\n", json.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "factor_orderings: %s\n", e.what());
    return 1;
  }
  return 0;
}
