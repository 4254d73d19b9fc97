// Cost of evaluating hierarchical NURBS (issue 3; paper Sect. 5, Fig. 9a blames its slower
// hierarchical runtime on evaluating hierarchical NURBS).
//
//   hierarchical_basis [REPEATS]
//
// 1. Basis values and first derivatives (rational, Eq. 4) at 4 x 4 points in every element
//    of the finest level of sphere2d_h6 (nlvl = 6), against the same points in its global
//    reference sphere2d_g6, evaluated (a) through HierarchicalSpace with one level and
//    (b) through TensorSpace. Element lookup is done once, outside the timing (the runtime
//    knows the element of every collocation point). Prints the median over REPEATS runs
//    (default 21) of the cost per point and the ratio hierarchical / global (target <= 1.5).
// 2. Displacement DOFs of all hierarchical models and their global references
//    (countDofs(), as igaprep), next to the paper's Tables 1 and 2.
// The last line is the same data as one JSON object.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "preproc/input/body_config.h"

namespace {

using ffriga::HierarchicalSpace;
using ffriga::PatchBasis;
using ffriga::SplineSpace;

struct Point {
  int element;
  double xi[3];
};

// Median over `repeats` runs of the time per point (ns) of elementBasis(order 1).
double timePerPoint(const SplineSpace& space, const std::vector<Point>& pts, int repeats,
                    double* checksum) {
  PatchBasis out;
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    double sum = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for (const Point& p : pts) {
      space.elementBasis(p.element, p.xi, 1, out);
      sum += out.table(1, 0);
    }
    const auto t1 = std::chrono::steady_clock::now();
    *checksum += sum;
    t.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / pts.size());
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

std::string configPath(const std::string& stem) {
  return std::string(FFRIGA_SOURCE_DIR) + "/configs/bodies/" + stem + ".yaml";
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 21;
  const ffriga::BodyConfig hc = ffriga::loadBodyConfig(configPath("sphere2d_h6"));
  const ffriga::BodyConfig gc = ffriga::loadBodyConfig(configPath("sphere2d_g6"));
  const HierarchicalSpace H = ffriga::bodySpace(hc);
  const HierarchicalSpace G = ffriga::bodySpace(gc);
  const ffriga::TensorSpace T(ffriga::globalReferencePatch(ffriga::refinedPatch(gc), gc.hierarchy));

  std::vector<Point> ph, pg, pt;
  const int finest = H.numLevels() - 1;
  for (int e = 0; e < H.numElements(); ++e) {
    if (H.elementLevel(e) != finest) continue;
    const ffriga::ElementBox box = H.element(e);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        Point p{e,
                {box.lower[0] + (i + 0.5) / 4 * (box.upper[0] - box.lower[0]),
                 box.lower[1] + (j + 0.5) / 4 * (box.upper[1] - box.lower[1]), 0.0}};
        ph.push_back(p);
        p.element = G.findElement(p.xi);
        pg.push_back(p);
        p.element = T.findElement(p.xi);
        pt.push_back(p);
      }
    }
  }
  double checksum = 0.0;
  // Warm-up, then interleaved measurements.
  timePerPoint(H, ph, 2, &checksum);
  timePerPoint(G, pg, 2, &checksum);
  const double th = timePerPoint(H, ph, repeats, &checksum);
  const double tg = timePerPoint(G, pg, repeats, &checksum);
  const double tt = timePerPoint(T, pt, repeats, &checksum);
  std::printf(
      "basis values + first derivatives, finest level of sphere2d_h6 (%zu points in %zu "
      "elements), median of %d runs:\n",
      ph.size(), ph.size() / 16, repeats);
  std::printf("  hierarchical (nlvl = 6)           %8.1f ns/point\n", th);
  std::printf("  global reference, one-level space %8.1f ns/point\n", tg);
  std::printf("  global reference, TensorSpace     %8.1f ns/point\n", tt);
  std::printf("  ratio hierarchical / global       %8.2f (TensorSpace: %.2f), target <= 1.5\n",
              th / tg, th / tt);

  struct Row {
    const char* stem;
    int n;
    int paper_h, paper_g;
  };
  const Row rows[] = {{"sphere2d", 3, 3856, 9216},    {"sphere2d", 4, 2884, 7440},
                      {"sphere2d", 5, 2728, 6726},    {"sphere2d", 6, 1708, 5368},
                      {"sphere3d", 3, 18891, 139431}, {"sphere3d", 4, 14940, 117267},
                      {"sphere3d", 5, 12711, 92823}};
  std::printf("\ndisplacement DOFs (ndof as igaprep counts them) and the paper's Tables 1-2:\n");
  std::printf("  %-9s %5s %12s %12s %7s   %12s %12s %7s\n", "model", "nlvl", "hierarchical",
              "global", "ratio", "paper hier.", "paper glob.", "ratio");
  std::string json = "{\"ns_per_point\": {\"hierarchical\": " + std::to_string(th) +
                     ", \"global\": " + std::to_string(tg) + ", \"tensor\": " + std::to_string(tt) +
                     "}, \"ratio\": " + std::to_string(th / tg) + ", \"ndof\": [";
  bool first = true;
  for (const Row& r : rows) {
    const std::string base = r.stem;
    const ffriga::BodyConfig h =
        ffriga::loadBodyConfig(configPath(base + "_h" + std::to_string(r.n)));
    const ffriga::BodyConfig g =
        ffriga::loadBodyConfig(configPath(base + "_g" + std::to_string(r.n)));
    const int nh = ffriga::countDofs(ffriga::bodySpace(h), h.model == ffriga::ModelKind::kAxisymmetric).ndof;
    const int ng = ffriga::countDofs(ffriga::bodySpace(g), g.model == ffriga::ModelKind::kAxisymmetric).ndof;
    std::printf("  %-9s %5d %12d %12d %7.3f   %12d %12d %7.3f\n", r.stem, r.n, nh, ng,
                double(nh) / ng, r.paper_h, r.paper_g, double(r.paper_h) / r.paper_g);
    json += std::string(first ? "" : ", ") + "{\"model\": \"" + r.stem +
            "\", \"nlvl\": " + std::to_string(r.n) + ", \"hierarchical\": " + std::to_string(nh) +
            ", \"global\": " + std::to_string(ng) +
            ", \"paper_hierarchical\": " + std::to_string(r.paper_h) +
            ", \"paper_global\": " + std::to_string(r.paper_g) + "}";
    first = false;
  }
  json += "]}";
  std::printf("\n%s\n", json.c_str());
  std::fprintf(stderr, "(checksum %.6g)\n", checksum);
  return 0;
}
