#include "preproc/geometry/body_geometry.h"

#include <array>
#include <map>
#include <stdexcept>

#include "common/base/error.h"
#include "common/splines/refinement.h"
#include "preproc/geometry/geometry_builders.h"

namespace ffriga {

namespace {

const char* const kDirectionNames[3] = {"xi", "eta", "zeta"};

}  // namespace

std::string degenerateFace(const NurbsPatch& patch, int dir, bool upper) {
  const Eigen::MatrixXd& X = patch.points();
  const double tol = 1e-12 * (X.colwise().maxCoeff() - X.colwise().minCoeff()).maxCoeff();
  const int d = patch.paramDim();
  std::array<int, 3> n{1, 1, 1};
  for (int a = 0; a < d; ++a) n[a] = patch.numBasis(a);
  const auto same = [&](std::array<int, 3> i, std::array<int, 3> j) {
    return (X.row(patch.linearIndex(i)) - X.row(patch.linearIndex(j))).norm() <= tol;
  };
  const auto allOnFace = [&](const auto& test) {  // test(i) for every i on the face
    std::array<int, 3> lo{0, 0, 0}, hi = n, i{};
    lo[dir] = upper ? n[dir] - 1 : 0;
    hi[dir] = lo[dir] + 1;
    for (i[2] = lo[2]; i[2] < hi[2]; ++i[2])
      for (i[1] = lo[1]; i[1] < hi[1]; ++i[1])
        for (i[0] = lo[0]; i[0] < hi[0]; ++i[0])
          if (!test(i)) return false;
    return true;
  };
  for (int b = 0; b < d; ++b) {
    if (b == dir) continue;
    if (allOnFace([&](std::array<int, 3> i) {
          if (i[b] == 0) return true;
          std::array<int, 3> j = i;
          --j[b];
          return same(i, j);
        })) {
      return Str() << "its control points collapse along " << kDirectionNames[b]
                   << ": an axis, a pole line or a collapsed edge";
    }
  }
  if (allOnFace([&](std::array<int, 3> i) {
        std::array<int, 3> j = i;
        j[dir] = upper ? 0 : n[dir] - 1;
        return same(i, j);
      })) {
    return "it coincides with the opposite face: a closed seam";
  }
  return "";
}

int GeometryConfig::paramDim() const {
  switch (kind) {
    case GeometryKind::kHalfDisk:
      return 2;
    case GeometryKind::kSphere:
    case GeometryKind::kRod:
      return 3;
    case GeometryKind::kNurbs:
      break;
  }
  return patch.paramDim();
}

NurbsPatch exactPatch(const GeometryConfig& g) {
  switch (g.kind) {
    case GeometryKind::kHalfDisk:
      return halfDisk(g.radius);
    case GeometryKind::kSphere:
      return solidSphere(g.radius, g.contact_direction);
    case GeometryKind::kRod:
      return solidRod(g.radius, g.length);
    case GeometryKind::kNurbs:
      break;
  }
  return g.patch;
}

NurbsPatch refinedPatch(const NurbsPatch& exact, const RefinementConfig& r) {
  NurbsPatch patch = exact;
  const int d = patch.paramDim();
  for (int a = 0; a < d && a < static_cast<int>(r.elevate_degree.size()); ++a) {
    if (r.elevate_degree[a] > 0) patch = elevateDegree(patch, a, r.elevate_degree[a]);
  }
  for (int a = 0; a < d && a < static_cast<int>(r.insert_knots.size()); ++a) {
    if (r.insert_knots[a] > 0) {
      patch = insertKnots(patch, a, uniformInsertionKnots(patch.knots(a), r.insert_knots[a]));
    }
  }
  for (int a = 0; a < static_cast<int>(r.insert.size()); ++a) {
    if (!r.insert[a].empty()) {
      try {
        patch = insertKnots(patch, a, r.insert[a]);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(Str() << "direction " << a << ": " << e.what());
      }
    }
  }
  return patch;
}

HierarchicalSpace bodySpace(const NurbsPatch& refined, const HierarchyOptions& hierarchy,
                            bool global_reference) {
  if (global_reference)
    return HierarchicalSpace(globalReferencePatch(refined, hierarchy), HierarchyOptions{});
  return HierarchicalSpace(refined, hierarchy);
}

std::vector<std::vector<int>> tiedControlPoints(const HierarchicalSpace& space) {
  // Degeneracies are read from the THB control points (refined control points of the
  // patch): HB control points of one level can coincide without any degeneracy (functions
  // whose only coarse parent in the region is the same). HB and THB share the active set.
  Eigen::MatrixXd thb;
  if (!space.truncated()) {
    HierarchyOptions o = space.options();
    o.truncated = true;
    thb = HierarchicalSpace(space.basePatch(), o).controlPoints();
  }
  const Eigen::MatrixXd& P = space.truncated() ? space.controlPoints() : thb;
  const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
  std::vector<std::vector<int>> groups;
  for (const auto& g : coincidentPoints(P, 1e-12 * size)) {
    std::map<int, std::vector<int>> byLevel;
    for (int k : g) byLevel[space.functionLevel(k)].push_back(k);
    for (auto& entry : byLevel)
      if (entry.second.size() >= 2) groups.push_back(std::move(entry.second));
  }
  return groups;
}

DofCount countDofs(const HierarchicalSpace& space, bool axisymmetric) {
  const std::vector<std::vector<int>> groups = tiedControlPoints(space);
  const Eigen::MatrixXd& P = space.controlPoints();
  const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).maxCoeff();
  DofCount n;
  n.groups = static_cast<int>(groups.size());
  std::vector<char> tiedAway(P.rows(), 0);
  for (const auto& g : groups) {
    n.tied += static_cast<int>(g.size()) - 1;
    for (std::size_t i = 1; i < g.size(); ++i) tiedAway[g[i]] = 1;
  }
  if (axisymmetric) {
    for (int k = 0; k < P.rows(); ++k) n.on_axis += !tiedAway[k] && P(k, 0) <= 1e-12 * size;
  }
  n.ndof = space.spaceDim() * (space.numFunctions() - n.tied) - n.on_axis;
  return n;
}

}  // namespace ffriga
