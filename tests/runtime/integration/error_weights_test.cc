// Error weights with algebraic components (runtime/integration/error_weights.h): the weights
// and difference-quotient scales by hand, and an oscillator against a one-sided penalty
// spring whose force is an algebraic component kept exact by a projection, as the
// quasi-static coordinates of a body in contact are. Against the closed-form solution, with
// the algebraic component left out of the error test and with it in.
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "runtime/integration/bdf_integrator.h"
#include "runtime/integration/error_weights.h"

using namespace ffriga;

TEST_CASE("error weights: sqrt(n / m) / (rtol |y| + atol), 0 for algebraic components", "[ffr]") {
  SUNContext ctx = nullptr;
  REQUIRE(SUNContext_Create(nullptr, &ctx) == 0);
  N_Vector y = N_VNew_Serial(3, ctx), ewt = N_VNew_Serial(3, ctx);
  NV_Ith_S(y, 0) = -2.0, NV_Ith_S(y, 1) = 5.0, NV_Ith_S(y, 2) = 0.5;
  ErrorWeights w;
  w.rtol = 1e-3;
  w.atol = Eigen::Vector3d(1e-4, 2e-4, 1e-2);
  w.algebraic = {false, true, false};
  REQUIRE(w.anyAlgebraic());
  REQUIRE(ErrorWeights::evaluate(y, ewt, &w) == 0);
  // n = 3 components, m = 2 differential: the norm is their own root mean square.
  const double factor = std::sqrt(3.0 / 2.0);
  CHECK(NV_Ith_S(ewt, 0) == Approx(factor / 2.1e-3).epsilon(1e-15));
  CHECK(NV_Ith_S(ewt, 1) == 0.0);
  CHECK(NV_Ith_S(ewt, 2) == Approx(factor / 1.05e-2).epsilon(1e-15));
  N_Vector e = N_VNew_Serial(3, ctx);
  NV_Ith_S(e, 0) = 2.1e-3, NV_Ith_S(e, 1) = 1e3, NV_Ith_S(e, 2) = -1.05e-2;  // one tolerance each
  CHECK(N_VWrmsNorm(e, ewt) == Approx(1.0).epsilon(1e-15));
  N_VDestroy(e);
  // Difference quotients step by the tolerance of each component.
  std::vector<double> scale;
  w.differenceScale(y, ewt, scale);
  CHECK(scale[0] == Approx(2.1e-3).epsilon(1e-15));
  CHECK(scale[1] == Approx(5.2e-3).epsilon(1e-15));
  CHECK(scale[2] == Approx(1.05e-2).epsilon(1e-15));
  // A differential component without a positive tolerance is refused.
  w.atol(0) = 0.0;
  NV_Ith_S(y, 0) = 0.0;
  CHECK(ErrorWeights::evaluate(y, ewt, &w) == -1);
  w.algebraic.clear();
  CHECK_FALSE(w.anyAlgebraic());
  N_VDestroy(y);
  N_VDestroy(ewt);
  SUNContext_Free(&ctx);
}

namespace {

// x'' = -omega^2 x - z with z = c max(0, x - g): a unit mass on a soft spring that meets a
// stiff one-sided spring at x = g, like a point entering contact. State (x, v, z); z is the
// algebraic component, integrated as the relaxation tau z' = c max(0, x - g) - z and put on
// z = c max(0, x - g) by the projection after every step (the quasi-static coordinates'
// treatment, runtime/bodies/quasi_static_modes.h). Its Jacobian is given exactly.
class KinkedOscillator : public OdeSystem {
 public:
  static constexpr double kOmega = 1.0, kStiffness = 1e4, kGap = 0.5, kTau = 1e-9;
  int size() const override { return 3; }
  static double target(double x) { return kStiffness * std::max(0.0, x - kGap); }
  void rhs(double, const double* y, double* ydot) override {
    ydot[0] = y[1];
    ydot[1] = -kOmega * kOmega * y[0] - y[2];
    ydot[2] = (target(y[0]) - y[2]) / kTau;
  }
  bool jacobian(double, const double* y, const double*, const double*, double* J) override {
    auto at = [J](int r, int c) -> double& { return J[r + 3 * c]; };  // column-major
    at(0, 1) = 1.0;
    at(1, 0) = -kOmega * kOmega;
    at(1, 2) = -1.0;
    at(2, 0) = (y[0] > kGap ? kStiffness : 0.0) / kTau;
    at(2, 2) = -1.0 / kTau;
    return true;
  }
  bool hasConstraints() const override { return true; }
  bool project(double, const double* y, double* corr) override {
    corr[0] = corr[1] = 0.0;
    corr[2] = target(y[0]) - y[2];
    return true;
  }
};

// The closed form from x(0) = 0, v(0) = v0 (amplitude v0 / omega > g): free until x = g at
// t1, then an oscillation of frequency Omega = sqrt(omega^2 + c) about x_e = c g / Omega^2
// until x = g again at t2 (leaving with the opposite velocity), then free again. x and v at
// a time t after t2 and before the next contact.
struct ClosedForm {
  double A, theta1, t1, t2;
  explicit ClosedForm(double v0) {
    const double w = KinkedOscillator::kOmega, c = KinkedOscillator::kStiffness;
    const double g = KinkedOscillator::kGap;
    A = v0 / w;
    theta1 = std::asin(g / A);
    t1 = theta1 / w;
    const double Omega = std::sqrt(w * w + c), xe = c * g / (Omega * Omega);
    const double v1 = A * w * std::cos(theta1);
    const double phi = std::atan2(g - xe, v1 / Omega);  // x - x_e = B sin(Omega s + phi)
    t2 = t1 + (M_PI - 2.0 * phi) / Omega;
  }
  double x(double t) const {
    return A * std::sin(M_PI - theta1 + KinkedOscillator::kOmega * (t - t2));
  }
  double v(double t) const {
    return A * KinkedOscillator::kOmega *
           std::cos(M_PI - theta1 + KinkedOscillator::kOmega * (t - t2));
  }
};

struct Run {
  double x, v;
  IntegratorStats stats;
};

Run integrate(bool algebraic, double T) {
  KinkedOscillator sys;
  IntegratorOptions o;
  o.linear_solver = LinearSolverKind::kEigenDense;
  o.rtol = 1e-6;
  o.atol = Eigen::Vector3d(1e-9, 1e-9, 1e-9 * KinkedOscillator::kStiffness);
  if (algebraic) o.algebraic = {false, false, true};
  BdfIntegrator integ(sys, 0.0, Eigen::Vector3d(0.0, 1.0, 0.0), o);
  integ.setStopTime(T);
  Eigen::VectorXd y;
  integ.advance(T, y);
  return {y(0), y(1), integ.stats()};
}

}  // namespace

TEST_CASE("error weights: an algebraic penalty force left out of the error test",
          "[ffr][integration]") {
  const ClosedForm exact(1.0);
  const double T = exact.t2 + 1.0;  // 1 s after the contact, before the next one (x < g)
  REQUIRE(exact.x(T) < KinkedOscillator::kGap);
  const Run without = integrate(true, T), with = integrate(false, T);
  INFO("left out: x " << without.x << ", v " << without.v << ", steps " << without.stats.steps
                      << ", error test failures " << without.stats.error_test_failures
                      << "; tested: x " << with.x << ", v " << with.v << ", steps "
                      << with.stats.steps << ", error test failures "
                      << with.stats.error_test_failures << "; exact x " << exact.x(T) << ", v "
                      << exact.v(T));
  // Both follow the closed form: a local tolerance of 1e-6 over a few hundred steps and a
  // contact of 0.03 s whose entry and exit the steps must locate; 2e-4 of the amplitude
  // (1 m, 1 m/s) is 200 rtol.
  CHECK(std::abs(without.x - exact.x(T)) < 2e-4);
  CHECK(std::abs(without.v - exact.v(T)) < 2e-4);
  CHECK(std::abs(with.x - exact.x(T)) < 2e-4);
  CHECK(std::abs(with.v - exact.v(T)) < 2e-4);
  // The penalty force's kink at entry and exit rejects steps where z is tested (its
  // polynomial prediction fails there at any step size); left out, the kink is seen only
  // through x and v, which stay smooth to first order.
  CHECK(without.stats.error_test_failures < with.stats.error_test_failures);
  CHECK(without.stats.steps <= with.stats.steps);
}
