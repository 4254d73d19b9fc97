#include "common/splines/contact_surface.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "common/splines/bspline_basis.h"
#include "common/base/error.h"
#include "common/splines/extracted_surface.h"
#include "common/splines/gauss_legendre.h"

namespace ffriga {

namespace {

// 1D Bezier extraction on span s of U: b_j(u) = sum_beta M(j, beta) Bern_beta(t).
Eigen::MatrixXd bezierExtraction1d(const KnotVector& U, int span) {
  const int p = U.degree();
  const double lo = U[span], hi = U[span + 1];
  Eigen::MatrixXd Vb(p + 1, p + 1), Vn(p + 1, p + 1);
  double N[kMaxDegree + 1];
  Eigen::MatrixXd Bern;
  for (int m = 0; m <= p; ++m) {
    const double t = p == 0 ? 0.5 : static_cast<double>(m) / p;
    basisFunctions(U, span, lo + t * (hi - lo), N);
    bernsteinBasis(p, t, 0, Bern);
    for (int j = 0; j <= p; ++j) {
      Vn(m, j) = N[j];
      Vb(m, j) = Bern(0, j);
    }
  }
  // Vn = Vb M^T.
  return Vb.partialPivLu().solve(Vn).transpose();
}

Eigen::MatrixXd kron(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  // Index with A's (first direction) index fastest: (i_B, i_A) -> i_A + nA i_B.
  Eigen::MatrixXd K(A.rows() * B.rows(), A.cols() * B.cols());
  for (int ib = 0; ib < B.rows(); ++ib)
    for (int jb = 0; jb < B.cols(); ++jb)
      for (int ia = 0; ia < A.rows(); ++ia)
        for (int ja = 0; ja < A.cols(); ++ja)
          K(ia + A.rows() * ib, ja + A.cols() * jb) = A(ia, ja) * B(ib, jb);
  return K;
}

// The parametric directions of the surface parameters: all but dir, in increasing order.
std::vector<int> surfaceDirections(int d, int dir) {
  std::vector<int> sd;
  for (int a = 0; a < d; ++a)
    if (a != dir) sd.push_back(a);
  return sd;
}

// The elements of the hierarchical mesh on face (dir, side) whose face cell lies
// inside the region (within 1e-12 of the region's size), in element order.
std::vector<int> faceElementsInRegion(const HierarchicalSpace& space, int dir, int side,
                                      const std::vector<int>& sd, const ParamBox& region,
                                      const std::string& name) {
  const int dc = static_cast<int>(sd.size());
  const int p = space.levelKnots(0)[dir].degree();
  std::vector<int> elems;
  for (int e = 0; e < space.numElements(); ++e) {
    const int l = space.elementLevel(e);
    const int s = space.elementSpans(e)[dir];
    if (s != (side == 0 ? p : space.levelKnots(l)[dir].numBasis() - 1)) continue;
    const ElementBox box = space.element(e);
    bool inside = true;
    for (int i = 0; i < dc; ++i) {
      const double tol = 1e-12 * (region.upper[i] - region.lower[i]);
      inside = inside && box.lower[sd[i]] >= region.lower[i] - tol &&
               box.upper[sd[i]] <= region.upper[i] + tol;
    }
    if (inside) elems.push_back(e);
  }
  if (elems.empty()) {
    throw std::invalid_argument(Str() << "contact region '" << name << "' on face (direction "
                                      << dir << ", side " << side << ") holds no element");
  }
  return elems;
}

// The level's local tensor B-splines (columns of a volume extraction operator) that are 1 on
// face (dir, side): local index 0 along dir on the front face, p on the back face.
std::vector<int> faceColumns(const HierarchicalSpace& space, int dir, int side) {
  const int d = space.paramDim();
  const std::vector<KnotVector>& U0 = space.levelKnots(0);
  const int p = U0[dir].degree();
  int stride = 1, nloc = 1;
  for (int a = 0; a < d; ++a) {
    if (a < dir) stride *= U0[a].degree() + 1;
    nloc *= U0[a].degree() + 1;
  }
  const int jl = side == 0 ? 0 : p;
  std::vector<int> cols;
  for (int c = 0; c < nloc; ++c)
    if ((c / stride) % (p + 1) == jl) cols.push_back(c);
  return cols;
}

// M_e: the Kronecker product of the 1D Bezier extraction matrices of element e's level-l
// B-splines along the surface directions.
Eigen::MatrixXd surfaceBezierExtraction(const HierarchicalSpace& space, const std::vector<int>& sd,
                                        int e) {
  const int l = space.elementLevel(e);
  Eigen::MatrixXd M = bezierExtraction1d(space.levelKnots(l)[sd[0]], space.elementSpans(e)[sd[0]]);
  if (sd.size() == 2) {
    M = kron(M, bezierExtraction1d(space.levelKnots(l)[sd[1]], space.elementSpans(e)[sd[1]]));
  }
  return M;
}

// Extraction operators: per face element its box (surface parameters) and level, the
// functions that do not vanish on the face and their operator E_e = C_e|face M_e.
void extractFaceElements(const HierarchicalSpace& space, int dir, int side,
                         const std::vector<int>& sd, const std::vector<int>& elems,
                         ContactSurface& cs) {
  const int dc = static_cast<int>(sd.size());
  const int ne = static_cast<int>(elems.size());
  const std::vector<int> cols = faceColumns(space, dir, side);
  cs.element_lower.resize(ne, dc);
  cs.element_upper.resize(ne, dc);
  cs.function_offsets.push_back(0);
  for (int i = 0; i < ne; ++i) {
    const int e = elems[i];
    const ElementBox box = space.element(e);
    for (int a = 0; a < dc; ++a) {
      cs.element_lower(i, a) = box.lower[sd[a]];
      cs.element_upper(i, a) = box.upper[sd[a]];
    }
    cs.element_level.push_back(space.elementLevel(e));
    const Eigen::MatrixXd& C = space.elementExtraction(e);
    const Eigen::MatrixXd M = surfaceBezierExtraction(space, sd, e);
    std::vector<int> rows;
    for (int r = 0; r < C.rows(); ++r) {
      bool nz = false;
      for (int c : cols) nz = nz || C(r, c) != 0.0;
      if (nz) rows.push_back(r);
    }
    Eigen::MatrixXd Cf(rows.size(), cols.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      for (std::size_t c = 0; c < cols.size(); ++c) Cf(r, c) = C(rows[r], cols[c]);
      cs.functions.push_back(space.elementFunctions(e)[rows[r]]);
    }
    cs.extraction.push_back(Cf * M);
    cs.function_offsets.push_back(static_cast<int>(cs.functions.size()));
  }
}

// Outward sign: +1 if the surface normal at the centre of face element e (the surface's
// first) points out of the body, judged against the inward parametric direction; else -1.
double outwardSign(const HierarchicalSpace& space, const ExtractedSurface& surf, int dir, int side,
                   const std::vector<int>& sd, int e) {
  const int d = space.paramDim();
  const int dc = static_cast<int>(sd.size());
  const ElementBox box = space.element(e);
  double xi[3], s[2];
  for (int a = 0; a < d; ++a) xi[a] = 0.5 * (box.lower[a] + box.upper[a]);
  for (int a = 0; a < dc; ++a) s[a] = xi[sd[a]];
  const PatchPoint vp = space.evaluate(xi, 1);
  const Eigen::VectorXd out = (side == 1 ? 1.0 : -1.0) * vp.dx.col(dir);
  SurfacePoint sp;
  surf.evaluate(0, s, space.controlPoints(), 1, sp);
  Eigen::VectorXd n(sp.x.size());
  if (dc == 2) {
    n = Eigen::Vector3d(sp.dx.col(0)).cross(Eigen::Vector3d(sp.dx.col(1)));
  } else {
    n << sp.dx(1, 0), -sp.dx(0, 0);
  }
  return n.dot(out) >= 0.0 ? 1.0 : -1.0;
}

// The collocation index of each surface function: its rank among the functions.
std::map<int, int> collocationIndices(const std::vector<int>& functions) {
  std::map<int, int> colloc;  // function -> collocation index
  for (int f : functions) colloc.emplace(f, 0);
  int nc = 0;
  for (auto& kv : colloc) kv.second = nc++;
  return colloc;
}

// Polynomial trace of local function r of element i at s, with derivatives (rows as
// rational_basis.h), from the Bernstein form.
void polynomialTrace(const ContactSurface& cs, int i, int r, const double* s, int order,
                     Eigen::VectorXd& v) {
  const int dc = cs.dim;
  Eigen::MatrixXd ders[2];
  double scale[2] = {1, 1};
  int nb[2] = {1, 1};
  for (int a = 0; a < dc; ++a) {
    scale[a] = 1.0 / (cs.element_upper(i, a) - cs.element_lower(i, a));
    nb[a] = cs.degrees[a] + 1;
    bernsteinBasis(cs.degrees[a], (s[a] - cs.element_lower(i, a)) * scale[a], order, ders[a]);
  }
  const int rowsN = numDerivativeRows(dc, order);
  v = Eigen::VectorXd::Zero(rowsN);
  const Eigen::MatrixXd& E = cs.extraction[i];
  for (int j1 = 0; j1 < nb[1]; ++j1)
    for (int j0 = 0; j0 < nb[0]; ++j0) {
      const double c = E(r, j0 + nb[0] * j1);
      if (c == 0.0) continue;
      auto D = [&](int a, int k, int j) {
        return a < dc ? ders[a](k, j) * std::pow(scale[a], k) : 1.0;
      };
      v(0) += c * D(0, 0, j0) * D(1, 0, j1);
      if (order >= 1) {
        v(1) += c * D(0, 1, j0) * D(1, 0, j1);
        if (dc == 2) v(2) += c * D(0, 0, j0) * D(1, 1, j1);
      }
      if (order >= 2) {
        v(1 + dc) += c * D(0, 2, j0) * D(1, 0, j1);
        if (dc == 2) {
          v(4) += c * D(0, 1, j0) * D(1, 1, j1);
          v(5) += c * D(0, 0, j0) * D(1, 2, j1);
        }
      }
    }
}

// Gauss-Legendre quadrature over element i of the surface, degrees[a] + extra points per
// direction: visit(s, wq, R) at each point (first direction fastest) with its surface
// parameters s, the quadrature weight times the surface Jacobian wq (m^2 in 3D, m in 2D),
// and the basis table R there (values and first derivatives).
template <class Visit>
void elementQuadrature(const HierarchicalSpace& space, const ExtractedSurface& surf,
                       const ContactSurface& cs, int i, int extra, Visit visit) {
  const int dc = cs.dim;
  QuadratureRule q[2];
  for (int a = 0; a < 2; ++a) {
    q[a] = a < dc ? gaussLegendre(cs.degrees[a] + extra, cs.element_lower(i, a),
                                  cs.element_upper(i, a))
                  : QuadratureRule{{0.0}, {1.0}};
  }
  Eigen::MatrixXd R;
  for (std::size_t g1 = 0; g1 < q[1].points.size(); ++g1)
    for (std::size_t g0 = 0; g0 < q[0].points.size(); ++g0) {
      const double s[2] = {q[0].points[g0], q[1].points[g1]};
      surf.basis(i, s, 1, R);
      const Eigen::MatrixXd dx =
          pointFromTable(R, surf.functions(i), space.controlPoints(), dc, 1).dx;  // s x dc
      const double J = dc == 2
                           ? Eigen::Vector3d(dx.col(0)).cross(Eigen::Vector3d(dx.col(1))).norm()
                           : dx.col(0).norm();
      visit(s, q[0].weights[g0] * q[1].weights[g1] * J, R);
    }
}

// Weights: w_k = integral over the region of R_k dA, element by element, by
// Gauss-Legendre with p + 3 points per direction.
void collocationWeights(const HierarchicalSpace& space, const ExtractedSurface& surf,
                        const std::map<int, int>& colloc, ContactSurface& cs) {
  const int ne = static_cast<int>(cs.element_level.size());
  for (int i = 0; i < ne; ++i) {
    elementQuadrature(space, surf, cs, i, 3,
                      [&](const double*, double wq, const Eigen::MatrixXd& R) {
                        for (int c = 0; c < R.cols(); ++c)
                          cs.collocation_weights(colloc.at(surf.functions(i)[c])) += wq * R(0, c);
                      });
  }
}

// The best of (ns + 1)^dc samples of local function r's trace on element i: its value,
// and its point in bs.
double bestSample(const ContactSurface& cs, int i, int r, int ns, double bs[2]) {
  const int dc = cs.dim;
  Eigen::VectorXd v;
  double bv = -1.0;
  for (int m1 = 0; m1 <= (dc == 2 ? ns : 0); ++m1)
    for (int m0 = 0; m0 <= ns; ++m0) {
      double s[2] = {
          cs.element_lower(i, 0) + m0 * (cs.element_upper(i, 0) - cs.element_lower(i, 0)) / ns,
          dc == 2
              ? cs.element_lower(i, 1) + m1 * (cs.element_upper(i, 1) - cs.element_lower(i, 1)) / ns
              : 0.0};
      polynomialTrace(cs, i, r, s, 0, v);
      if (v(0) > bv) {
        bv = v(0);
        bs[0] = s[0];
        bs[1] = s[1];
      }
    }
  return bv;
}

// Projected Newton steps from (bs, bv) on local function r's trace on element i, each kept
// only if it increases the value: the improved value, its point in bs.
double newtonAscent(const ContactSurface& cs, int i, int r, double bs[2], double bv) {
  const int dc = cs.dim;
  Eigen::VectorXd v;
  for (int it = 0; it < 20; ++it) {
    polynomialTrace(cs, i, r, bs, 2, v);
    Eigen::VectorXd g = v.segment(1, dc);
    Eigen::MatrixXd Hs(dc, dc);
    for (int a = 0; a < dc; ++a)
      for (int b = 0; b < dc; ++b) Hs(a, b) = v(secondDerivativeRow(dc, a, b));
    const Eigen::VectorXd step = -Hs.fullPivLu().solve(g);
    double s[2] = {bs[0], bs[1]};
    for (int a = 0; a < dc; ++a) {
      if (!std::isfinite(step(a))) continue;
      s[a] = std::clamp(s[a] + step(a), cs.element_lower(i, a), cs.element_upper(i, a));
    }
    Eigen::VectorXd vn;
    polynomialTrace(cs, i, r, s, 0, vn);
    if (!(vn(0) > bv)) break;
    bv = vn(0);
    bs[0] = s[0];
    bs[1] = s[1];
  }
  return bv;
}

// Collocation points: the Botella point of each surface function, the maximum of its trace
// over the region's elements: sampling, then projected Newton on each element's polynomial.
void botellaPoints(const std::map<int, int>& colloc, ContactSurface& cs) {
  const int dc = cs.dim;
  const int ne = static_cast<int>(cs.element_level.size());
  std::vector<double> best(colloc.size(), -1.0);
  for (int i = 0; i < ne; ++i) {
    const int f0 = cs.function_offsets[i], f1 = cs.function_offsets[i + 1];
    const int ns = 4 * (*std::max_element(cs.degrees.begin(), cs.degrees.end()) + 1);
    for (int r = 0; r < f1 - f0; ++r) {
      const int k = colloc.at(cs.functions[f0 + r]);
      double bs[2] = {0, 0};
      double bv = bestSample(cs, i, r, ns, bs);
      bv = newtonAscent(cs, i, r, bs, bv);
      if (bv > best[k]) {
        best[k] = bv;
        for (int a = 0; a < dc; ++a) cs.collocation_points(k, a) = bs[a];
        cs.collocation_element[k] = i;
      }
    }
  }
}

// Gauss collocation (header comment): p_a + 1 Gauss-Legendre points per direction of every
// element, weights = quadrature weight x surface Jacobian, element by element.
void gaussCollocation(const HierarchicalSpace& space, const ExtractedSurface& surf,
                      ContactSurface& cs) {
  const int dc = cs.dim;
  const int ne = static_cast<int>(cs.element_level.size());
  int per = 1;
  for (int a = 0; a < dc; ++a) per *= cs.degrees[a] + 1;
  cs.collocation_points.resize(ne * per, dc);
  cs.collocation_element.assign(ne * per, -1);
  cs.collocation_weights = Eigen::VectorXd::Zero(ne * per);
  int k = 0;
  for (int i = 0; i < ne; ++i) {
    elementQuadrature(space, surf, cs, i, 1,
                      [&](const double* s, double wq, const Eigen::MatrixXd&) {
                        for (int a = 0; a < dc; ++a) cs.collocation_points(k, a) = s[a];
                        cs.collocation_element[k] = i;
                        cs.collocation_weights(k++) = wq;
                      });
  }
}

}  // namespace

ContactSurface extractContactSurface(const HierarchicalSpace& space, int dir, int side,
                                     const ParamBox& region, const std::string& name,
                                     CollocationRule rule) {
  const int d = space.paramDim();
  FFRIGA_CHECK(d >= 2 && dir >= 0 && dir < d && (side == 0 || side == 1),
               "d " << d << " dir " << dir << " side " << side);
  const int dc = d - 1;
  const std::vector<int> sd = surfaceDirections(d, dir);
  ContactSurface cs;
  cs.name = name;
  cs.dim = dc;
  for (int a : sd) cs.degrees.push_back(space.levelKnots(0)[a].degree());
  const std::vector<int> elems = faceElementsInRegion(space, dir, side, sd, region, name);
  extractFaceElements(space, dir, side, sd, elems, cs);

  const ExtractedSurface surf(cs, space.weights());  // reads cs, which stays in place
  cs.outward_sign = outwardSign(space, surf, dir, side, sd, elems[0]);

  cs.collocation_rule = rule;
  if (rule == CollocationRule::kGauss) {
    gaussCollocation(space, surf, cs);
    return cs;
  }
  const std::map<int, int> colloc = collocationIndices(cs.functions);
  const int nc = static_cast<int>(colloc.size());
  cs.collocation_points.resize(nc, dc);
  cs.collocation_element.assign(nc, -1);
  cs.collocation_weights = Eigen::VectorXd::Zero(nc);
  collocationWeights(space, surf, colloc, cs);
  botellaPoints(colloc, cs);
  return cs;
}

}  // namespace ffriga
