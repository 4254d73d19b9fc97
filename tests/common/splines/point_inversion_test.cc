// Point inversion on solid NURBS patches (common/splines/point_inversion.h), directly, on the
// paper's exact geometries: the parameters of points x(xi) inside, on boundary faces and on
// degenerate edges are found again, and a point outside the ball reports its distance to it.
#include "common/splines/point_inversion.h"

#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "preproc/geometry/geometry_builders.h"

using namespace ffriga;

namespace {

// Parameters of x(xi) for the patch at xi: the point found must be x(xi) to `tol`, and where
// the map is one-to-one (interior: lo <= xi_a <= hi) the parameters themselves.
void checkRoundTrip(const NurbsPatch& patch, const double* xi, double tol, bool interior) {
  const Eigen::VectorXd x = patch.evaluate(xi, 0).x;
  const InversionResult r = invertPoint(patch, x, tol);
  INFO("xi " << xi[0] << " " << xi[1] << " " << xi[2] << " -> " << r.xi[0] << " " << r.xi[1] << " "
             << r.xi[2] << ", distance " << r.distance);
  REQUIRE(r.found);
  CHECK(r.distance <= tol);
  CHECK((patch.evaluate(r.xi.data(), 0).x - x).norm() <= tol);
  // One-to-one inside, with a Jacobian of ~0.01-0.05 m per unit parameter: a residual of
  // tol = 1e-13 m leaves parameters within ~1e-11 (1e-8 bounds it with a wide margin).
  if (interior)
    for (int a = 0; a < patch.paramDim(); ++a) CHECK(std::abs(r.xi[a] - xi[a]) < 1e-8);
}

}  // namespace

TEST_CASE("point inversion: interior, boundary and degenerate points of the half-disk and ball",
          "[inversion]") {
  const double R = 0.01, tol = 1e-13;  // 1e-11 of the radius: Newton converges quadratically
  std::mt19937 gen(51);
  auto uniform = [&gen](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(gen);
  };
  const NurbsPatch disk = halfDisk(R), ball = solidSphere(R);
  for (int trial = 0; trial < 20; ++trial) {
    // Interior points, away from the collapsed edge xi = 1 (disk) and the axis, equator and
    // seam (ball), where the map is one-to-one.
    double xi[3] = {uniform(0.05, 0.95), uniform(0.05, 0.95), 0.0};
    checkRoundTrip(disk, xi, tol, true);
    xi[2] = uniform(0.05, 0.95);
    checkRoundTrip(ball, xi, tol, true);
  }
  for (int trial = 0; trial < 10; ++trial) {
    // v (the ball's angle zeta) stays away from the seam zeta = 1 (see the seam's own case).
    const double u = uniform(0.0, 1.0), v = uniform(0.0, 0.95);
    // The disk's axis (xi = 0, x = 0), its arcs (eta = 0, 1) and its collapsed edge (xi = 1);
    // the ball's surface (eta = 0, 1), axis (xi = 0) and seam (zeta = 0): the point is found,
    // its parameters need not be unique.
    for (const std::array<double, 3>& p :
         {std::array<double, 3>{0.0, u, 0.0}, {u, 1.0, 0.0}, {u, 0.0, 0.0}, {1.0, u, 0.0}})
      checkRoundTrip(disk, p.data(), tol, false);
    for (const std::array<double, 3>& p :
         {std::array<double, 3>{u, 1.0, v}, {u, 0.0, v}, {0.0, u, v}, {u, v, 0.0}})
      checkRoundTrip(ball, p.data(), tol, false);
  }
}

TEST_CASE("point inversion: a point outside the ball is not found, no nearer than the ball",
          "[inversion]") {
  // Every point of the patch lies in the closed ball, so a point at |x| = 1.5 R is at least
  // 0.5 R from any of them (to round-off, 1e-15 m); the iteration ends near the nearest
  // point: Gauss-Newton converges only linearly at a non-zero residual (seen: up to 0.17 %
  // above 0.5 R), and 1 % still tells the near side from the far one (2.5 R).
  const double R = 0.01;
  const NurbsPatch ball = solidSphere(R);
  std::mt19937 gen(52);
  auto uniform = [&gen](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(gen);
  };
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Vector3d dir =
        Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)).normalized();
    const InversionResult r = invertPoint(ball, 1.5 * R * dir, 1e-13);
    INFO("direction " << dir.transpose() << ": distance " << r.distance);
    CHECK_FALSE(r.found);
    CHECK(r.distance >= 0.5 * R - 1e-15);
    CHECK(r.distance < 0.5 * R * 1.01);
  }
}

TEST_CASE("point inversion: points next to the ball's seam are found", "[inversion]") {
  // The angle zeta of solidSphere is periodic (zeta = 0 and 1 are the same seam): for a point
  // just below zeta = 1 the nearest grid sample can be the seam's copy at zeta = 0, from which
  // the clamped iteration cannot step below 0 (once reported as not found for surface points,
  // eta = 1: zeta = 0.99234 stuck at zeta = 0, 0.28 mm away, with R = 10 mm). The search
  // now goes on from the next nearest samples, among them the copy at zeta = 1.
  const double R = 0.01;
  const NurbsPatch ball = solidSphere(R);
  for (const double zeta : {0.995, 0.99234, 0.99}) {
    for (const double eta : {0.5, 1.0}) {
      const double xi[3] = {0.45, eta, zeta};
      const Eigen::VectorXd x = ball.evaluate(xi, 0).x;
      const InversionResult r = invertPoint(ball, x, 1e-13);
      INFO("zeta " << zeta << ", eta " << eta << ": found at zeta " << r.xi[2] << ", distance "
                   << r.distance);
      CHECK(r.found);
    }
  }
}
