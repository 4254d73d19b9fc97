#include "preproc/assembly/visualisation_mesh.h"

#include <cmath>
#include <map>

#include "common/base/error.h"

namespace ffriga {

namespace {

using ParameterKey = std::array<long long, 3>;

// Parameters rounded to 2^-40 of the range: equal keys for corners shared by elements.
ParameterKey keyOf(const std::array<double, 3>& xi, const std::array<double, 3>& lo,
                   const std::array<double, 3>& range) {
  ParameterKey k{0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    if (range[a] > 0.0) k[a] = std::llround((xi[a] - lo[a]) / range[a] * 1099511627776.0);
  }
  return k;
}

// Corner c of a cell (bit a of c: upper end in direction a) in VTK order: the 2D order
// (0,0), (1,0), (1,1), (0,1) swaps corners 2 and 3 of the lexicographic order.
int vtkCorner(int c) {
  const int inPlane = c & 3, layer = c & 4;
  const int swapped = inPlane == 2 ? 3 : inPlane == 3 ? 2 : inPlane;
  return layer | swapped;
}

}  // namespace

MeshTopology meshTopology(const SplineSpace& space, int subdivisions) {
  FFRIGA_CHECK(subdivisions > 0, "visualisation mesh: subdivisions " << subdivisions);
  const int d = space.paramDim();
  const int ncorner = 1 << d;
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (int e = 0; e < space.numElements(); ++e) {
    const ElementBox b = space.element(e);
    for (int a = 0; a < d; ++a) {
      lo[a] = e == 0 ? b.lower[a] : std::min(lo[a], b.lower[a]);
      hi[a] = e == 0 ? b.upper[a] : std::max(hi[a], b.upper[a]);
    }
  }
  std::array<double, 3> range{0, 0, 0};
  for (int a = 0; a < d; ++a) range[a] = hi[a] - lo[a];

  MeshTopology m;
  std::map<ParameterKey, int> numberOf;
  const int n = subdivisions;
  int cellsPerElement = 1;
  for (int a = 0; a < d; ++a) cellsPerElement *= n;
  m.cells.resize(static_cast<Eigen::Index>(space.numElements()) * cellsPerElement, ncorner);
  Eigen::Index cell = 0;
  for (int e = 0; e < space.numElements(); ++e) {
    const ElementBox b = space.element(e);
    for (int k = 0; k < cellsPerElement; ++k) {
      std::array<int, 3> idx{0, 0, 0};
      for (int a = 0, rest = k; a < d; ++a, rest /= n) idx[a] = rest % n;
      for (int c = 0; c < ncorner; ++c) {
        ParametricPoint p;
        p.element = e;
        for (int a = 0; a < d; ++a) {
          const int i = idx[a] + ((c >> a) & 1);
          p.xi[a] = i == n ? b.upper[a] : b.lower[a] + (b.upper[a] - b.lower[a]) * i / n;
        }
        const auto [it, inserted] =
            numberOf.emplace(keyOf(p.xi, lo, range), static_cast<int>(m.points.size()));
        if (inserted) m.points.push_back(p);
        m.cells(cell, vtkCorner(c)) = it->second;
      }
      ++cell;
    }
  }
  return m;
}

VisualisationMesh visualisationMesh(const SplineSpace& space, int subdivisions,
                                    const Eigen::MatrixXd& Phi, const IsotropicMaterial& material,
                                    bool axisymmetric, const Eigen::VectorXd& origin, double size) {
  VisualisationMesh mesh;
  if (subdivisions <= 0) return mesh;
  MeshTopology t = meshTopology(space, subdivisions);
  mesh.subdivisions = subdivisions;
  mesh.cells = std::move(t.cells);
  mesh.samples = sampleModes(space, t.points, Phi, material, axisymmetric, origin, size);
  return mesh;
}

}  // namespace ffriga
