#include "preproc/assembly/elasticity_assembly.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <omp.h>

#include "common/base/error.h"
#include "common/splines/gauss_legendre.h"
#include "preproc/assembly/strain_operator.h"

namespace ffriga {

namespace {

const double kTwoPi = 2.0 * std::acos(-1.0);

// Upper-triangular (row <= column) sparsity pattern of a symmetric matrix whose columns are
// numbered by `index(node, component)` (< 0: absent), from the node adjacency.
SparseMatrix buildPattern(const std::vector<std::vector<int>>& adjacency, int components, int size,
                          const std::vector<int>& index) {
  std::vector<int> outer(1, 0);
  std::vector<int> inner;
  const int nodes = static_cast<int>(adjacency.size());
  for (int b = 0; b < nodes; ++b) {
    for (int cb = 0; cb < components; ++cb) {
      const int col = index[b * components + cb];
      if (col < 0) continue;
      FFRIGA_ASSERT(col == static_cast<int>(outer.size()) - 1, "column order");
      for (int a : adjacency[b]) {
        if (a > b) break;
        for (int ca = 0; ca < components; ++ca) {
          const int row = index[a * components + ca];
          if (row < 0 || row > col) continue;
          inner.push_back(row);
        }
      }
      outer.push_back(static_cast<int>(inner.size()));
    }
  }
  FFRIGA_CHECK(static_cast<int>(outer.size()) == size + 1,
               "pattern has " << outer.size() - 1 << " columns, expected " << size);
  std::vector<double> values(inner.size(), 0.0);
  return Eigen::Map<const SparseMatrix>(size, size, static_cast<int>(inner.size()), outer.data(),
                                        inner.data(), values.data());
}

// Adds v at (row, col), row <= col, of a compressed pattern.
inline void addAt(SparseMatrix& A, int row, int col, double v) {
  const int* inner = A.innerIndexPtr();
  const int begin = A.outerIndexPtr()[col];
  const int end = A.outerIndexPtr()[col + 1];
  const int pos = static_cast<int>(std::lower_bound(inner + begin, inner + end, row) - inner);
  FFRIGA_ASSERT(pos < end && inner[pos] == row, "entry (" << row << ", " << col << ") missing");
  A.valuePtr()[pos] += v;
}

// What the quadrature of one element leaves for the scatter.
struct ElementMatrices {
  std::vector<int> functions;  // control points of the element's basis functions
  Eigen::MatrixXd Ke, Me;      // (components * nb)^2 and nb^2, local order (j, c) -> j * s + c
  bool singular = false;       // det J = 0 (or not finite) at a Gauss point
};

// Scratch space of one thread.
struct QuadratureWork {
  PatchBasis basis;
  // Gauss points x nb, scaled by (w detJ [2 pi r])^(1/2): G[c] physical gradients d/dx_c,
  // axisymmetric G[2] = R / r (the hoop strain; strain_operator.h isotropicStiffness).
  Eigen::MatrixXd G[3];
  Eigen::MatrixXd N;  // Gauss points x nb, scaled values (rho w detJ)^(1/2) R
};

struct QuadratureSetup {
  int d = 0, s = 0, ng = 0;
  std::array<QuadratureRule, 3> rules;
  IsotropicMaterial material;
};

// Phase 1 of an element: the scaled values and physical gradients at its Gauss points.
void gaussPointTables(const SplineSpace& space, const ElasticityModel& model,
                      const QuadratureSetup& q, int e, QuadratureWork& w, ElementMatrices& out) {
  const int d = q.d, s = q.s, ng = q.ng;
  const Eigen::MatrixXd& P = space.controlPoints();
  const ElementBox box = space.element(e);
  int nb = -1;
  for (int g = 0; g < ng; ++g) {
    double xi[3] = {0, 0, 0};
    double weight = 1.0;
    int rest = g;
    for (int a = 0; a < d; ++a) {
      const int i = rest % model.gauss_points[a];
      rest /= model.gauss_points[a];
      const double h = 0.5 * (box.upper[a] - box.lower[a]);
      xi[a] = box.lower[a] + h * (q.rules[a].points[i] + 1.0);
      weight *= h * q.rules[a].weights[i];
    }
    space.elementBasis(e, xi, 1, w.basis);
    if (nb < 0) {
      nb = static_cast<int>(w.basis.index.size());
      out.functions = w.basis.index;
      for (int c = 0; c < 3; ++c) w.G[c].setZero(ng, nb);
      w.N.setZero(ng, nb);
    }
    const Eigen::MatrixXd& R = w.basis.table;  // rows: value, d/dxi_a
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    if (s == 2) J(2, 2) = 1.0;  // 2D: the 2 x 2 map embedded
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int j = 0; j < nb; ++j) {
      const int k = out.functions[j];
      for (int c = 0; c < s; ++c) {
        x(c) += R(0, j) * P(k, c);
        for (int a = 0; a < d; ++a) J(c, a) += R(1 + a, j) * P(k, c);
      }
    }
    const double det = J.determinant();
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) {
      out.singular = true;
      return;
    }
    const Eigen::Matrix3d Jinv = J.inverse();
    double dV = std::abs(det) * weight;
    if (model.axisymmetric) dV *= kTwoPi * x(0);
    const double sq = std::sqrt(dV);
    // Physical gradients: grad R = J^{-T} dR/dxi.
    for (int c = 0; c < s; ++c) {
      for (int j = 0; j < nb; ++j) {
        double v = 0.0;
        for (int a = 0; a < d; ++a) v += Jinv(a, c) * R(1 + a, j);
        w.G[c](g, j) = sq * v;
      }
    }
    w.N.row(g) = std::sqrt(model.material.density * dV) * R.row(0);
    // Gauss points are interior: r > 0.
    if (model.axisymmetric) w.G[2].row(g) = (sq / x(0)) * R.row(0);
  }
}

// Phase 2: element stiffness K_e = sum_g B_g^T D B_g (strain_operator.h, factored form)
// and the scalar mass matrix.
void elementMatrices(const ElasticityModel& model, const QuadratureSetup& q, QuadratureWork& w,
                     ElementMatrices& out) {
  isotropicStiffness(w.G, q.material, model.axisymmetric, out.Ke);
  out.Me.noalias() = w.N.transpose() * w.N;
}

// Phase 3: adds the element's matrices into the upper triangles of K and Ms, only the
// columns whose node lies in [node_begin, node_end): each thread owns a range of columns,
// and every entry receives its element contributions in element order, whatever the number
// of threads (bitwise reproducible sums).
void scatterOwnedColumns(const ElementMatrices& em, const DofMap& dofs, int s, int node_begin,
                         int node_end, ElasticSystem& sys) {
  const int nb = static_cast<int>(em.functions.size());
  for (int b = 0; b < nb; ++b) {
    const int kb = em.functions[b];
    const int nbd = dofs.node(kb);
    if (nbd < node_begin || nbd >= node_end) continue;
    for (int a = 0; a < nb; ++a) {
      const int ka = em.functions[a];
      const int nad = dofs.node(ka);
      if (nad <= nbd) addAt(sys.Ms, nad, nbd, em.Me(a, b));
      for (int cb = 0; cb < s; ++cb) {
        const int col = dofs.dof(kb, cb);
        if (col < 0) continue;
        for (int ca = 0; ca < s; ++ca) {
          const int row = dofs.dof(ka, ca);
          if (row < 0 || row > col) continue;
          addAt(sys.K, row, col, em.Ke(a * s + ca, b * s + cb));
        }
      }
    }
  }
}

// The node adjacency: for every node the nodes that share an element with it (sorted),
// from the functions of each element (constant on an element, taken at its centre).
std::vector<std::vector<int>> nodeAdjacency(const SplineSpace& space, const DofMap& dofs) {
  const int d = space.paramDim();
  const int ncp = space.numFunctions();
  const int ne = space.numElements();
  std::vector<std::vector<int>> elementNodes(ne);
  std::vector<std::vector<int>> nodeElements(ncp);
  PatchBasis basis;
  for (int e = 0; e < ne; ++e) {
    const ElementBox box = space.element(e);
    double xi[3];
    for (int a = 0; a < d; ++a) xi[a] = 0.5 * (box.lower[a] + box.upper[a]);
    space.elementBasis(e, xi, 0, basis);
    for (int k : basis.index) elementNodes[e].push_back(dofs.node(k));
    std::sort(elementNodes[e].begin(), elementNodes[e].end());
    elementNodes[e].erase(std::unique(elementNodes[e].begin(), elementNodes[e].end()),
                          elementNodes[e].end());
    for (int n : elementNodes[e]) nodeElements[n].push_back(e);
  }
  std::vector<std::vector<int>> adjacency(ncp);
#pragma omp parallel for schedule(dynamic, 64)
  for (int n = 0; n < ncp; ++n) {
    auto& adj = adjacency[n];
    for (int e : nodeElements[n])
      adj.insert(adj.end(), elementNodes[e].begin(), elementNodes[e].end());
    std::sort(adj.begin(), adj.end());
    adj.erase(std::unique(adj.begin(), adj.end()), adj.end());
  }
  return adjacency;
}

// The pattern of K: the node adjacency with the DOFs of each node (the nodes' own points).
SparseMatrix stiffnessPattern(const std::vector<std::vector<int>>& adjacency, const DofMap& dofs,
                              int ncp, int s) {
  std::vector<int> dofIndex(static_cast<std::size_t>(ncp) * s);
  for (int k = 0; k < ncp; ++k) {
    for (int c = 0; c < s; ++c) dofIndex[k * s + c] = dofs.node(k) == k ? dofs.dof(k, c) : -1;
  }
  return buildPattern(adjacency, s, dofs.numDofs(), dofIndex);
}

// The pattern of Ms: the same node adjacency with one component; columns of tied points
// stay empty.
SparseMatrix scalarMassPattern(const std::vector<std::vector<int>>& adjacency, const DofMap& dofs,
                               int ncp) {
  std::vector<int> outer(ncp + 1, 0), inner;
  for (int b = 0; b < ncp; ++b) {
    if (dofs.node(b) == b) {
      for (int a : adjacency[b]) {
        if (a > b) break;
        inner.push_back(a);
      }
    }
    outer[b + 1] = static_cast<int>(inner.size());
  }
  std::vector<double> values(inner.size(), 0.0);
  return Eigen::Map<const SparseMatrix>(ncp, ncp, static_cast<int>(inner.size()), outer.data(),
                                        inner.data(), values.data());
}

// Gauss-Legendre rules on [-1, 1] per direction and the material, for every element.
QuadratureSetup quadratureSetup(const ElasticityModel& model, int d, int s) {
  std::array<QuadratureRule, 3> rules;
  int ng = 1;
  for (int a = 0; a < d; ++a) {
    FFRIGA_CHECK(model.gauss_points[a] >= 1, "gauss_points[" << a << "] must be >= 1");
    rules[a] = gaussLegendre(model.gauss_points[a]);
    ng *= model.gauss_points[a];
  }
  const IsotropicMaterial& material = model.material;
  QuadratureSetup setup;
  setup.d = d;
  setup.s = s;
  setup.ng = ng;
  setup.rules = rules;
  setup.material = material;
  return setup;
}

// K and Ms: the element matrices, then their scatter into the patterns. Throws ComputeError
// if the geometry map is singular at a Gauss point.
void assembleElements(const SplineSpace& space, const DofMap& dofs, const ElasticityModel& model,
                      const QuadratureSetup& setup, ElasticSystem& sys) {
  const int ncp = space.numFunctions();
  const int ne = space.numElements();
  // Elements in chunks of a fixed size (independent of the thread count): the element
  // matrices of a chunk are computed in parallel, then scattered by column owners.
  // 256 elements of degree 2 in 3D hold 15 MB of element matrices (84 MB for degree 3).
  const int chunk = 256;
  std::vector<ElementMatrices> em(static_cast<std::size_t>(std::min(chunk, std::max(ne, 1))));
  int singular = -1;
  for (int e0 = 0; e0 < ne && singular < 0; e0 += chunk) {
    const int count = std::min(chunk, ne - e0);
#pragma omp parallel
    {
      QuadratureWork w;
#pragma omp for schedule(dynamic, 8)
      for (int i = 0; i < count; ++i) {
        em[i].singular = false;
        gaussPointTables(space, model, setup, e0 + i, w, em[i]);
        if (!em[i].singular && !em[i].functions.empty()) elementMatrices(model, setup, w, em[i]);
      }
    }
    for (int i = 0; i < count && singular < 0; ++i)
      if (em[i].singular) singular = e0 + i;
    if (singular >= 0) break;
#pragma omp parallel
    {
      const int nt = omp_get_num_threads(), t = omp_get_thread_num();
      const int begin = static_cast<int>(static_cast<long long>(ncp) * t / nt);
      const int end = static_cast<int>(static_cast<long long>(ncp) * (t + 1) / nt);
      for (int i = 0; i < count; ++i) scatterOwnedColumns(em[i], dofs, setup.s, begin, end, sys);
    }
  }
  if (singular >= 0) {
    throw ComputeError(Str() << "the geometry map is singular (det J = 0) at a Gauss point of "
                             << "element " << singular
                             << "; the patch is degenerate inside an element");
  }
}

// M(dof(a, c), dof(b, c)) = Ms(a, b): same pattern as K, filled from Ms, without the
// couplings between different components (zero in M).
void consistentMass(const DofMap& dofs, int ncp, int s, ElasticSystem& sys) {
  sys.M = sys.K;
  sys.M.coeffs().setZero();
  for (int b = 0; b < ncp; ++b) {
    for (SparseMatrix::InnerIterator it(sys.Ms, b); it; ++it) {
      const int a = static_cast<int>(it.row());
      for (int c = 0; c < s; ++c) {
        const int row = dofs.dof(a, c), col = dofs.dof(b, c);
        if (row < 0 || col < 0) continue;
        addAt(sys.M, std::min(row, col), std::max(row, col), it.value());
      }
    }
  }
  sys.M.prune([](int, int, double v) { return v != 0.0; });
  sys.M.makeCompressed();
}

}  // namespace

ElasticSystem assembleElasticity(const SplineSpace& space, const DofMap& dofs,
                                 const ElasticityModel& model) {
  const int d = space.paramDim();
  const int s = space.spaceDim();
  const int ncp = space.numFunctions();
  FFRIGA_CHECK(d == s && (s == 2 || s == 3),
               "elasticity needs d = s = 2 or 3, found d = " << d << ", s = " << s);
  FFRIGA_CHECK(!model.axisymmetric || s == 2, "axisymmetric models are 2D");
  std::vector<std::vector<int>> adjacency = nodeAdjacency(space, dofs);
  ElasticSystem sys;
  sys.K = stiffnessPattern(adjacency, dofs, ncp, s);
  sys.Ms = scalarMassPattern(adjacency, dofs, ncp);
  adjacency.clear();
  const QuadratureSetup setup = quadratureSetup(model, d, s);
  assembleElements(space, dofs, model, setup, sys);
  consistentMass(dofs, ncp, s, sys);
  return sys;
}

}  // namespace ffriga
