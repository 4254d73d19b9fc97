#include "preproc/bezier_face_extraction.h"

#include <cmath>

#include "common/error.h"
#include "common/refinement.h"

namespace ffriga {

namespace {

struct Direction1D {
  int dir = 0;
  int p = 0;
  std::vector<double> breaks;
  Eigen::MatrixXd T;  // nfine x n
};

Direction1D bezierTransfer(const KnotVector& U, int dir) {
  Direction1D r;
  r.dir = dir;
  r.p = U.degree();
  r.breaks = U.breaks();
  std::vector<double> X;
  for (std::size_t i = 1; i + 1 < r.breaks.size(); ++i) {
    for (int m = U.multiplicity(r.breaks[i]); m < r.p; ++m) X.push_back(r.breaks[i]);
  }
  KnotVector fine;
  r.T = X.empty() ? Eigen::MatrixXd::Identity(U.numBasis(), U.numBasis())
                  : knotInsertionMatrix(U, X, &fine);
  return r;
}

}  // namespace

ContactSurface extractFaceSurface(const TensorSpace& space, const ContactRegion& region,
                                  const std::string& name) {
  const NurbsPatch& patch = space.patch();
  const int d = patch.paramDim();
  FFRIGA_CHECK(static_cast<int>(region.bounds.size()) == d - 1, "region dimension");
  std::vector<Direction1D> dirs;
  for (int a = 0; a < d; ++a) {
    if (a != region.direction) dirs.push_back(bezierTransfer(patch.knots(a), a));
  }
  const int dc = d - 1;
  ContactSurface cs;
  cs.name = name;
  cs.dim = dc;
  for (const auto& D : dirs) cs.degrees.push_back(D.p);
  const int faceIndex = region.upper ? patch.numBasis(region.direction) - 1 : 0;
  const int ne0 = static_cast<int>(dirs[0].breaks.size()) - 1;
  const int ne1 = dc == 2 ? static_cast<int>(dirs[1].breaks.size()) - 1 : 1;
  std::vector<std::array<int, 2>> elements;
  for (int j1 = 0; j1 < ne1; ++j1) {
    for (int j0 = 0; j0 < ne0; ++j0) {
      const int j[2] = {j0, j1};
      bool overlap = true;
      for (int b = 0; b < dc; ++b) {
        const double lo = std::max(dirs[b].breaks[j[b]], region.bounds[b][0]);
        const double hi = std::min(dirs[b].breaks[j[b] + 1], region.bounds[b][1]);
        overlap = overlap && hi > lo;
      }
      if (overlap) elements.push_back({j0, j1});
    }
  }
  const int ne = static_cast<int>(elements.size());
  if (ne == 0) throw InputError("contact.region contains no element of the contact face");
  cs.element_lower.resize(ne, dc);
  cs.element_upper.resize(ne, dc);
  cs.element_level.assign(ne, 0);
  cs.function_offsets.assign(1, 0);
  int nbern = 1;
  for (const auto& D : dirs) nbern *= D.p + 1;
  for (int e = 0; e < ne; ++e) {
    // 1D active functions and their Bernstein coefficients.
    std::vector<std::vector<int>> act(dc);
    for (int b = 0; b < dc; ++b) {
      const int j = elements[e][b];
      cs.element_lower(e, b) = dirs[b].breaks[j];
      cs.element_upper(e, b) = dirs[b].breaks[j + 1];
      for (int k = 0; k < dirs[b].T.cols(); ++k) {
        if (dirs[b].T.block(j * dirs[b].p, k, dirs[b].p + 1, 1).cwiseAbs().maxCoeff() > 0.0)
          act[b].push_back(k);
      }
    }
    const int n1 = dc == 2 ? static_cast<int>(act[1].size()) : 1;
    const int n0 = static_cast<int>(act[0].size());
    Eigen::MatrixXd C(n0 * n1, nbern);
    for (int i1 = 0; i1 < n1; ++i1) {
      for (int i0 = 0; i0 < n0; ++i0) {
        std::array<int, 3> t{0, 0, 0};
        t[region.direction] = faceIndex;
        t[dirs[0].dir] = act[0][i0];
        if (dc == 2) t[dirs[1].dir] = act[1][i1];
        cs.functions.push_back(patch.linearIndex(t));
        for (int q = 0; q < nbern; ++q) {
          const int t0 = q % (dirs[0].p + 1);
          double v = dirs[0].T(elements[e][0] * dirs[0].p + t0, act[0][i0]);
          if (dc == 2) {
            const int t1 = q / (dirs[0].p + 1);
            v *= dirs[1].T(elements[e][1] * dirs[1].p + t1, act[1][i1]);
          }
          C(i0 + n0 * i1, q) = v;
        }
      }
    }
    cs.extraction.push_back(C);
    cs.function_offsets.push_back(static_cast<int>(cs.functions.size()));
  }
  // Orientation at the centre of the first element.
  double xi[3];
  xi[region.direction] = faceCoordinate(space, region);
  for (int b = 0; b < dc; ++b)
    xi[dirs[b].dir] = 0.5 * (cs.element_lower(0, b) + cs.element_upper(0, b));
  const PatchPoint pt = space.evaluate(xi, 1);
  const int s = patch.spaceDim();
  Eigen::MatrixXd J = pt.dx;  // s x d
  const Eigen::MatrixXd Jinv = J.inverse();
  Eigen::VectorXd outward = Jinv.row(region.direction).transpose() * (region.upper ? 1.0 : -1.0);
  Eigen::VectorXd candidate(s);
  if (s == 3) {
    const Eigen::Vector3d t0 = J.col(dirs[0].dir), t1 = J.col(dirs[1].dir);
    candidate = t0.cross(t1);
  } else {
    candidate << J(1, dirs[0].dir), -J(0, dirs[0].dir);
  }
  cs.outward_sign = candidate.dot(outward) >= 0.0 ? 1.0 : -1.0;
  return cs;
}

}  // namespace ffriga
