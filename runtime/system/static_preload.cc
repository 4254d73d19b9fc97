#include "runtime/system/static_preload.h"

#include <cmath>
#include <limits>
#include <vector>

#include "common/base/error.h"

namespace ffriga {

namespace {

// State indices of the elastic coordinates and the rows of the rates that hold their
// accelerations, times `factor`: a dynamic coordinate's acceleration is its velocity's rate
// (factor 1); a quasi-static one's is its position's rate times k tau
// (runtime/bodies/quasi_static_modes.h: dq/dt = a / (k tau)).
struct ElasticIndex {
  std::vector<int> q, a;
  std::vector<double> k;       // stiffness diagonal (1/s^2)
  std::vector<double> factor;  // on the rate in row a
};

ElasticIndex elasticIndex(const MultibodySystem& sys) {
  ElasticIndex e;
  for (int b = 0; b < sys.numBodies(); ++b) {
    const BodyModel& body = sys.body(b);
    const int q0 = sys.positionOffset(b) + body.numRigidPositions();
    for (int i = 0; i < body.nq(); ++i) {
      e.q.push_back(q0 + i);
      e.a.push_back(sys.velocityOffset(b) + body.numRigidVelocities() + i);
      e.k.push_back(body.sid().Ke(i, i));
      e.factor.push_back(1.0);
    }
    const QuasiStaticModes& qs = body.quasiStatic();
    for (int s = 0; s < qs.size(); ++s) {
      const std::size_t j = e.q.size() - body.nq() + qs.index[s];
      e.a[j] = q0 + qs.index[s];
      e.factor[j] = qs.stiffness(s) * qs.tau;
    }
  }
  return e;
}

}  // namespace

PreloadReport staticPreload(MultibodySystem& sys, Eigen::VectorXd& y) {
  const ElasticIndex ix = elasticIndex(sys);
  const int n = static_cast<int>(ix.q.size());
  PreloadReport report;
  if (n == 0) return report;
  Eigen::VectorXd ydot(y.size());
  auto residual = [&](Eigen::VectorXd& state, Eigen::VectorXd& F) {
    if (!sys.projectStateRigidly(state.data()))
      throw ComputeError("static preload: the joints could not be closed at the deformed markers");
    sys.rhs(0.0, state.data(), ydot.data());
    F.resize(n);
    for (int i = 0; i < n; ++i) F(i) = ix.factor[i] * ydot(ix.a[i]);
  };
  auto elasticForce = [&](const Eigen::VectorXd& state) {
    double f = 0.0;
    for (int i = 0; i < n; ++i) f = std::max(f, std::abs(ix.k[i] * state(ix.q[i])));
    return f;
  };
  Eigen::VectorXd F, Ft, before;
  residual(y, F);
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  bool haveJacobian = false;
  double previous = std::numeric_limits<double>::infinity();
  for (int iter = 0; iter < 30; ++iter) {
    const double r = F.lpNorm<Eigen::Infinity>(), scale = elasticForce(y);
    report.iterations = iter;
    report.residual = r;
    report.elastic_force = scale;
    if (r == 0.0) return report;
    // Converged at 1e-10 of the elastic forces; then polished while Newton still gains a
    // factor 10 per step, down to round-off: what is left of the residual becomes rigid
    // accelerations and joint reactions (1e-10 left them at a few 1e-8 of the weight, and
    // the last bits depended on the BLAS kernels of the machine).
    if (r <= 1e-10 * scale && (r > 0.1 * previous || r <= 1e-15 * scale)) {
      if (r > previous) {  // the last polishing step lost: back to the state before it
        y = before;
        report.residual = previous;
      }
      return report;
    }
    if (!haveJacobian || r > 0.1 * previous) {
      // dF/dq by forward differences; increments relative to the static deflection scale
      // |F| / k (the response of a mode to its own residual) or to |q|.
      Eigen::MatrixXd D(n, n);
      const double sqrtEps = std::sqrt(std::numeric_limits<double>::epsilon());
      for (int j = 0; j < n; ++j) {
        Eigen::VectorXd yy = y;
        const double h = sqrtEps * std::max({std::abs(y(ix.q[j])), r / ix.k[j], 1e-30});
        yy(ix.q[j]) += h;
        residual(yy, Ft);
        D.col(j) = (Ft - F) / h;
      }
      lu.compute(D);
      haveJacobian = true;
    }
    previous = r;
    before = y;
    const Eigen::VectorXd dq = -lu.solve(F);
    for (int i = 0; i < n; ++i) y(ix.q[i]) += dq(i);
    residual(y, F);
  }
  throw ComputeError(Str() << "static preload did not converge in 30 Newton steps: elastic "
                           << "accelerations " << F.lpNorm<Eigen::Infinity>() << " against "
                           << "elastic forces " << elasticForce(y) << " (per unit q)");
}

}  // namespace ffriga
