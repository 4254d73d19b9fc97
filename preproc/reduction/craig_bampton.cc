#include "preproc/reduction/craig_bampton.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include <omp.h>

#include <Eigen/Eigenvalues>

#include "common/base/error.h"
#include "preproc/solvers/dense_products.h"
#include "preproc/solvers/eigen_solver.h"
#include "preproc/solvers/sparse_cholesky.h"

namespace ffriga {

namespace {

// Wall-clock steps into ReducedModel::timings.
class StepTimer {
 public:
  explicit StepTimer(ReducedModel* out) : out_(out), last_(std::chrono::steady_clock::now()) {}
  void step(const char* name) {
    const auto now = std::chrono::steady_clock::now();
    out_->timings.emplace_back(name, std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }

 private:
  ReducedModel* out_;
  std::chrono::steady_clock::time_point last_;
};

// Blocks of a symmetric matrix (upper triangle) for the split interior i / interface b.
struct Partition {
  std::vector<int> interior_of;   // DOF -> interior index or -1
  std::vector<int> interface_of;  // DOF -> interface index or -1
  std::vector<int> interior, boundary;
};

Partition partition(const std::vector<bool>& isInterface) {
  Partition p;
  const int n = static_cast<int>(isInterface.size());
  p.interior_of.assign(n, -1);
  p.interface_of.assign(n, -1);
  for (int j = 0; j < n; ++j) {
    if (isInterface[j]) {
      p.interface_of[j] = static_cast<int>(p.boundary.size());
      p.boundary.push_back(j);
    } else {
      p.interior_of[j] = static_cast<int>(p.interior.size());
      p.interior.push_back(j);
    }
  }
  return p;
}

// A_ii (upper), A_ib (full block), A_bb (upper) from the upper triangle of A.
void splitBlocks(const SparseMatrix& A, const Partition& p, SparseMatrix* Aii, SparseMatrix* Aib,
                 SparseMatrix* Abb) {
  const int ni = static_cast<int>(p.interior.size());
  const int nb = static_cast<int>(p.boundary.size());
  std::vector<int> outer(1, 0), inner;
  std::vector<double> values;
  outer.reserve(ni + 1);
  inner.reserve(A.nonZeros());
  values.reserve(A.nonZeros());
  std::vector<Eigen::Triplet<double>> ib, bb;
  for (int j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const int i = static_cast<int>(it.row());
      const int ii = p.interior_of[i], jj = p.interior_of[j];
      if (ii >= 0 && jj >= 0) {
        inner.push_back(ii);
        values.push_back(it.value());
      } else if (ii >= 0) {
        ib.emplace_back(ii, p.interface_of[j], it.value());
      } else if (jj >= 0) {
        ib.emplace_back(jj, p.interface_of[i], it.value());
      } else {
        bb.emplace_back(p.interface_of[i], p.interface_of[j], it.value());
      }
    }
    if (p.interior_of[j] >= 0) outer.push_back(static_cast<int>(inner.size()));
  }
  *Aii = Eigen::Map<const SparseMatrix>(ni, ni, static_cast<int>(inner.size()), outer.data(),
                                        inner.data(), values.data());
  if (Aib) {
    Aib->resize(ni, nb);
    Aib->setFromTriplets(ib.begin(), ib.end());
  }
  if (Abb) {
    Abb->resize(nb, nb);
    Abb->setFromTriplets(bb.begin(), bb.end());
  }
}

// Frees the expensive members as soon as they are not needed.
struct Basis {
  Eigen::MatrixXd Psi;  // ndof x nc
  Eigen::MatrixXd Kr;   // nc x nc, Psi^T K Psi
};

// The fixed-interface normal modes (ARPACK, shift-invert: one solve at a time) and the
// constraint modes X = -K_ii^{-1} K_ib (all right-hand sides, in blocks) only read the
// factor of K_ii. With two or more threads they run side by side, each with single-threaded
// BLAS: the same operations in the same order as one after the other, so the same bits.
void solveModesSideBySide(const SparseCholesky& chol, const SparseMatrix& Mii,
                          const SparseMatrix& Kib, int normal_modes, EigenResult* modes,
                          Eigen::MatrixXd* X, ReducedModel* out) {
  std::exception_ptr failure[2];
  double seconds[2] = {0.0, 0.0};
  const auto since = [](std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
#pragma omp parallel sections num_threads(2) if (omp_get_max_threads() >= 2)
  {
#pragma omp section
    {
      const auto t0 = std::chrono::steady_clock::now();
      try {
        if (normal_modes > 0) {
          EigenOptions eo;
          eo.count = normal_modes;
          eo.shift = 0.0;
          eo.what = "fixed-interface normal modes";
          *modes = solveEigenproblem(chol, Mii, eo);
        }
      } catch (...) {
        failure[0] = std::current_exception();
      }
      seconds[0] = since(t0);
    }
#pragma omp section
    {
      const auto t0 = std::chrono::steady_clock::now();
      try {
        // -K_ii^{-1} K_ib as K_ii^{-1} (-K_ib): negating the sparse right-hand side is
        // exact and spares a pass over the dense result.
        *X = chol.solve(SparseMatrix(-Kib));
      } catch (...) {
        failure[1] = std::current_exception();
      }
      seconds[1] = since(t0);
    }
  }
  for (const std::exception_ptr& f : failure)
    if (f) std::rethrow_exception(f);
  out->timings.emplace_back("fixed-interface modes (ARPACK)", seconds[0]);
  out->timings.emplace_back("constraint modes (CHOLMOD)", seconds[1]);
}

// Throws InputError unless the split is a well-posed Craig-Bampton problem: a non-empty
// interface that suppresses every rigid motion (else K_ii is singular), and
// 0 <= normal_modes < n_i.
void checkInterface(const Partition& p, const ReductionOptions& o, int n) {
  const int ni = static_cast<int>(p.interior.size());
  const int nb = static_cast<int>(p.boundary.size());
  if (nb == 0) {
    throw InputError(
        "Craig-Bampton reduction: the interface is empty (no control point of the "
        "contact region has a free degree of freedom); enlarge contact.region");
  }
  const int nr = static_cast<int>(o.rigid_modes.cols());
  Eigen::MatrixXd Rb(nb, nr);
  for (int k = 0; k < nb; ++k) Rb.row(k) = o.rigid_modes.row(p.boundary[k]);
  const int rank =
      static_cast<int>(Eigen::FullPivHouseholderQR<Eigen::MatrixXd>(Rb).setThreshold(1e-10).rank());
  if (rank < nr) {
    throw InputError(Str() << "Craig-Bampton reduction: the fixed-interface problem is "
                           << "unconstrained: fixing the " << nb << " interface DOFs suppresses "
                           << "only " << rank << " of the " << nr << " rigid-body motions "
                           << "(the interface needs points that are not collinear); enlarge "
                           << "contact.region");
  }
  if (o.normal_modes < 0 || o.normal_modes >= ni) {
    throw ParameterError("reduction.normal_modes",
                         Str() << o.normal_modes << " normal modes, but the fixed-interface "
                               << "problem has " << ni << " DOFs (" << n << " in total, " << nb
                               << " on the interface)");
  }
}

// Factorises K_ii into chol and records its statistics in out; throws ComputeError if K_ii
// is not positive definite or its factor is non-finite or numerically singular.
void factorInterior(const SparseMatrix& Kii, SparseCholesky& chol, ReducedModel* out) {
  std::string message;
  const auto status = chol.factorize(Kii, &message);
  if (status == SparseCholesky::Status::kNotPositiveDefinite) {
    throw ComputeError(
        "Craig-Bampton reduction: the fixed-interface stiffness K_ii is not "
        "positive definite (" +
        message +
        "); is the body unconstrained or the "
        "geometry inverted?");
  }
  if (status != SparseCholesky::Status::kOk) {
    throw ComputeError("Craig-Bampton reduction: factorisation of K_ii failed: " + message);
  }
  out->factor_rcond = chol.rcond();
  out->factor_nonzeros = chol.factorNonzeros();
  out->factor_flops = chol.factorFlops();
  // A crude estimate (ratio of pivots); singular matrices give round-off level values.
  if (!std::isfinite(out->factor_rcond)) {
    throw ComputeError(
        "Craig-Bampton reduction: the factorisation of K_ii has non-finite "
        "entries (overflow: check the material constants and the geometry)");
  }
  if (!(out->factor_rcond > 1e-14)) {
    throw ComputeError(Str() << "Craig-Bampton reduction: the factorisation of K_ii is "
                             << "numerically singular (CHOLMOD rcond estimate " << out->factor_rcond
                             << "): the fixed-interface problem is "
                             << "unconstrained or the stiffness overflowed");
  }
}

// Psi = [normal modes, constraint modes] on the interior DOFs, the identity on the interface
// ones, and Kr = Psi^T K Psi = diag(lambda) (+) (K_bb + K_ib^T X): the couplings vanish
// since K_ii X = -K_ib.
Basis assembleBasis(const Partition& p, const EigenResult& modes, const Eigen::MatrixXd& X,
                    const SparseMatrix& Kib, const SparseMatrix& Kbb, int n, int nm) {
  const int ni = static_cast<int>(p.interior.size());
  const int nb = static_cast<int>(p.boundary.size());
  Basis basis;
  basis.Psi.setZero(n, nm + nb);
  for (int k = 0; k < ni; ++k) {
    const int row = p.interior[k];
    if (nm > 0) basis.Psi.row(row).head(nm) = modes.vectors.row(k);
    basis.Psi.row(row).tail(nb) = X.row(k);
  }
  for (int k = 0; k < nb; ++k) basis.Psi(p.boundary[k], nm + k) = 1.0;
  basis.Kr.setZero(nm + nb, nm + nb);
  for (int j = 0; j < nm; ++j) basis.Kr(j, j) = modes.values(j);
  const SparseMatrix KbbFull = Kbb.selfadjointView<Eigen::Upper>();
  Eigen::MatrixXd Kc = Eigen::MatrixXd(KbbFull) + Kib.transpose() * X;
  basis.Kr.bottomRightCorner(nb, nb) = 0.5 * (Kc + Kc.transpose());
  return basis;
}

// The fixed-interface modes below the cutoff f_c (options.mode_cutoff_hz): solved again for
// twice as many until the highest lies above f_c (or none are left), then cut to those
// below it. Returns how many remain.
int modesBelowCutoff(const SparseCholesky& chol, const SparseMatrix& Mii, double cutoff_hz,
                     EigenResult* modes) {
  const int ni = static_cast<int>(Mii.rows());
  const double cutoff = std::pow(2.0 * M_PI * cutoff_hz, 2);  // (rad/s)^2
  while (modes->values.size() > 0 && modes->values(modes->values.size() - 1) < cutoff &&
         modes->values.size() < ni - 1) {
    EigenOptions eo;
    eo.count = std::min(2 * static_cast<int>(modes->values.size()), ni - 1);
    eo.shift = 0.0;
    eo.what = "fixed-interface normal modes";
    *modes = solveEigenproblem(chol, Mii, eo);
  }
  int keep = 0;
  while (keep < modes->values.size() && modes->values(keep) < cutoff) ++keep;
  modes->values.conservativeResize(keep);
  modes->vectors.conservativeResize(Eigen::NoChange, keep);
  return keep;
}

Basis craigBamptonBasis(const SparseMatrix& K, const SparseMatrix& M, const ReductionOptions& o,
                        ReducedModel* out) {
  const int n = static_cast<int>(K.rows());
  const Partition p = partition(o.interface);
  checkInterface(p, o, n);
  StepTimer timer(out);
  SparseMatrix Kii, Kib, Kbb, Mii;
  splitBlocks(K, p, &Kii, &Kib, &Kbb);
  splitBlocks(M, p, &Mii, nullptr, nullptr);
  timer.step("partition");
  SparseCholesky chol;
  factorInterior(Kii, chol, out);
  timer.step("factorise K_ii");
  Kii = SparseMatrix();  // the factor has what it needs (0.8 GB for a 160k-DOF body)
  EigenResult modes;
  Eigen::MatrixXd X;  // constraint modes -K_ii^{-1} K_ib
  solveModesSideBySide(chol, Mii, Kib, o.normal_modes, &modes, &X, out);
  timer.step("fixed-interface and constraint modes (wall)");
  const int nm =
      o.mode_cutoff_hz > 0.0 ? modesBelowCutoff(chol, Mii, o.mode_cutoff_hz, &modes) : o.normal_modes;
  if (o.mode_cutoff_hz > 0.0) timer.step("fixed-interface modes below the cutoff");
  out->arpack_iterations = modes.iterations;
  out->normal_mode_omega2 = modes.values;
  out->normal_modes = nm;
  out->constraint_modes = static_cast<int>(p.boundary.size());
  out->interface_dofs = out->constraint_modes;
  return assembleBasis(p, modes, X, Kib, Kbb, n, nm);
}

Basis modalBasis(const SparseMatrix& K, const SparseMatrix& M, const ReductionOptions& o,
                 ReducedModel* out) {
  const int n = static_cast<int>(K.rows());
  const int nr = static_cast<int>(o.rigid_modes.cols());
  if (o.normal_modes < 1 || o.normal_modes + nr >= n) {
    throw ParameterError("reduction.normal_modes",
                         Str() << o.normal_modes << " normal modes, but the model has " << n
                               << " DOFs and " << nr << " rigid-body modes");
  }
  // Any sigma < 0 makes K - sigma M positive definite and selects the lowest eigenvalues;
  // a small |sigma| relative to the stiffness scale keeps the rigid and the low elastic
  // modes well separated in 1 / (lambda - sigma).
  const double scale = K.diagonal().sum() / M.diagonal().sum();
  EigenOptions eo;
  eo.count = o.normal_modes + nr;
  eo.shift = -1e-5 * scale;
  eo.what = "free-free normal modes";
  const EigenResult r = solveEigenproblem(K, M, eo);
  out->arpack_iterations = r.iterations;
  const double top = r.values.cwiseAbs().maxCoeff();
  for (int j = 0; j < nr; ++j) {
    if (std::abs(r.values(j)) > 1e-8 * top) {
      throw ComputeError(Str() << "free-free modes: expected " << nr << " rigid-body modes with "
                               << "zero frequency, eigenvalue " << j << " is " << r.values(j)
                               << " (largest computed " << top << ")");
    }
  }
  out->normal_mode_omega2 = r.values.tail(o.normal_modes);
  out->normal_modes = o.normal_modes;
  Basis basis;
  basis.Psi = r.vectors.rightCols(o.normal_modes);
  basis.Kr = r.values.tail(o.normal_modes).asDiagonal();
  return basis;
}

// The characteristic constraint modes of the interface (characteristic_constraint_modes.h)
// for the Craig-Bampton reduced matrices Mr (before the frame projection) and Kr; returns the
// transformation and records what was kept in out.
Eigen::MatrixXd reduceInterface(const ReductionOptions& o, const Eigen::MatrixXd& Mr,
                                const Eigen::MatrixXd& Kr, ReducedModel* out) {
  std::vector<bool> retained;  // per interface DOF, in the basis' (ascending DOF) order
  for (std::size_t j = 0; j < o.interface.size(); ++j) {
    if (o.interface[j])
      retained.push_back(!o.interface_retained.empty() && o.interface_retained[j]);
  }
  InterfaceReduction r =
      characteristicConstraintModes(Mr, Kr, out->normal_modes, retained, o.interface_modes,
                                    o.interface_loads, o.interface_check_loads);
  if (r.compliance_error.size() > 0)
    out->interface_compliance_error = r.compliance_error.maxCoeff();
  out->characteristic_rigid = r.rigid;
  out->characteristic_elastic = r.elastic;
  out->patch_modes = r.patch_modes;
  out->interface_retained = r.retained;
  out->characteristic_omega2 = std::move(r.omega2);
  // The rigid ones count as dropped.
  out->constraint_modes = r.rigid + r.elastic + r.patch_modes + r.retained;
  return std::move(r.T);
}

// The frame projection Phi' = Psi Tif - R A of the basis Psi Tif (Tif: no columns for none)
// with W = R^T M Psi Tif: Buckens A = (R^T M R)^{-1} W, tangent A = (C R)^{-1} C Psi Tif;
// Mr (the reduced mass of Psi Tif) becomes that of Phi'. Returns A.
Eigen::MatrixXd projectFrame(const ReductionOptions& o, const Eigen::MatrixXd& MR,
                             const Eigen::MatrixXd& Psi, const Eigen::MatrixXd& Tif,
                             const Eigen::MatrixXd& W, Eigen::MatrixXd* Mr) {
  const Eigen::MatrixXd& R = o.rigid_modes;
  const Eigen::MatrixXd RMR = R.transpose() * MR;
  Eigen::MatrixXd A;
  if (o.frame == FrameKind::kBuckens) {
    A = RMR.ldlt().solve(W);
    *Mr -= W.transpose() * A;
  } else {
    const Eigen::MatrixXd& C = o.frame_conditions;
    FFRIGA_CHECK(C.rows() == R.cols() && C.cols() == R.rows(),
                 "frame conditions " << C.rows() << "x" << C.cols());
    const Eigen::MatrixXd CR = C * R;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(CR);
    if (lu.rank() < CR.rows()) {
      throw InputError(
          "tangent frame: the frame conditions at the marker do not determine the "
          "rigid-body motion (marker on a degenerate point?)");
    }
    A = Tif.size() > 0 ? lu.solve((C * Psi) * Tif).eval() : lu.solve(C * Psi).eval();
    *Mr += -A.transpose() * W - W.transpose() * A + A.transpose() * RMR * A;
  }
  *Mr = 0.5 * (*Mr + Mr->transpose()).eval();
  return A;
}

// The reduced eigenproblem in the range of Mr: returns T with T^T Mr T = E and
// T^T Kr T = diag(out->omega2), dropping the dependent (rigid) directions (counted in
// out->rigid_dropped).
Eigen::MatrixXd reducedEigenvectors(const ReductionOptions& o, Eigen::MatrixXd Mr,
                                    Eigen::MatrixXd Kr, ReducedModel* out) {
  const int nr = static_cast<int>(o.rigid_modes.cols());
  // Equilibrate (unit diagonal): constraint modes of a small interface have a tiny mass
  // compared with normal modes; scaling keeps the orthonormalisation at round-off level.
  Eigen::VectorXd scale = Mr.diagonal();
  for (int j = 0; j < scale.size(); ++j)
    scale(j) = scale(j) > 0.0 ? 1.0 / std::sqrt(scale(j)) : 1.0;
  Mr = scale.asDiagonal() * Mr * scale.asDiagonal();
  Kr = scale.asDiagonal() * Kr * scale.asDiagonal();
  // Orthonormalise in the range of Mr: the rigid directions have (numerically) zero mass.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> em(Mr);
  if (em.info() != Eigen::Success) throw ComputeError("reduced mass matrix: eigen solver failed");
  // The Craig-Bampton basis contains the rigid modes exactly (K r = 0 gives
  // r_i = -K_ii^{-1} K_ib r_b), so the projection leaves exactly nr dependent directions:
  // the nr smallest eigenvalues of the equilibrated Mr (round-off, amplified by the
  // conditioning of K_ii for slender bodies); zero characteristic constraint modes were
  // left out as rigid already. The modal basis is M-orthogonal to R already. Any further
  // direction below 1e-12 of the largest is dropped as well.
  const double mmax = em.eigenvalues().maxCoeff();
  const int dependent =
      o.method == ReductionMethod::kCraigBampton ? nr - out->characteristic_rigid : 0;
  std::vector<int> keep;
  for (int j = dependent; j < Mr.cols(); ++j) {
    if (em.eigenvalues()(j) > 1e-12 * mmax) keep.push_back(j);
  }
  const int kept = static_cast<int>(keep.size());
  Eigen::MatrixXd Z(Mr.rows(), kept);
  for (int j = 0; j < kept; ++j)
    Z.col(j) = em.eigenvectors().col(keep[j]) / std::sqrt(em.eigenvalues()(keep[j]));
  out->rigid_dropped = static_cast<int>(Mr.cols()) - kept + out->characteristic_rigid;
  if (o.method == ReductionMethod::kModal) out->rigid_dropped += nr;
  Eigen::MatrixXd Kz = Z.transpose() * Kr * Z;
  Kz = 0.5 * (Kz + Kz.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ek(Kz);
  if (ek.info() != Eigen::Success) throw ComputeError("reduced eigenproblem: solver failed");
  out->omega2 = ek.eigenvalues();
  return scale.asDiagonal() * (Z * ek.eigenvectors());
}

}  // namespace

ReducedModel reduceBody(const SparseMatrix& K, const SparseMatrix& M, const ReductionOptions& o) {
  const int n = static_cast<int>(K.rows());
  FFRIGA_CHECK(o.rigid_modes.rows() == n, "rigid modes have " << o.rigid_modes.rows() << " rows");
  ReducedModel out;
  Basis basis = o.method == ReductionMethod::kCraigBampton ? craigBamptonBasis(K, M, o, &out)
                                                           : modalBasis(K, M, o, &out);
  StepTimer timer(&out);
  const Eigen::MatrixXd& R = o.rigid_modes;
  const Eigen::MatrixXd MR = symmetricProduct(M, R);
  Eigen::MatrixXd Mr = transposeTimes(basis.Psi, symmetricProduct(M, basis.Psi));
  Eigen::MatrixXd W = MR.transpose() * basis.Psi;  // R^T M Psi
  timer.step("reduced mass matrix");
  // Interface reduction: the basis becomes Psi Tif (Psi itself is only multiplied at the end).
  Eigen::MatrixXd Tif;
  if (o.reducesInterface()) {
    Tif = reduceInterface(o, Mr, basis.Kr, &out);
    Mr = (Tif.transpose() * Mr * Tif).eval();
    basis.Kr = (Tif.transpose() * basis.Kr * Tif).eval();
    W = (W * Tif).eval();
    timer.step("characteristic constraint modes");
  }
  const Eigen::MatrixXd A = projectFrame(o, MR, basis.Psi, Tif, W, &Mr);  // Phi' = Psi - R A
  timer.step("frame projection");
  const Eigen::MatrixXd T = reducedEigenvectors(o, std::move(Mr), std::move(basis.Kr), &out);
  out.Phi = times(basis.Psi, Tif.size() > 0 ? (Tif * T).eval() : T);
  basis.Psi.resize(0, 0);
  out.Phi -= R * (A * T);
  timer.step("reduced eigenproblem and modes");
  return out;
}

}  // namespace ffriga
