// Rigid obstacles as contact targets: the exact gap, normal and box bound of a plane or a
// sphere (runtime/contact/rigid_obstacle.h), the penalty forces of a flexible body's
// collocated contact surface against them (runtime/contact/obstacle_contact.h, Eq. 17-18)
// against sums formed here from the NURBS patch itself, the stiffness terms against
// difference quotients, and the scene checks that need a SID (runtime/scene/scene_obstacles.cc;
// those that do not are the tests/bad_scenes/obstacle_*.yaml cases).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "common/base/error.h"
#include "common/splines/refinement.h"
#include "runtime/bodies/floating_body.h"
#include "runtime/bodies/rotation.h"
#include "runtime/contact/obstacle_contact.h"
#include "runtime/contact/rigid_obstacle.h"
#include "runtime/scene/scene.h"
#include "runtime/system/multibody_system.h"
#include "tests/support/surface_fixtures.h"
#include "tests/support/synthetic_bodies.h"
#include "tests/support/test_util.h"

using namespace ffriga;

namespace {

// A generator of its own per case: each case draws the same numbers whichever cases ran
// before it in the same process.
struct Draw {
  std::mt19937 gen;
  explicit Draw(unsigned seed) : gen(seed) {}
  double operator()(double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(gen);
  }
  Eigen::Vector3d vector(double a, double b) {
    const double x = (*this)(a, b), y = (*this)(a, b), z = (*this)(a, b);
    return Eigen::Vector3d(x, y, z);
  }
};

// A flexible body whose contact surface is a bumpy rational cap facing -z,
//   z = 0.45 - 0.3 (1 - (x^2 + y^2) / 2) + noise 0.02,  x, y in [-1, 1] (m),
// lowest (z ~ 0.15) in the middle; p = 2 x 3, refined by knot insertion (the geometry is
// unchanged) to 12 x 13 control points, with a collocation point of weight 1e-2 m^2 at each
// tensor Greville abscissa (156 points). Point masses of 1 kg sit at the control points and
// the nq modes are random (|Phi| <= 0.05), as in contact_test.cc.
struct Cap {
  NurbsPatch patch;
  Eigen::MatrixXd Phi;  // 3N x nq, the modes at the patch's control points
  std::shared_ptr<FlexibleBodySid> sid;
};

constexpr double kWeight = 1e-2;  // m^2, every collocation point's weight

Cap makeCap(int nq, Draw& draw) {
  std::vector<KnotVector> U = {KnotVector({0, 0, 0, 0.4, 1, 1, 1}, 2),
                               KnotVector({0, 0, 0, 0, 0.6, 1, 1, 1, 1}, 3)};
  const int n0 = U[0].numBasis(), n1 = U[1].numBasis();
  Eigen::MatrixXd P(n0 * n1, 3);
  Eigen::VectorXd w(n0 * n1);
  for (int j = 0; j < n1; ++j) {
    for (int i = 0; i < n0; ++i) {
      const double x = -1.0 + 2.0 * i / (n0 - 1), y = -1.0 + 2.0 * j / (n1 - 1);
      P.row(i + n0 * j) << x, y, 0.45 - 0.3 * (1.0 - 0.5 * (x * x + y * y)) + 0.02 * draw(-1, 1);
      w(i + n0 * j) = draw(0.6, 1.4);
    }
  }
  NurbsPatch patch(U, P, w);
  patch = insertKnots(patch, 0, {0.1, 0.2, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9});
  patch = insertKnots(patch, 1, {0.1, 0.2, 0.3, 0.4, 0.5, 0.7, 0.8, 0.9});
  const int N = patch.numControlPoints();
  Eigen::MatrixXd Phi(3 * N, nq);
  for (int c = 0; c < nq; ++c)
    for (int r = 0; r < 3 * N; ++r) Phi(r, c) = 0.05 * draw(-1, 1);
  FlexibleBodySid sid;
  test::pointMassInvariants(sid, Eigen::VectorXd::Ones(N), patch.points(), Phi,
                            Eigen::MatrixXd::Identity(3 * N, 3 * N));
  sid.weights = patch.weights();
  // x_s0 x x_s1 points +z, into the body (its centre of mass is above the cap's middle).
  ContactSurface s = test::bezierExtract(patch, -1.0);
  test::addGrevilleCollocation(patch, s, kWeight);
  sid.surfaces.push_back(s);
  return Cap{patch, Phi, std::make_shared<FlexibleBodySid>(sid)};
}

// Positions s_p of a floating body: r (m), a unit quaternion, q.
Eigen::VectorXd positions(const Eigen::Vector3d& r, const Eigen::Vector4d& quaternion,
                          const Eigen::VectorXd& q) {
  Eigen::VectorXd sp(7 + q.size());
  sp << r, quaternion.normalized(), q;
  return sp;
}

// The cap (seed 303, nq = 3) over a tilted plane, at a pose where about 30 of its points
// press into it: the stiffness and friction tests' setting.
struct CapOnTiltedPlane {
  Draw draw{303};
  Cap cap = makeCap(3, draw);
  FloatingBody3d body{"cap", cap.sid};
  Eigen::Vector3d p{-0.03, 0.02, 0.21}, normal{-0.08, 0.12, 2.0};
  Eigen::Vector3d n = normal.normalized();
  Eigen::VectorXd sp =
      positions(Eigen::Vector3d(0.005, 0.01, -0.004), Eigen::Vector4d(1, -0.02, 0.01, 0.03),
                Eigen::Vector3d(-0.012, 0.02, 0.008));
  RigidObstacle floor() const { return RigidObstacle::plane("floor", p, normal, 0.0); }
};

// A collocation point of the cap at positions s_p, evaluated here from the patch and not
// by the runtime's collocated surface: x(s) is linear in the control points at fixed
// weights, so the deformed point is the patch with control points P + Phi q, and the
// point's modes Phi_i (3 x nq) are the patches with control points Phi e_j.
struct CapPoint {
  Eigen::Vector3d body;   // x_i = x0_i + Phi_i q, body frame (m)
  Eigen::Vector3d world;  // r + A x_i (m)
  Eigen::MatrixXd Phi;    // 3 x nq
  double weight = 0.0;    // m^2
};

std::vector<CapPoint> capPoints(const Cap& cap, const Eigen::VectorXd& sp) {
  const int N = cap.patch.numControlPoints(), nq = static_cast<int>(cap.Phi.cols());
  const Eigen::VectorXd q = sp.tail(nq);
  const Eigen::Matrix3d A = rotationMatrix(sp.data() + 3);
  auto reshaped = [N](const Eigen::VectorXd& v) {
    Eigen::MatrixXd M(N, 3);
    for (int k = 0; k < N; ++k) M.row(k) = v.segment<3>(3 * k).transpose();
    return M;
  };
  const NurbsPatch deformed(cap.patch.knotVectors(), cap.patch.points() + reshaped(cap.Phi * q),
                            cap.patch.weights());
  std::vector<NurbsPatch> modes;
  for (int j = 0; j < nq; ++j)
    modes.emplace_back(cap.patch.knotVectors(), reshaped(cap.Phi.col(j)), cap.patch.weights());
  const ContactSurface& cs = cap.sid->surfaces[0];
  std::vector<CapPoint> points(cs.collocation_points.rows());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double s[2] = {cs.collocation_points(i, 0), cs.collocation_points(i, 1)};
    CapPoint& c = points[i];
    c.body = deformed.evaluate(s).x;
    c.world = sp.head<3>() + A * c.body;
    c.Phi.resize(3, nq);
    for (int j = 0; j < nq; ++j) c.Phi.col(j) = modes[j].evaluate(s).x;
    c.weight = cs.collocation_weights(i);
  }
  return points;
}

// Gap (m), unit normal and coverage of a world point, written here from the obstacle's
// definition (rigid_obstacle.h header) for the cases below.
struct HandGap {
  double gap = 0.0;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  bool covered = true;
};
using GapFunction = std::function<HandGap(const Eigen::Vector3d&)>;

GapFunction planeGap(const Eigen::Vector3d& p, const Eigen::Vector3d& normal, double radius) {
  return [=](const Eigen::Vector3d& x) {
    HandGap g;
    g.n = normal / normal.norm();
    g.gap = g.n.dot(x - p);
    g.covered = radius <= 0.0 || (x - g.gap * g.n - p).norm() <= radius;
    return g;
  };
}

GapFunction sphereGap(const Eigen::Vector3d& c, double radius) {
  return [=](const Eigen::Vector3d& x) {
    HandGap g;
    g.gap = (x - c).norm() - radius;
    g.n = (x - c) / (x - c).norm();
    return g;
  };
}

// What the pair must report at s_p, summed here over the collocation points: the penalty
// force f_i = -c_p g_i w_i n_i on each covered point with g_i < 0 (Eq. 17) and the
// generalised forces [A^T f_i, x_i x A^T f_i, Phi_i^T A^T f_i] (Eq. 18).
struct Expected {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, inertial
  double magnitudes = 0.0;                          // N, sum |f_i|
  Eigen::VectorXd h;                                // generalised forces (6 + nq)
  double energy = 0.0;                              // J, sum 1/2 c_p g^2 w
  int active = 0;
  double deepest = 0.0;  // m, largest -g over covered points
  Eigen::Vector3d deepestPoint = Eigen::Vector3d::Zero();
  double smallestGap = std::numeric_limits<double>::infinity();     // m, over all points
  double smallestAbsGap = std::numeric_limits<double>::infinity();  // m: |g| nearest 0
};

Expected expectedContact(const std::vector<CapPoint>& points, const Eigen::VectorXd& sp,
                         const GapFunction& gapOf, double penalty) {
  const int nq = static_cast<int>(sp.size()) - 7;
  const Eigen::Matrix3d A = rotationMatrix(sp.data() + 3);
  Expected e;
  e.h = Eigen::VectorXd::Zero(6 + nq);
  for (const CapPoint& c : points) {
    const HandGap g = gapOf(c.world);
    e.smallestGap = std::min(e.smallestGap, g.gap);
    e.smallestAbsGap = std::min(e.smallestAbsGap, std::abs(g.gap));
    if (!g.covered) continue;
    if (-g.gap > e.deepest) {
      e.deepest = -g.gap;
      e.deepestPoint = c.world;
    }
    if (g.gap >= 0.0) continue;
    const Eigen::Vector3d f = -penalty * g.gap * c.weight * g.n;
    const Eigen::Vector3d fb = A.transpose() * f;
    e.force += f;
    e.magnitudes += f.norm();
    e.h.head<3>() += fb;
    e.h.segment<3>(3) += c.body.cross(fb);
    e.h.tail(nq) += c.Phi.transpose() * fb;
    e.energy += 0.5 * penalty * g.gap * g.gap * c.weight;
    ++e.active;
  }
  return e;
}

// A one-body system: the cap against `obstacle` at positions sp (velocities random: the
// contact forces do not depend on them).
struct CapScene {
  MultibodySystem sys;
  Eigen::VectorXd y;
  CapScene(const Cap& cap, const RigidObstacle& obstacle, double penalty, const Eigen::VectorXd& sp,
           Draw& draw) {
    sys.addBody(std::make_unique<FloatingBody3d>("cap", cap.sid));
    ContactOptions opt;
    opt.penalty = penalty;
    sys.addForceElement(
        std::make_unique<ObstacleContact>("cap-obstacle", 0, sys.body(0), 0, obstacle, opt));
    y = Eigen::VectorXd::Zero(sys.size());
    setPositions(sp);
    for (int k = 0; k < sys.body(0).numVelocities(); ++k)
      y(sys.velocityOffset(0) + k) = draw(-1, 1);
  }
  void setPositions(const Eigen::VectorXd& sp) { y.segment(sys.positionOffset(0), sp.size()) = sp; }
  ObstacleContact& contact() { return dynamic_cast<ObstacleContact&>(sys.contact(0)); }
};

constexpr double kPenalty = 1e4;  // N/m^3: k = c_p w = 100 N/m per collocation point

// Round-off of the sums over the points. The runtime reaches a collocation point by Bezier
// extraction and sums over its surface's control points' displacements, the test by de Boor
// on the patch: both agree to a few ulp of the coordinates (<= 1.5 m), ~2e-16 m. A point's
// force k g n (k = 100 N/m) then differs by ~2e-14 N, its moment (lever <= 1.5 m) and
// elastic force (|Phi_i| < 0.1) by no more; over ~30 active points, adding up even in the
// worst case, 6e-13. Seen: 4e-14 N.
constexpr double kAbsForce = 1e-12;  // N (and N m, and the elastic rows' units)
// The energy: a point's 1/2 k g^2 differs by k |g| 2e-16 m <= 100 * 0.05 * 2e-16 = 1e-15 J;
// over ~30 points at most 3e-14 J. Seen: 6e-16 J.
constexpr double kAbsEnergy = 1e-13;  // J

}  // namespace

TEST_CASE("obstacle contact: a plane's gap and normal, finite plates, hand values", "[contact]") {
  // A non-unit normal is normalised: (0, 0, 2) -> (0, 0, 1).
  const RigidObstacle floor =
      RigidObstacle::plane("floor", Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0, 0, 2), 0.0);
  CHECK(floor.normal() == Eigen::Vector3d(0, 0, 1));
  CHECK(std::string(floor.shapeName()) == "plane");
  ObstaclePoint p = floor.nearest(Eigen::Vector3d(4, 5, 7));
  CHECK(p.gap == 4.0);  // exact: 1 * (7 - 3)
  CHECK(p.normal == Eigen::Vector3d(0, 0, 1));
  CHECK(p.covered);  // infinite plane: always covered
  CHECK(floor.nearest(Eigen::Vector3d(100, -50, 2.5)).gap == -0.5);
  CHECK(floor.nearest(Eigen::Vector3d(100, -50, 2.5)).covered);

  // A 3-4-5 normal given 10 long: n = (0.6, 0, 0.8); the point p + 2 n + 5 t with the
  // tangent t = (0.8, 0, -0.6) has gap 2, and -1.5 below. Round-off: a few ulp of the
  // coordinates (~5), hence 1e-14.
  const Eigen::Vector3d p0(0.5, -1, 2), n(0.6, 0, 0.8), t(0.8, 0, -0.6);
  const RigidObstacle slope = RigidObstacle::plane("slope", p0, Eigen::Vector3d(6, 0, 8), 0.0);
  CHECK((slope.normal() - n).norm() <= 1e-15);
  CHECK(std::abs(slope.nearest(p0 + 2.0 * n + 5.0 * t).gap - 2.0) <= 1e-14);
  CHECK(std::abs(slope.nearest(p0 - 1.5 * n - 3.0 * t).gap + 1.5) <= 1e-14);
  CHECK((slope.nearest(p0 - 1.5 * n).normal - n).norm() <= 1e-15);

  // A finite plate of radius 1 about p0: covered where the foot point is within 1 of p0,
  // on either side of the plate; beside it (foot 1.5 or 3 away) not covered.
  const RigidObstacle plate = RigidObstacle::plane("plate", p0, Eigen::Vector3d(6, 0, 8), 1.0);
  CHECK(plate.radius() == 1.0);
  CHECK(plate.nearest(p0 - 0.2 * n + 0.5 * t).covered);
  CHECK(plate.nearest(p0 + 0.2 * n + 0.99 * t).covered);
  CHECK_FALSE(plate.nearest(p0 - 0.2 * n + 1.5 * t).covered);
  CHECK_FALSE(plate.nearest(p0 - 0.2 * n + 3.0 * Eigen::Vector3d(0, 1, 0)).covered);
  // The gap is that of the infinite plane, covered or not.
  CHECK(std::abs(plate.nearest(p0 - 0.2 * n + 1.5 * t).gap + 0.2) <= 1e-14);
  // radius <= 0 means infinite.
  CHECK(RigidObstacle::plane("x", p0, n, -3.0).nearest(p0 + 1e6 * t).covered);

  // Bad input: a zero or non-finite normal.
  CHECK_THROWS(RigidObstacle::plane("x", p0, Eigen::Vector3d::Zero(), 0.0));
  CHECK_THROWS(RigidObstacle::plane(
      "x", p0, Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0, 0), 0.0));
}

TEST_CASE("obstacle contact: a sphere's gap and normal, hand values", "[contact]") {
  const Eigen::Vector3d c(0.1, -0.2, 0.3);
  const RigidObstacle ball = RigidObstacle::sphere("ball", c, 0.5);
  CHECK(std::string(ball.shapeName()) == "sphere");
  // (2, 3, 6) / 7 is a unit vector: a point 3 from the centre has gap 2.5, one 0.2 from
  // it gap -0.3 (round-off: a few ulp of coordinates ~3, 1e-14).
  const Eigen::Vector3d u = Eigen::Vector3d(2, 3, 6) / 7.0;
  const ObstaclePoint out = ball.nearest(c + 3.0 * u);
  CHECK(std::abs(out.gap - 2.5) <= 1e-14);
  CHECK((out.normal - u).norm() <= 1e-14);
  CHECK(out.covered);
  const ObstaclePoint in = ball.nearest(c - 0.2 * u);
  CHECK(std::abs(in.gap + 0.3) <= 1e-14);
  CHECK((in.normal + u).norm() <= 1e-14);  // out of the sphere through the nearer side
  // At the centre: radius deep, some unit normal.
  const ObstaclePoint centre = ball.nearest(c);
  CHECK(centre.gap == -0.5);
  CHECK(std::abs(centre.normal.norm() - 1.0) <= 1e-15);
  CHECK_THROWS(RigidObstacle::sphere("x", c, 0.0));
  CHECK_THROWS(RigidObstacle::sphere("x", c, -1.0));
}

TEST_CASE("obstacle contact: a cylinder's gap and normal, hand values", "[contact]") {
  // The axis through p along (1, 2, 2) / 3 (given unnormalised), radius 0.5.
  const Eigen::Vector3d p(1, -2, 0.5), d = Eigen::Vector3d(1, 2, 2) / 3.0;
  const RigidObstacle post = RigidObstacle::cylinder("post", p, 3.0 * d, 0.5);
  CHECK(std::string(post.shapeName()) == "cylinder");
  CHECK((post.normal() - d).norm() <= 1e-16);
  // (2, 2, -3) / sqrt(17) is perpendicular to d: a point 3 off the axis (and anywhere along
  // it) has gap 2.5 and that normal; one 0.2 off it gap -0.3 (round-off: a few ulp of
  // coordinates ~5, 1e-14).
  const Eigen::Vector3d u = Eigen::Vector3d(2, 2, -3) / std::sqrt(17.0);
  REQUIRE(std::abs(u.dot(d)) <= 1e-16);
  for (const double along : {0.0, -4.0, 7.5}) {
    const ObstaclePoint out = post.nearest(p + along * d + 3.0 * u);
    CHECK(std::abs(out.gap - 2.5) <= 1e-14);
    CHECK((out.normal - u).norm() <= 1e-14);
    CHECK(out.covered);
    const ObstaclePoint in = post.nearest(p + along * d - 0.2 * u);
    CHECK(std::abs(in.gap + 0.3) <= 1e-14);
    CHECK((in.normal + u).norm() <= 1e-14);
  }
  // On the axis: radius deep, a unit normal perpendicular to the axis.
  const ObstaclePoint axis = post.nearest(p + 2.0 * d);
  CHECK(std::abs(axis.gap + 0.5) <= 1e-15);
  CHECK(std::abs(axis.normal.norm() - 1.0) <= 1e-15);
  CHECK(std::abs(axis.normal.dot(d)) <= 1e-15);
  CHECK_THROWS(RigidObstacle::cylinder("x", p, d, 0.0));
  CHECK_THROWS(RigidObstacle::cylinder("x", p, Eigen::Vector3d::Zero(), 1.0));
}

TEST_CASE("obstacle contact: boxGap is a lower bound of the gap over the box, tight", "[contact]") {
  Draw draw(101);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d a = draw.vector(-2, 2), b = draw.vector(-2, 2);
    const Eigen::Vector3d lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    const Eigen::Vector3d normal = draw.vector(-1, 1) * draw(0.1, 10);
    const RigidObstacle plane =
        RigidObstacle::plane("p", draw.vector(-1, 1), normal, trial % 3 == 0 ? 0.7 : 0.0);
    const RigidObstacle sphere = RigidObstacle::sphere("s", draw.vector(-3, 3), draw(0.05, 1.5));
    const RigidObstacle cylinder =
        RigidObstacle::cylinder("c", draw.vector(-3, 3), draw.vector(-1, 1), draw(0.05, 1.5));
    const double planeBound = plane.boxGap(lo, hi), sphereBound = sphere.boxGap(lo, hi);
    const double cylinderBound = cylinder.boxGap(lo, hi);
    INFO("trial " << trial << ", box " << lo.transpose() << " .. " << hi.transpose());
    // A bound: no point of the box has a smaller gap. Round-off: a few ulp of the gaps
    // (coordinates ~5), 1e-14.
    for (int k = 0; k < 50; ++k) {
      Eigen::Vector3d x;
      for (int c = 0; c < 3; ++c) x(c) = draw(lo(c), hi(c));
      CHECK(planeBound <= plane.nearest(x).gap + 1e-14);
      CHECK(sphereBound <= sphere.nearest(x).gap + 1e-14);
      CHECK(cylinderBound <= cylinder.nearest(x).gap + 1e-14);
    }
    // The cylinder's bound (the centre's gap less half the diagonal) is off by at most the
    // diagonal: the gap is 1-Lipschitz.
    const Eigen::Vector3d mid = 0.5 * (lo + hi);
    CHECK(cylinder.nearest(mid).gap - cylinderBound <= (hi - lo).norm() + 1e-14);
    // Tight: the plane's bound is the gap of the box's corner lowest along n, the sphere's
    // that of the box's point nearest the centre (the centre clamped to the box; inside
    // the box: the centre itself, gap -R).
    Eigen::Vector3d corner;
    for (int c = 0; c < 3; ++c) corner(c) = plane.normal()(c) >= 0.0 ? lo(c) : hi(c);
    CHECK(std::abs(planeBound - plane.nearest(corner).gap) <= 1e-14);
    const Eigen::Vector3d clamped = sphere.point().cwiseMax(lo).cwiseMin(hi);
    CHECK(std::abs(sphereBound - sphere.nearest(clamped).gap) <= 1e-14);
  }
  // A degenerate box (a point) gives that point's gap.
  const RigidObstacle plane =
      RigidObstacle::plane("p", Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 2), 0.0);
  const Eigen::Vector3d x(3, 0, 0);
  CHECK(std::abs(plane.boxGap(x, x) - 1.0) <= 1e-15);
}

TEST_CASE("obstacle contact: which obstacles an axisymmetric scene allows", "[contact]") {
  const Eigen::Vector3d up(0, 1, 0), down(0, -3, 0), tilted(1e-3, 1, 0);
  // Infinite planes normal to the axis, wherever their point: the plane y = p_y.
  CHECK(RigidObstacle::plane("a", Eigen::Vector3d(3, 1, 2), up, 0.0).axisymmetric());
  CHECK(RigidObstacle::plane("a", Eigen::Vector3d(0, -1, 0), down, 0.0).axisymmetric());
  CHECK_FALSE(RigidObstacle::plane("a", Eigen::Vector3d::Zero(), tilted, 0.0).axisymmetric());
  CHECK_FALSE(RigidObstacle::plane("a", Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 1, 1e-9), 0.0)
                  .axisymmetric());
  // Finite plates: centred on the axis only.
  CHECK(RigidObstacle::plane("a", Eigen::Vector3d(0, 0.5, 0), up, 1.0).axisymmetric());
  CHECK_FALSE(RigidObstacle::plane("a", Eigen::Vector3d(0.1, 0.5, 0), up, 1.0).axisymmetric());
  CHECK_FALSE(RigidObstacle::plane("a", Eigen::Vector3d(0, 0.5, 0.1), up, 1.0).axisymmetric());
  // Spheres: centred on the axis only.
  CHECK(RigidObstacle::sphere("s", Eigen::Vector3d(0, 5, 0), 1.0).axisymmetric());
  CHECK_FALSE(RigidObstacle::sphere("s", Eigen::Vector3d(0, 5, 0.1), 1.0).axisymmetric());
  CHECK_FALSE(RigidObstacle::sphere("s", Eigen::Vector3d(1e-6, 5, 0), 1.0).axisymmetric());
  // Cylinders: coaxial only.
  CHECK(RigidObstacle::cylinder("c", Eigen::Vector3d(0, 5, 0), down, 1.0).axisymmetric());
  CHECK_FALSE(RigidObstacle::cylinder("c", Eigen::Vector3d(0, 5, 0), tilted, 1.0).axisymmetric());
  CHECK_FALSE(RigidObstacle::cylinder("c", Eigen::Vector3d(0.1, 5, 0), up, 1.0).axisymmetric());
}

TEST_CASE("obstacle contact: penalty forces of a flexible body on a plane, Eq. (17)-(18)",
          "[contact]") {
  Draw draw(202);
  const Cap cap = makeCap(3, draw);
  // A tilted floor through z ~ 0.2: the middle of the cap (z ~ 0.15 + r^2 0.15) is below
  // it, the rim above. The normal is given unnormalised.
  const Eigen::Vector3d p(0.02, -0.01, 0.2), normal(0.1, -0.05, 1.0);
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::VectorXd sp =
      positions(Eigen::Vector3d(0.01, -0.02, 0.005), Eigen::Vector4d(1, 0.01, -0.02, 0.015),
                Eigen::Vector3d(0.01, -0.02, 0.015));
  const std::vector<CapPoint> points = capPoints(cap, sp);
  const Eigen::Matrix3d A = rotationMatrix(sp.data() + 3);

  SECTION("infinite plane") {
    CapScene scene(cap, RigidObstacle::plane("floor", p, normal, 0.0), kPenalty, sp, draw);
    const Expected e = expectedContact(points, sp, planeGap(p, normal, 0.0), kPenalty);
    INFO("active " << e.active << " of " << points.size() << ", deepest " << e.deepest);
    REQUIRE(e.active >= 10);                                    // partly below ...
    REQUIRE(e.active <= static_cast<int>(points.size()) - 10);  // ... partly above
    // No point within 1e-9 m of the plane: the two routes to a point (1e-15 m apart) see
    // the same active set.
    REQUIRE(e.smallestAbsGap > 1e-9);

    std::vector<Eigen::VectorXd> h;
    std::vector<ContactState> st;
    scene.sys.contactForces(scene.y.data(), h, &st);
    REQUIRE(st.size() == 1);
    const ContactState& s = st[0];
    CHECK(s.active_points == e.active);
    CHECK((s.force - e.force).norm() <= kAbsForce);
    // The resultant is along the plane's normal: f_i all along n.
    CHECK((s.force - s.force.dot(n) * n).norm() <= kAbsForce);
    CHECK(s.force.dot(n) > 0.0);  // pushes the body out
    CHECK(std::abs(s.normal_force - e.force.norm()) <= kAbsForce);
    CHECK(std::abs(s.energy - e.energy) <= kAbsEnergy);       // sum 1/2 c_p g^2 w
    CHECK(std::abs(s.max_penetration - e.deepest) <= 1e-14);  // 1e-15 m routes, a few ulp
    CHECK(s.projection_failures == 0);
    CHECK(s.beyond_edge_penetration == 0.0);

    // Generalised forces (layout of s_v = [v, w, qdot] in body components): translational
    // part A^T F, the resultant; rotational part sum x_i x A^T f_i; elastic Phi_i^T A^T f_i.
    REQUIRE(h.size() == 1);
    REQUIRE(h[0].size() == 9);
    CHECK((A * h[0].head<3>() - s.force).norm() <= kAbsForce);
    CHECK((h[0].head<3>() - e.h.head<3>()).norm() <= kAbsForce);
    CHECK((h[0].segment<3>(3) - e.h.segment<3>(3)).norm() <= kAbsForce);
    CHECK((h[0].tail(3) - e.h.tail(3)).norm() <= kAbsForce);
    CHECK(e.h.tail(3).norm() > 1e-3);  // the elastic rows are exercised

    // evaluate() directly gives the same numbers bit for bit (the system calls it through
    // addForces with the same pose).
    ObstacleContact& pair = scene.contact();
    CHECK(pair.bodyA() == 0);
    CHECK(pair.bodyB() == -1);
    CHECK(pair.obstacleName() == "floor");
    CHECK(scene.sys.contactSideName(0, 1) == "floor");
    CHECK(scene.sys.contactSideName(0, 0) == "cap");
    Eigen::VectorXd hd = Eigen::VectorXd::Zero(9);
    ContactState sd;
    pair.evaluate(scene.sys.body(0), scene.sys.body(0).pose(sp.data()), hd.data(), &sd);
    CHECK(hd == h[0]);
    CHECK(sd.force == s.force);
    CHECK(sd.energy == s.energy);

    // The pressure field of that evaluation (runtime/contact/contact_pressure.h): one role,
    // every collocation point at its world position with c_p max(0, -g) by the hand gap
    // (the two routes to a point agree to ~2e-16 m, kAbsForce: 2e-12 Pa at c_p = 1e4 N/m^3;
    // bound 1e-10 Pa), and sum p_i w_i n_i the resultant (kAbsForce).
    const ContactPressure& field = pair.pressureField();
    REQUIRE(field.numRoles() == 1);
    REQUIRE(field.pressure.size() == static_cast<Eigen::Index>(points.size()));
    CHECK(field.factor == 1.0);
    Eigen::Vector3d resultant = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double gap = planeGap(p, normal, 0.0)(points[i].world).gap;
      const double expected = kPenalty * std::max(0.0, -gap);
      CHECK(std::abs(field.pressure(i) - expected) <= 1e-10);
      CHECK((field.position.row(i).transpose() - points[i].world).norm() <= 1e-14);
      CHECK(field.weight(i) == points[i].weight);
      resultant += field.pressure(i) * field.weight(i) * field.normal.row(i).transpose();
    }
    CHECK((resultant - s.force).norm() <= kAbsForce);
    // An evaluation without diagnostics (a Jacobian's, a projection's) leaves it; one with
    // the body lifted clear of the plane (apart, no work) clears it.
    const ContactPressure kept = field;
    pair.evaluate(scene.sys.body(0), scene.sys.body(0).pose(sp.data()), hd.data(), nullptr);
    CHECK(field.pressure == kept.pressure);
    Eigen::VectorXd lifted = sp;
    lifted.head<3>() += 10.0 * n;
    ContactState apart;  // evaluate() leaves it as given when apart (the system zeroes it)
    pair.evaluate(scene.sys.body(0), scene.sys.body(0).pose(lifted.data()), hd.data(), &apart);
    CHECK(apart.active_points == 0);
    CHECK(field.pressure.isZero(0.0));
  }

  SECTION("finite plate: only the points whose foot lies on it") {
    // A plate of radius 0.3 about p covers the middle of the cap: fewer points than the
    // infinite plane, but some.
    const double radius = 0.3;
    CapScene scene(cap, RigidObstacle::plane("plate", p, normal, radius), kPenalty, sp, draw);
    const Expected e = expectedContact(points, sp, planeGap(p, normal, radius), kPenalty);
    const Expected all = expectedContact(points, sp, planeGap(p, normal, 0.0), kPenalty);
    INFO("active " << e.active << " of " << all.active);
    REQUIRE(e.active > 0);
    REQUIRE(e.active < all.active);
    std::vector<Eigen::VectorXd> h;
    std::vector<ContactState> st;
    scene.sys.contactForces(scene.y.data(), h, &st);
    CHECK(st[0].active_points == e.active);
    CHECK((st[0].force - e.force).norm() <= kAbsForce);
    CHECK(std::abs(st[0].energy - e.energy) <= kAbsEnergy);
    CHECK((h[0] - e.h).cwiseAbs().maxCoeff() <= kAbsForce);
    CHECK(std::abs(scene.sys.deepestPenetration(scene.y.data(), 0).depth - e.deepest) <= 1e-14);
  }
}

TEST_CASE("obstacle contact: stiffness terms are the derivative of the forces", "[contact]") {
  // With the active set fixed, the forces against a plane are linear in the translation and
  // in q except for the lever arm of the rotational rows, x_i(q) x A^T f_i(q), quadratic in
  // q. The stiffness terms give d h / d s_p = -k bvC bpC^T per active point
  // (force_element.h), which neglects the lever arm's change (Phi_i dq) x A^T f_i; the test
  // adds that term, formed here, to the rotational rows. Central differences are then exact
  // but for the round-off of the two force evaluations, a few ulp of |h| each, divided by
  // the step: eps |h|max / step ~ 2e-16 * 20 N / 1e-6 m ~ 4e-9 N/m, as seen. The tolerance
  // is 100 times that, still 1e-5 of the smallest effect checked (the lever arm's change,
  // ~0.2 N/m per unit dq) and 1e-8 of the translational stiffness (~3e3 N/m).
  const CapOnTiltedPlane setting;
  const Cap& cap = setting.cap;
  const FloatingBody3d& body = setting.body;
  const Eigen::Vector3d &p = setting.p, &normal = setting.normal, &n = setting.n;
  const Eigen::VectorXd& sp = setting.sp;
  ContactOptions opt;
  opt.penalty = kPenalty;
  ObstacleContact pair("cap-floor", 0, body, 0, setting.floor(), opt);
  const Eigen::Matrix3d A = rotationMatrix(sp.data() + 3);
  const int nv = body.numVelocities();
  auto forces = [&](const Eigen::VectorXd& at, ContactState& s) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(nv);
    pair.evaluate(body, body.pose(at.data()), h.data(), &s);
    return h;
  };
  const std::vector<CapPoint> points = capPoints(cap, sp);
  const Expected e = expectedContact(points, sp, planeGap(p, normal, 0.0), kPenalty);
  // The steps below move a point by at most 1e-6 m: no point within 1e-4 m of the plane,
  // so the active set stays.
  REQUIRE(e.smallestAbsGap > 1e-4);
  ContactState s0;
  const Eigen::VectorXd h0 = forces(sp, s0);
  REQUIRE(s0.active_points == e.active);
  REQUIRE(s0.active_points >= 10);
  const std::vector<StiffnessTerm> terms = pair.stiffnessTerms();  // at sp: the last evaluate
  REQUIRE(static_cast<int>(terms.size()) == s0.active_points);
  for (const StiffnessTerm& t : terms) {
    CHECK(t.body_c == 0);
    CHECK(t.body_t == -1);                                    // the obstacle is fixed in space
    CHECK(t.k == Approx(kPenalty * kWeight).epsilon(1e-15));  // c_p w_i, N/m
    REQUIRE(t.bvC.size() == nv);
    REQUIRE(t.bpC.size() == body.numPositions());
  }
  auto predicted = [&](const Eigen::VectorXd& d) {
    Eigen::VectorXd dh = Eigen::VectorXd::Zero(nv);
    for (const StiffnessTerm& t : terms) dh -= t.k * t.bvC * t.bpC.dot(d);
    return dh;
  };
  // A hand value: moving the body along the plane's normal by dr lowers every active
  // point's force by k dr: dh_v = -(active k) A^T n (a sum of ~30 equal terms: round-off
  // ~30 ulp, hence 1e-12 relative).
  Eigen::VectorXd alongNormal = Eigen::VectorXd::Zero(10);
  alongNormal.head<3>() = n;
  const double kSum = s0.active_points * kPenalty * kWeight;
  CHECK((predicted(alongNormal).head<3>() + kSum * A.transpose() * n).norm() <= 1e-12 * kSum);

  Eigen::VectorXd elastic = Eigen::VectorXd::Zero(10);
  elastic(7 + 1) = 1.0;
  Eigen::VectorXd mixed = Eigen::VectorXd::Zero(10);
  mixed.head<3>() = Eigen::Vector3d(0.6, -0.8, 0.0);  // a tangential translation (mostly)
  mixed(7) = 1.0;
  mixed(9) = -0.5;
  const std::vector<std::pair<const char*, Eigen::VectorXd>> directions = {
      {"translation along n", alongNormal}, {"elastic q_1", elastic}, {"mixed", mixed}};
  const double step = 1e-6;
  const double tol =
      100.0 * std::numeric_limits<double>::epsilon() * h0.cwiseAbs().maxCoeff() / step;  // N/m
  for (const auto& [what, d] : directions) {
    INFO(what);
    ContactState sPlus, sMinus;
    const Eigen::VectorXd dhFd =
        (forces(sp + step * d, sPlus) - forces(sp - step * d, sMinus)) / (2.0 * step);
    REQUIRE(sPlus.active_points == s0.active_points);
    REQUIRE(sMinus.active_points == s0.active_points);
    Eigen::VectorXd dh = predicted(d);
    // The neglected change of lever arm, sum (Phi_i dq) x A^T f_i over the active points.
    Eigen::Vector3d lever = Eigen::Vector3d::Zero();
    for (const CapPoint& c : points) {
      const HandGap g = planeGap(p, normal, 0.0)(c.world);
      if (g.gap >= 0.0) continue;
      const Eigen::Vector3d fb = A.transpose() * (-kPenalty * g.gap * c.weight * g.n);
      lever += Eigen::Vector3d(c.Phi * d.tail(3)).cross(fb);
    }
    const double scale = dh.cwiseAbs().maxCoeff();
    INFO("tolerance " << tol << " N/m, finite differences " << dhFd.transpose()
                      << "\nstiffness terms " << dh.transpose() << "\nlever arm "
                      << lever.transpose());
    REQUIRE(scale > 1.0);
    CHECK((dhFd.head<3>() - dh.head<3>()).cwiseAbs().maxCoeff() <= tol);
    CHECK((dhFd.tail(3) - dh.tail(3)).cwiseAbs().maxCoeff() <= tol);
    CHECK((dhFd.segment<3>(3) - dh.segment<3>(3) - lever).cwiseAbs().maxCoeff() <= tol);
  }
}

TEST_CASE("obstacle contact with friction: Coulomb's bound and its terms", "[contact][friction]") {
  // The cap of the stiffness test on the same plane, moving: random s_v. Every active point
  // carries f_t = -mu f_n v_t / sqrt(|v_t|^2 + eps^2) (coulomb_friction.h), so the
  // tangential resultant stays below mu times the normal one, the friction's power is >= 0,
  // and the kFrictionDamping terms are d h / d s_v exactly (the positions are held: n, the
  // lever arms and the normal forces do not move), checked against central differences
  // whose truncation, O(step^2) relative to (step / eps)^2 = (1e-7 / 3e-3)^2 at |v_t| ~ eps,
  // and round-off, eps |h| / step ~ 2e-16 * 20 N / 1e-7 m/s = 4e-8 N s/m, sit below the
  // tolerance of 1e-6 relative to the largest term. The kFrictionLoad term with the normal
  // term gives d h / d s_p along the normal translation exactly (the points' velocities do
  // not depend on the translation): central differences as in the stiffness test.
  const CapOnTiltedPlane setting;
  const FloatingBody3d& body = setting.body;
  const Eigen::Vector3d& n = setting.n;
  const Eigen::VectorXd& sp = setting.sp;
  ContactOptions opt;
  opt.penalty = kPenalty;
  opt.friction.coefficient = 0.3;
  opt.friction.slip_velocity = 3e-3;  // m/s: some points stick, some slip (below)
  ObstacleContact pair("cap-floor", 0, body, 0, setting.floor(), opt);
  const int nv = body.numVelocities();
  Eigen::VectorXd sv(nv);
  sv << 2e-3, -1e-3, 5e-4, 3e-3, -2e-3, 1e-3, 0.01, -0.02, 0.015;
  auto forces = [&](const Eigen::VectorXd& at, const Eigen::VectorXd& vel, ContactState& st) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(nv);
    pair.evaluate(body, body.pose(at.data()), h.data(), &st, vel.data());
    return h;
  };
  ContactState s0;
  const Eigen::VectorXd h0 = forces(sp, sv, s0);
  REQUIRE(s0.active_points >= 10);
  CHECK(s0.sticking_points + s0.slipping_points == s0.active_points);
  CHECK(s0.sticking_points > 0);
  CHECK(s0.slipping_points > 0);
  CHECK(s0.tangential_force.dot(n) == Approx(0.0).margin(1e-12 * s0.normal_force));
  CHECK(s0.tangential_force.norm() < 0.3 * s0.normal_force);
  CHECK(s0.tangential_force.norm() > 0.01 * s0.normal_force);
  CHECK(s0.friction_power > 0.0);
  CHECK((s0.force - s0.tangential_force).norm() == Approx(s0.normal_force).epsilon(1e-14));
  // Frictionless, the same state: the normal force is the same; no tangential part.
  ContactOptions frictionless = opt;
  frictionless.friction = FrictionLaw{};
  ObstacleContact plain("cap-floor", 0, body, 0, setting.floor(), frictionless);
  Eigen::VectorXd hPlain = Eigen::VectorXd::Zero(nv);
  ContactState sPlain;
  plain.evaluate(body, body.pose(sp.data()), hPlain.data(), &sPlain);
  CHECK(sPlain.tangential_force.isZero(0.0));
  CHECK(sPlain.normal_force == Approx(s0.normal_force).epsilon(1e-14));

  const std::vector<StiffnessTerm> terms = pair.stiffnessTerms();  // at (sp, sv)
  int damping = 0, load = 0;
  for (const StiffnessTerm& t : terms) {
    damping += t.kind == StiffnessTerm::Kind::kFrictionDamping;
    load += t.kind == StiffnessTerm::Kind::kFrictionLoad;
  }
  CHECK(damping == 2 * s0.active_points);
  CHECK(load == s0.active_points);
  auto predicted = [&](const Eigen::VectorXd& d, bool velocities) {
    Eigen::VectorXd dh = Eigen::VectorXd::Zero(nv);
    for (const StiffnessTerm& t : terms)
      if (t.onVelocities() == velocities) dh -= t.k * t.bvC * t.bpC.dot(d);
    return dh;
  };
  const double step = 1e-7;
  for (int j = 0; j < nv; ++j) {
    INFO("velocity " << j);
    const Eigen::VectorXd d = Eigen::VectorXd::Unit(nv, j);
    ContactState a, b;
    const Eigen::VectorXd fd =
        (forces(sp, sv + step * d, a) - forces(sp, sv - step * d, b)) / (2.0 * step);
    const Eigen::VectorXd dh = predicted(d, true);
    REQUIRE(dh.cwiseAbs().maxCoeff() > 0.0);
    CHECK((fd - dh).cwiseAbs().maxCoeff() <= 1e-6 * dh.cwiseAbs().maxCoeff());
  }
  Eigen::VectorXd alongNormal = Eigen::VectorXd::Zero(10);
  alongNormal.head<3>() = n;
  ContactState a, b;
  const double dstep = 1e-6;
  const Eigen::VectorXd fd =
      (forces(sp + dstep * alongNormal, sv, a) - forces(sp - dstep * alongNormal, sv, b)) /
      (2.0 * dstep);
  REQUIRE(a.active_points == s0.active_points);
  REQUIRE(b.active_points == s0.active_points);
  const Eigen::VectorXd dh = predicted(alongNormal, false);
  const double tol =
      100.0 * std::numeric_limits<double>::epsilon() * h0.cwiseAbs().maxCoeff() / dstep;
  CHECK((fd - dh).cwiseAbs().maxCoeff() <= tol);
}

TEST_CASE("obstacle contact: deepest penetration and the box gap bound the points", "[contact]") {
  Draw draw(404);
  const Cap cap = makeCap(2, draw);
  const Eigen::Vector3d p(0.0, 0.03, 0.19), normal(0.05, 0.0, 1.0);
  const Eigen::Vector3d n = normal.normalized();
  CapScene scene(
      cap, RigidObstacle::plane("floor", p, normal, 0.0), kPenalty,
      positions(Eigen::Vector3d::Zero(), Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector2d::Zero()),
      draw);
  int touching = 0;
  for (int trial = 0; trial < 30; ++trial) {
    // Random poses: turned by up to ~0.1 rad, shifted by up to 5 cm, deformed; every
    // fourth lifted by 0.5 m along n, clear of the plane.
    const Eigen::Vector3d r = draw.vector(-0.05, 0.05) + (trial % 4 == 3 ? 0.5 : 0.0) * n;
    const Eigen::Vector4d quaternion(1, draw(-0.05, 0.05), draw(-0.05, 0.05), draw(-0.05, 0.05));
    const Eigen::VectorXd sp =
        positions(r, quaternion, Eigen::Vector2d(draw(-0.05, 0.05), draw(-0.05, 0.05)));
    scene.setPositions(sp);
    const Expected e = expectedContact(capPoints(cap, sp), sp, planeGap(p, normal, 0.0), kPenalty);
    INFO("trial " << trial << ": deepest " << e.deepest << ", smallest gap " << e.smallestGap);
    const Penetration pen = scene.sys.deepestPenetration(scene.y.data(), 0);
    // The two routes to a point agree to ~1e-15 m; the depth is one gap: 1e-14.
    CHECK(std::abs(pen.depth - e.deepest) <= 1e-14);
    if (e.deepest > 0.0) {
      ++touching;
      CHECK(pen.contact_body == 0);
      CHECK((pen.point - e.deepestPoint).norm() <= 1e-14);
    } else {
      CHECK(pen.contact_body == -1);
      CHECK(pen.depth == 0.0);
    }
    // The approach control's gap is a lower bound of every point's gap (the surface lies in
    // its control points' hull). Exact comparison: the bound is below by the hull's slack
    // (the control net lies off the surface and the box is wider than the tilted net:
    // 4-7 cm seen), far beyond round-off.
    const double bound = scene.sys.contactGap(scene.y.data());
    CHECK(bound <= e.smallestGap);
    if (trial % 4 == 3) {
      CHECK(bound > 0.0);  // lifted: the box is clear of the plane
      // Apart: no force, no active point, an empty state.
      std::vector<Eigen::VectorXd> h;
      std::vector<ContactState> st;
      scene.sys.contactForces(scene.y.data(), h, &st);
      CHECK(h[0].isZero(0.0));
      CHECK(st[0].active_points == 0);
      CHECK(st[0].energy == 0.0);
      CHECK(scene.contact().stiffnessTerms().empty());
    }
  }
  CHECK(touching >= 15);
}

TEST_CASE("obstacle contact: a sphere pushes along (x - c) / |x - c|", "[contact]") {
  Draw draw(505);
  const Cap cap = makeCap(3, draw);
  const Eigen::VectorXd sp =
      positions(Eigen::Vector3d(-0.01, 0.02, 0.01), Eigen::Vector4d(1, 0.02, 0.01, -0.01),
                Eigen::Vector3d(0.015, 0.01, -0.02));
  const Eigen::Matrix3d A = rotationMatrix(sp.data() + 3);
  const std::vector<CapPoint> points = capPoints(cap, sp);

  SECTION("one point inside a small sphere: its force along the sphere's normal there") {
    // A sphere of radius 2 cm whose surface passes 1 mm above the cap's lowest collocation
    // point, approached from an oblique direction m (the points are >= ~0.1 m apart: no
    // other point is inside).
    const auto lowest = std::min_element(
        points.begin(), points.end(),
        [](const CapPoint& a, const CapPoint& b) { return a.world(2) < b.world(2); });
    const Eigen::Vector3d x = lowest->world;
    const Eigen::Vector3d m = Eigen::Vector3d(0.3, -0.2, -1.0).normalized();
    const double R = 0.02, depth = 1e-3;
    const Eigen::Vector3d c = x - (R - depth) * m;
    CapScene scene(cap, RigidObstacle::sphere("pebble", c, R), kPenalty, sp, draw);
    std::vector<Eigen::VectorXd> h;
    std::vector<ContactState> st;
    scene.sys.contactForces(scene.y.data(), h, &st);
    REQUIRE(st[0].active_points == 1);
    // Direction (x - c) / |x - c| = m, magnitude c_p w depth (0.1 N). Round-off: x and c
    // are known to ~2e-16 m (coordinates < 1 m), which turns a direction of length 2e-2 m by
    // ~1e-14 and changes the depth by ~1e-16 m, the force by 1e-14 N (seen: 4e-16, 3e-15).
    const Eigen::Vector3d direction = (x - c).normalized();
    CHECK((direction - m).norm() <= 1e-14);
    CHECK((st[0].force.normalized() - direction).norm() <= 1e-14);
    CHECK(std::abs(st[0].normal_force - kPenalty * kWeight * depth) <= 1e-13);
    CHECK(std::abs(st[0].max_penetration - depth) <= 1e-15);
    CHECK((A * h[0].head<3>() - st[0].force).norm() <= 1e-15);  // a rotation of 0.1 N
    // Its moment about the body frame's origin: x_i x A^T f (lever < 1.5 m).
    CHECK((h[0].segment<3>(3) - lowest->body.cross(A.transpose() * st[0].force)).norm() <= 1e-14);
  }

  SECTION("a large sphere under the cap: the sum over the points") {
    const Eigen::Vector3d c(0.05, -0.02, -0.8);
    const double R = 1.05;  // top at z = 0.25: the middle of the cap (z ~ 0.16) inside
    CapScene scene(cap, RigidObstacle::sphere("dome", c, R), kPenalty, sp, draw);
    const Expected e = expectedContact(points, sp, sphereGap(c, R), kPenalty);
    INFO("active " << e.active);
    REQUIRE(e.active >= 5);
    REQUIRE(e.smallestAbsGap > 1e-9);  // the same active set by both routes
    std::vector<Eigen::VectorXd> h;
    std::vector<ContactState> st;
    scene.sys.contactForces(scene.y.data(), h, &st);
    CHECK(st[0].active_points == e.active);
    CHECK((st[0].force - e.force).norm() <= kAbsForce);
    CHECK(std::abs(st[0].energy - e.energy) <= kAbsEnergy);
    CHECK((h[0] - e.h).cwiseAbs().maxCoeff() <= kAbsForce);
    // Not along a single direction: the normals spread over the sphere, so the resultant
    // is shorter than the sum of the forces' magnitudes (by far more than round-off).
    CHECK(e.force.norm() < (1.0 - 1e-6) * e.magnitudes);
    CHECK(std::abs(scene.sys.deepestPenetration(scene.y.data(), 0).depth - e.deepest) <= 1e-14);
    CHECK(scene.sys.contactGap(scene.y.data()) <= e.smallestGap);
  }
}

// --- Scenes with obstacles whose checks need a SID ------------------------------------------

namespace {

// A rigid axisymmetric sphere of radius R (m): the meridian half circle from the bottom
// pole to the top pole (rational quadratic), all of it the contact surface, collocation
// points at its Greville abscissae (the bottom pole among them) with weight 1e-4 m.
FlexibleBodySid ball2d(double R) {
  const double h = 1.0 / std::sqrt(2.0);
  Eigen::MatrixXd P(5, 2);
  P << 0, -R, R, -R, R, 0, R, R, 0, R;
  Eigen::VectorXd w(5);
  w << 1, h, 1, h, 1;
  const NurbsPatch arc({KnotVector({0, 0, 0, 0.5, 0.5, 1, 1, 1}, 2)}, P, w);
  FlexibleBodySid sid;
  sid.name = "ball";
  sid.model = ffriga::ModelKind::kAxisymmetric;
  sid.space_dim = 2;
  sid.mass = 7850.0 * 4.0 / 3.0 * M_PI * R * R * R;
  sid.inertia = Eigen::Matrix3d::Identity() * 0.4 * sid.mass * R * R;
  sid.Me = sid.Ke = sid.De = Eigen::MatrixXd(0, 0);
  sid.Ct = sid.Cr0 = Eigen::MatrixXd(0, 3);
  sid.control_points = arc.points();
  sid.weights = arc.weights();
  sid.Phi = Eigen::MatrixXd(2 * arc.numControlPoints(), 0);
  ContactSurface s = test::bezierExtract(arc, 1.0);
  test::addGrevilleCollocation(arc, s, 1e-4);
  sid.surfaces.push_back(s);
  return sid;
}

// The scene's SID name resolves to a placeholder file; the loader hands over `sid`.
SidLoader ballLoader(const FlexibleBodySid& sid) {
  std::ofstream("obstacle_ball.sid.h5") << "placeholder";
  return [sid](const std::string&, SidContent) { return sid; };
}

// A ball of radius 1 cm, 0.1 mm above a floor y = 0, falling.
const char* kBallScene = R"(name: ball_on_floor
bodies:
  - name: ball
    sid: obstacle_ball.sid.h5
    position: [0, 0.0101, 0]
    velocity: [0, -0.1, 0]
obstacles:
  - name: floor
    plane: {point: [0, 0, 0], normal: [0, 1, 0]}
contacts:
  - bodies: [ball, floor]
    penalty_factor: 1.0e13
integrator: {end_time: 1.0e-4, output_interval: 1.0e-6}
)";

std::string sceneError(const std::string& text) {
  try {
    buildScene(parseYamlText(text, "scene.yaml"), {}, ballLoader(ball2d(0.01)));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("obstacle contact scene: a ball over a floor builds one obstacle pair", "[contact]") {
  const Scene scene =
      buildScene(parseYamlText(kBallScene, "scene.yaml"), {}, ballLoader(ball2d(0.01)));
  const MultibodySystem& sys = *scene.system;
  REQUIRE(sys.numContacts() == 1);
  const auto* pair = dynamic_cast<const ObstacleContact*>(&sys.contact(0));
  REQUIRE(pair != nullptr);
  CHECK(pair->name() == "ball-floor");  // default name: the two names of the pair
  CHECK(pair->obstacle().shape() == RigidObstacle::Shape::kPlane);
  CHECK(pair->obstacleName() == "floor");
  CHECK(sys.contactSideName(0, 0) == "ball");
  CHECK(sys.contactSideName(0, 1) == "floor");
  // 0.1 mm apart at t = 0: the bottom pole is the nearest point (round-off of 1e-2 m
  // coordinates: 1e-17 m).
  std::vector<Eigen::VectorXd> h;
  std::vector<ContactState> st;
  Eigen::VectorXd y = scene.y0;
  scene.system->contactForces(y.data(), h, &st);
  CHECK(st[0].active_points == 0);
  CHECK(std::abs(scene.system->contactGap(y.data()) - 1e-4) <= 1e-16);
  // The body named second works as well: the body is side A whichever order the file gives.
  const Scene swapped = buildScene(
      parseYamlText(test::replaced(kBallScene, "bodies: [ball, floor]", "bodies: [floor, ball]"),
                    "scene.yaml"),
      {}, ballLoader(ball2d(0.01)));
  CHECK(swapped.system->contact(0).bodyA() == 0);
  CHECK(swapped.system->contactSideName(0, 1) == "floor");
}

TEST_CASE("obstacle contact scene: bad obstacles name file, line and key", "[contact]") {
  CHECK(sceneError(kBallScene) == "no error");
  // An axisymmetric scene: a plane tilted off the axis, a plate or a sphere off it.
  CHECK_THAT(sceneError(test::replaced(kBallScene, "normal: [0, 1, 0]", "normal: [0.1, 1, 0]")),
             Catch::Contains("scene.yaml:9: key 'obstacles[0].plane'") &&
                 Catch::Contains("an axisymmetric scene needs a plane normal to its axis"));
  CHECK_THAT(sceneError(test::replaced(kBallScene, "{point: [0, 0, 0], normal: [0, 1, 0]}",
                                 "{point: [0.2, 0, 0], normal: [0, 1, 0], radius: 0.5}")),
             Catch::Contains("scene.yaml:9: key 'obstacles[0].plane'") &&
                 Catch::Contains("finite ones centred on it"));
  CHECK_THAT(sceneError(test::replaced(kBallScene, "plane: {point: [0, 0, 0], normal: [0, 1, 0]}",
                                 "sphere: {centre: [0.001, -1, 0], radius: 1.0}")),
             Catch::Contains("scene.yaml:9: key 'obstacles[0].sphere'") &&
                 Catch::Contains("an axisymmetric scene needs a sphere centred on its axis"));
  // A plane normal along -y is normal to the axis (the floor is a ceiling then).
  CHECK(sceneError(test::replaced(kBallScene, "{point: [0, 0, 0], normal: [0, 1, 0]}",
                            "{point: [0, 0.1, 0], normal: [0, -1, 0]}")) == "no error");
  // The ball placed 5 mm into the floor: its bottom pole is 5 mm deep.
  CHECK_THAT(
      sceneError(test::replaced(kBallScene, "position: [0, 0.0101, 0]", "position: [0, 0.005, 0]")),
      Catch::Contains("scene.yaml:11: key 'contacts[0]'") &&
          Catch::Contains("'ball' and 'floor' start 0.005 m into each other") &&
          Catch::Contains("key penetration_tolerance"));
  // ... and 5 mm into a sphere on the axis below it.
  CHECK_THAT(sceneError(test::replaced(kBallScene, "plane: {point: [0, 0, 0], normal: [0, 1, 0]}",
                                 "sphere: {centre: [0, -0.0049, 0], radius: 0.01}")),
             Catch::Contains("scene.yaml:11: key 'contacts[0]'") &&
                 Catch::Contains("'ball' and 'floor' start 0.005 m into each other"));
}

TEST_CASE("contact regions: a pair names BODY.REGION of a body with several", "[contact]") {
  // The ball with two contact surfaces (the same arc twice, named top and bottom).
  FlexibleBodySid two = ball2d(0.01);
  two.surfaces[0].name = "top";
  two.surfaces.push_back(two.surfaces[0]);
  two.surfaces[1].name = "bottom";
  auto build = [&](const std::string& text) {
    return buildScene(parseYamlText(text, "scene.yaml"), {}, ballLoader(two));
  };
  auto error = [&](const std::string& text) -> std::string {
    try {
      build(text);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string named = test::replaced(kBallScene, "bodies: [ball, floor]", "bodies: [ball.bottom, floor]");
  const Scene scene = build(named);
  CHECK(scene.system->contact(0).regionName(0) == "bottom");
  CHECK(scene.system->contact(0).regionName(1).empty());
  CHECK(scene.system->contact(0).name() == "ball.bottom-floor");  // default: the two entries
  // bodies[].surface names the region where the pair does not.
  const Scene bySurface = build(test::replaced(kBallScene, "velocity: [0, -0.1, 0]",
                                         "velocity: [0, -0.1, 0]\n    surface: bottom"));
  CHECK(bySurface.system->contact(0).regionName(0) == "bottom");
  // Without a name the choice is the user's to make; unknown names list the regions.
  CHECK_THAT(error(kBallScene),
             Catch::Contains("scene.yaml:11: key 'contacts[0].bodies[0]'") &&
                 Catch::Contains("body 'ball' has 2 contact regions (top, bottom): name one, "
                                 "as ball.top"));
  CHECK_THAT(error(test::replaced(kBallScene, "bodies: [ball, floor]", "bodies: [ball.side, floor]")),
             Catch::Contains("key 'contacts[0].bodies[0]'") &&
                 Catch::Contains("body 'ball' has no contact region 'side' (its regions: top, "
                                 "bottom)"));
  CHECK_THAT(error(test::replaced(named, "[ball.bottom, floor]", "[ball.bottom, floor.top]")),
             Catch::Contains("key 'contacts[0].bodies[1]'") &&
                 Catch::Contains("obstacle 'floor' has no contact regions"));
  CHECK_THAT(error(test::replaced(named, "  - name: ball\n", "  - name: ba.ll\n")),
             Catch::Contains("key 'bodies[0].name'") &&
                 Catch::Contains("a body name cannot contain '.'"));
}

namespace {

// One body's state as the force elements see it (a contact's initialAnchors).
struct OneBodyContext : ForceContext {
  OneBodyContext(const BodyModel& b, const Eigen::VectorXd& sp)
      : model(b), positions_(sp), pose_(b.pose(sp.data())) {}
  const BodyModel& body(int) const override { return model; }
  const double* positions(int) const override { return positions_.data(); }
  const double* velocities(int) const override { return nullptr; }
  const BodyPose& pose(int) const override { return pose_; }
  const BodyModel& model;
  Eigen::VectorXd positions_;
  BodyPose pose_;
};

}  // namespace

TEST_CASE("obstacle contact with anchored friction: stick, slip and their terms",
          "[contact][friction]") {
  // The cap of the stiffness test on the same plane with stick anchors (coulomb_friction.h
  // AnchoredFriction): each active point's anchor is put off its point along a random
  // tangent by a multiple m of the slip limit mu |g| (c_t = c_p), m < 1 sticking, m > 1
  // slipping, so the law's hand values hold: a sticking point carries -c_p w d and its
  // anchor rests, a slipping one carries mu f_n along -d and its anchor moves at
  // (m - 1) mu |g| / eta; an anchor out of contact rests, and followAnchors puts it back on
  // its point (the projection between steps) leaving the others where they are.
  // The terms (their columns on the anchors and the anchors' rows) are checked against
  // central differences in every anchor and in the three translations: the forces and rates
  // are linear or smooth there (no point within 0.3 mu |g| of the slip limit, steps of
  // 1e-4 of the smallest), so the differences are exact to their round-off (below) and to
  // 1e-6 of the largest term.
  const CapOnTiltedPlane setting;
  const FloatingBody3d& body = setting.body;
  const Eigen::Vector3d &n = setting.n, &p = setting.p;
  const Eigen::VectorXd& sp = setting.sp;
  const double mu = 0.3, eta = 1e-3;
  ContactOptions opt;
  opt.penalty = kPenalty;
  opt.friction.coefficient = mu;
  opt.friction.anchored = true;
  opt.friction.relaxation_time = eta;
  ObstacleContact pair("cap-floor", 0, body, 0, setting.floor(), opt);
  const int na = pair.numAnchors(), nv = body.numVelocities();
  REQUIRE(na > 0);
  REQUIRE(na % 3 == 0);
  Eigen::VectorXd x0(na);
  pair.initialAnchors(OneBodyContext(body, sp), x0.data());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
  const double multiples[4] = {0.3, 0.7, 1.3, 2.5};
  const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  Eigen::VectorXd z = x0, expectedRate = Eigen::VectorXd::Zero(na);
  int stick = 0, slip = 0, active = 0;
  for (int i = 0; i < na / 3; ++i) {
    const Eigen::Vector3d x = x0.segment<3>(3 * i);
    const double g = n.dot(x - p), phi = angle(rng);
    const Eigen::Vector3d t = std::cos(phi) * t1 + std::sin(phi) * t2;
    if (g >= 0.0) {  // out of contact: any offset, at rest
      z.segment<3>(3 * i) -= 1e-3 * t;
      continue;
    }
    const double m = multiples[active++ % 4];
    z.segment<3>(3 * i) -= m * mu * (-g) * t;  // d = x - z = m mu |g| t
    (m < 1.0 ? stick : slip)++;
    if (m > 1.0) expectedRate.segment<3>(3 * i) = (m - 1.0) * mu * (-g) / eta * t;
  }
  REQUIRE(stick >= 4);
  REQUIRE(slip >= 4);
  auto evaluate = [&](const Eigen::VectorXd& at, const Eigen::VectorXd& anchors, ContactState& s,
                      Eigen::VectorXd& rate) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(nv);
    pair.evaluate(body, body.pose(at.data()), h.data(), &s, nullptr, anchors.data());
    rate = pair.anchorRates();
    return h;
  };
  ContactState s0;
  Eigen::VectorXd rate0;
  const Eigen::VectorXd h0 = evaluate(sp, z, s0, rate0);
  CHECK(s0.active_points == active);
  CHECK(s0.sticking_points == stick);
  CHECK(s0.slipping_points == slip);
  CHECK((rate0 - expectedRate).cwiseAbs().maxCoeff() <= 1e-12 * expectedRate.cwiseAbs().maxCoeff());
  CHECK(s0.tangential_force.dot(n) == Approx(0.0).margin(1e-12 * s0.normal_force));
  CHECK(s0.tangential_force.norm() < mu * s0.normal_force);
  CHECK(s0.friction_power > 0.0);
  const std::vector<StiffnessTerm> terms = pair.stiffnessTerms();
  // The predicted changes of h and of the anchors' rates for a change ds of the positions
  // and dz of the anchors.
  auto predicted = [&](const Eigen::VectorXd& ds, const Eigen::VectorXd& dz, Eigen::VectorXd& dh,
                       Eigen::VectorXd& drate) {
    dh = Eigen::VectorXd::Zero(nv);
    drate = Eigen::VectorXd::Zero(na);
    for (const StiffnessTerm& t : terms) {
      double v = t.bpC.dot(ds);
      if (t.anchor >= 0) v += t.aV.dot(dz.segment(t.anchor, t.aV.size()));
      dh -= t.k * t.bvC * v;
      if (t.anchor >= 0) drate.segment(t.anchor, t.aU.size()) += t.aU * v;
    }
  };
  // The steps: 1e-4 of the smallest slip limit of an active point (no point crosses its
  // limit or the plane). Round-off: eps |x| / eta of every rate and eps |h| of every force,
  // per evaluation, over the step.
  double limit = std::numeric_limits<double>::infinity();
  for (int i = 0; i < na / 3; ++i) {
    const double g = n.dot(x0.segment<3>(3 * i) - p);
    if (g < 0.0) limit = std::min(limit, mu * -g);
  }
  const double step = 1e-4 * limit, eps = std::numeric_limits<double>::epsilon();
  const double roundoffRate = 10.0 * eps * x0.cwiseAbs().maxCoeff() / eta / step;
  // followAnchors: the anchors out of contact back on their points, the others held.
  Eigen::VectorXd followed = z;
  pair.followAnchors(OneBodyContext(body, sp), followed.data());
  for (int i = 0; i < na / 3; ++i) {
    const bool out = n.dot(x0.segment<3>(3 * i) - p) >= 0.0;
    CHECK(followed.segment<3>(3 * i) == (out ? x0 : z).segment<3>(3 * i));
  }
  const double roundoffForce = 10.0 * eps * h0.cwiseAbs().maxCoeff() / step;
  auto compare = [&](const Eigen::VectorXd& ds, const Eigen::VectorXd& dz) {
    ContactState a, b;
    Eigen::VectorXd ra, rb, dh, drate;
    const Eigen::VectorXd fd = (evaluate(sp + step * ds, z + step * dz, a, ra) -
                                evaluate(sp - step * ds, z - step * dz, b, rb)) /
                               (2.0 * step);
    REQUIRE(a.sticking_points == stick);
    REQUIRE(b.sticking_points == stick);
    REQUIRE(a.active_points == active);
    REQUIRE(b.active_points == active);
    predicted(ds, dz, dh, drate);
    const Eigen::VectorXd fdRate = (ra - rb) / (2.0 * step);
    CHECK((fd - dh).cwiseAbs().maxCoeff() <= 1e-6 * dh.cwiseAbs().maxCoeff() + roundoffForce);
    CHECK((fdRate - drate).cwiseAbs().maxCoeff() <=
          1e-6 * drate.cwiseAbs().maxCoeff() + roundoffRate);
  };
  const Eigen::VectorXd noS = Eigen::VectorXd::Zero(sp.size()), noZ = Eigen::VectorXd::Zero(na);
  for (int j = 0; j < na; ++j) {
    INFO("anchor entry " << j);
    compare(noS, Eigen::VectorXd::Unit(na, j));
  }
  for (int j = 0; j < 3; ++j) {
    INFO("translation " << j);
    compare(Eigen::VectorXd::Unit(sp.size(), j), noZ);
  }
}

TEST_CASE("obstacle contact scene: anchored friction adds the anchors; a pair refuses it",
          "[contact][friction]") {
  // The ball over the floor with friction_law anchored: two anchor entries per collocation
  // point (axisymmetric) after the ball's state, each on its point at the start (followed
  // points: the initial state is the projection's), at the atol of rtol times the surface's
  // size.
  const std::string anchored = test::replaced(
      kBallScene, "    penalty_factor: 1.0e13\n",
      "    penalty_factor: 1.0e13\n    friction_coefficient: 0.2\n    friction_law: anchored\n");
  const Scene scene =
      buildScene(parseYamlText(anchored, "scene.yaml"), {}, ballLoader(ball2d(0.01)));
  const MultibodySystem& sys = *scene.system;
  const SurfaceContact& pair = sys.contact(0);
  const int na = pair.numAnchors();
  REQUIRE(na > 0);
  CHECK(na % 2 == 0);
  CHECK(sys.anchorOffset(0) == sys.velocityOffset(0) + sys.body(0).numVelocities());
  CHECK(sys.size() == sys.anchorOffset(0) + na);
  REQUIRE(scene.y0.size() == sys.size());
  // The bottom pole (a collocation point) sits at height 0.0001 m on the axis.
  double lowest = 1.0;
  for (int i = 0; i < na / 2; ++i)
    lowest = std::min(lowest, scene.y0(sys.anchorOffset(0) + 2 * i + 1));
  CHECK(lowest == Approx(1e-4).epsilon(1e-12));
  CHECK(scene.settings.integrator.atol(sys.anchorOffset(0)) ==
        Approx(scene.settings.integrator.rtol * pair.surfaceSize()).epsilon(1e-15));
  // Two bodies: not yet (one line, the key named).
  const std::string two =
      test::replaced(test::replaced(anchored, "obstacles:\n",
                                    "  - name: ball2\n    sid: obstacle_ball.sid.h5\n"
                                    "    position: [0, 0.0302, 0]\nobstacles:\n"),
                     "bodies: [ball, floor]", "bodies: [ball, ball2]");
  CHECK_THAT(sceneError(two), Catch::Contains("key 'contacts[0].friction_law'") &&
                                  Catch::Contains("between a body and an obstacle only"));
}
