#include <catch2/catch.hpp>

#include "runtime/integration/bdf_integrator.h"
#include "runtime/contact/closest_point.h"
#include "runtime/contact/contact_pair.h"
#include "runtime/bodies/floating_body.h"
#include "runtime/system/multibody_system.h"
#include "tests/support/surface_fixtures.h"
#include "tests/support/synthetic_bodies.h"
#include "tests/support/test_util.h"

using namespace ffriga;

namespace {

// A curved rational surface over [0,1]^2: a bumpy cap z = 0.3 (1 - (x^2 + y^2)) + noise, with
// random weights and an interior knot per direction (p = 2, 3).
NurbsPatch curvedPatch(double zsign, double z0) {
  std::vector<KnotVector> U = {KnotVector({0, 0, 0, 0.4, 1, 1, 1}, 2),
                               KnotVector({0, 0, 0, 0, 0.6, 1, 1, 1, 1}, 3)};
  const int n0 = U[0].numBasis(), n1 = U[1].numBasis();
  Eigen::MatrixXd P(n0 * n1, 3);
  Eigen::VectorXd w(n0 * n1);
  for (int j = 0; j < n1; ++j) {
    for (int i = 0; i < n0; ++i) {
      const double x = -1.0 + 2.0 * i / (n0 - 1), y = -1.0 + 2.0 * j / (n1 - 1);
      P.row(i + n0 * j) << x, y,
          z0 + zsign * (0.3 * (1.0 - 0.5 * (x * x + y * y)) + 0.02 * test::uniform(-1, 1));
      w(i + n0 * j) = test::uniform(0.6, 1.4);
    }
  }
  return NurbsPatch(U, P, w);
}

// A body whose point masses sit at the patch's control points (random modes), carrying the
// patch as its contact surface.
FlexibleBodySid surfaceBody(const NurbsPatch& patch, double outward, int nq) {
  FlexibleBodySid sid;
  const int N = patch.numControlPoints();
  Eigen::MatrixXd Phi = 0.05 * Eigen::MatrixXd::Random(3 * N, nq);
  test::pointMassInvariants(sid, Eigen::VectorXd::Ones(N), patch.points(), Phi,
                            Eigen::MatrixXd::Identity(3 * N, 3 * N));
  sid.weights = patch.weights();
  ContactSurface s = test::bezierExtract(patch, outward);
  test::addGrevilleCollocation(patch, s, 1e-2);
  sid.surfaces.push_back(s);
  return sid;
}

// Body A: cap opening downwards facing +z at z ~ 0.3; body B: cap facing -z placed so that
// the two overlap by a few 1e-2 near the middle (3 elastic coordinates each).
std::pair<std::shared_ptr<FlexibleBodySid>, std::shared_ptr<FlexibleBodySid>> facingCaps() {
  auto a = std::make_shared<FlexibleBodySid>(surfaceBody(curvedPatch(1.0, 0.0), 1.0, 3));
  auto b = std::make_shared<FlexibleBodySid>(surfaceBody(curvedPatch(-1.0, 0.45), 1.0, 3));
  // Orientation of B's normal: x_s0 x x_s1 points +z for both patches; B's outside is -z.
  b->surfaces[0].outward_sign = -1.0;
  return {a, b};
}

// Positions and elastic coordinates of facingCaps' A and B (7 + 3 entries each) where the
// caps, slightly turned and deformed, overlap near the middle.
std::pair<Eigen::VectorXd, Eigen::VectorXd> overlappingStates() {
  Eigen::VectorXd spA(7 + 3), spB(7 + 3);
  spA << 0.01, -0.02, 0.0, 1.0, 0.01, -0.02, 0.03, 0.01, -0.02, 0.015;
  spB << -0.01, 0.02, 0.0, 1.0, -0.02, 0.01, 0.02, -0.01, 0.02, 0.01;
  return {spA, spB};
}

}  // namespace

TEST_CASE("closest point: Newton finds the nearest point of curved NURBS surfaces", "[contact]") {
  for (int trial = 0; trial < 5; ++trial) {
    const NurbsPatch patch = curvedPatch(1.0, 0.0);
    const ContactSurface cs = test::bezierExtract(patch);
    const ExtractedSurface surf(cs, patch.weights());
    // Brute force: a 201 x 201 parameter grid.
    const int ng = 201;
    std::vector<Eigen::Vector3d> grid;
    for (int j = 0; j < ng; ++j)
      for (int i = 0; i < ng; ++i) {
        const double s[2] = {i / (ng - 1.0), j / (ng - 1.0)};
        grid.push_back(patch.evaluate(s, 0).x);
      }
    for (int k = 0; k < 40; ++k) {
      // Points around the surface, some beyond its edges and on either side.
      const Eigen::Vector3d x(test::uniform(-1.2, 1.2), test::uniform(-1.2, 1.2),
                              test::uniform(-0.3, 0.8));
      double best = 1e300;
      for (const auto& g : grid) best = std::min(best, (g - x).norm());
      const SurfaceProjection p = closestPoint(surf, patch.points(), x, nullptr);
      REQUIRE(p.converged);
      const double dist = (p.point.x - x).norm();
      // The minimiser is at least as close as every sample (to round-off), and the samples
      // (spacing 0.005 in s, |dx/ds| <= ~3) come within ~1e-2 of it.
      REQUIRE(dist <= best * (1.0 + 1e-12) + 1e-14);
      REQUIRE(best - dist <= 1e-2);
      // Eq. (15) holds at foot points flagged orthogonal (to the edge tolerance 1e-6 at the
      // domain boundary, to Newton's tolerance inside).
      if (p.orthogonal) {
        const Eigen::Vector2d g = p.point.dx.transpose() * (x - p.point.x);
        for (int a = 0; a < 2; ++a)
          REQUIRE(std::abs(g(a)) <= 1e-6 * p.point.dx.col(a).norm() * dist);
      }
    }
  }
}

TEST_CASE("closest point: points just off the surface have proper foot points", "[contact]") {
  // A contact point a few nm from the target (the penetrations of a penalty contact) must
  // project orthogonally: a point dropped as "beyond the edge" switches its force off
  // discontinuously and stalls the integrator (seen with sphere2d_h6).
  const NurbsPatch patch = curvedPatch(1.0, 0.0);
  const ContactSurface cs = test::bezierExtract(patch);
  const ExtractedSurface surf(cs, patch.weights());
  for (int k = 0; k < 200; ++k) {
    const double s[2] = {test::uniform(0.05, 0.95), test::uniform(0.05, 0.95)};
    const PatchPoint foot = patch.evaluate(s, 1);
    const Eigen::Vector3d t0 = foot.dx.col(0), t1 = foot.dx.col(1);
    const Eigen::Vector3d n = t0.cross(t1).normalized();
    const double offset = (k % 2 ? 1.0 : -1.0) * std::pow(10.0, test::uniform(-14.0, -6.0));
    const Eigen::Vector3d x = foot.x + offset * n;
    const SurfaceProjection p = closestPoint(surf, patch.points(), x, nullptr);
    REQUIRE(p.converged);
    REQUIRE(p.orthogonal);
    // The foot point is s itself: its distance is |offset| up to Newton's tangential
    // tolerance (1e-12 times the surface size ~2, squared in the normal distance) and
    // a few ulp of coordinates of size ~1.
    CHECK(std::abs((p.point.x - x).dot(n) + offset) <= 1e-14);
    CHECK((p.point.x - foot.x).norm() <= 1e-10);
  }
}

TEST_CASE("contact forces: equal and opposite, and the gradient of the penalty energy",
          "[contact]") {
  const auto [a, b] = facingCaps();
  FloatingBody3d A("A", a), B("B", b);
  ContactOptions opt;
  opt.penalty = 1e4;
  ContactPair pair("A-B", 0, A, 0, 1, B, 0, opt);
  const auto [spA, spB] = overlappingStates();
  auto forces = [&](const Eigen::VectorXd& pa, const Eigen::VectorXd& pb, Eigen::VectorXd& hA,
                    Eigen::VectorXd& hB, ContactState& st) {
    hA.setZero(9);
    hB.setZero(9);
    pair.evaluate(A, A.pose(pa.data()), B, B.pose(pb.data()), hA.data(), hB.data(), &st);
  };
  Eigen::VectorXd hA, hB;
  ContactState st;
  forces(spA, spB, hA, hB, st);
  INFO("active " << st.active_points << " failures " << st.projection_failures << " pen "
                 << st.max_penetration);
  REQUIRE(st.active_points > 0);
  REQUIRE(st.projection_failures == 0);
  // Equal and opposite resultants (inertial components), to round-off.
  const Eigen::Vector3d FA = A.pose(spA.data()).A * hA.head<3>();
  const Eigen::Vector3d FB = B.pose(spB.data()).A * hB.head<3>();
  REQUIRE((FA + FB).norm() <= 1e-12 * FA.norm());
  REQUIRE((FA - st.force).norm() <= 1e-12 * FA.norm());
  // Elastic generalised forces are minus the gradient of the penalty energy (envelope
  // theorem at the closest point, Eq. 15-18). Central differences, step 1e-7: error
  // O(h^2 E''') plus round-off 1e-16 E / h; 1e-5 relative is safe.
  const double h = 1e-7;
  for (int side = 0; side < 2; ++side) {
    for (int j = 0; j < 3; ++j) {
      Eigen::VectorXd p1 = side == 0 ? spA : spB, p2 = p1;
      p1(7 + j) += h;
      p2(7 + j) -= h;
      Eigen::VectorXd ha, hb;
      ContactState s1, s2;
      if (side == 0) {
        forces(p1, spB, ha, hb, s1);
        forces(p2, spB, ha, hb, s2);
      } else {
        forces(spA, p1, ha, hb, s1);
        forces(spA, p2, ha, hb, s2);
      }
      const double dE = (s1.energy - s2.energy) / (2 * h);
      const double gen = side == 0 ? hA(6 + j) : hB(6 + j);
      INFO("side " << side << " mode " << j << ": -dE/dq " << -dE << ", h_q " << gen);
      REQUIRE(std::abs(-dE - gen) <= 1e-5 * hA.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("contact pressure field: c_p max(0, -g_n) of both roles, its resultant the force",
          "[contact]") {
  const auto [a, b] = facingCaps();
  FloatingBody3d A("A", a), B("B", b);
  ContactOptions opt;
  opt.penalty = 1e4;
  ContactPair pair("A-B", 0, A, 0, 1, B, 0, opt);
  const auto [spA, spB] = overlappingStates();
  Eigen::VectorXd hA = Eigen::VectorXd::Zero(9), hB = Eigen::VectorXd::Zero(9);
  ContactState st;
  pair.evaluate(A, A.pose(spA.data()), B, B.pose(spB.data()), hA.data(), hB.data(), &st);
  REQUIRE(st.active_points > 0);
  const ContactPressure& field = pair.pressureField();
  REQUIRE(field.numRoles() == 2);
  CHECK(field.factor == 0.5);
  const int nA = static_cast<int>(a->surfaces[0].collocation_weights.size());
  CHECK(field.offset(1) == nA);
  // Role r's force on its own body is sum p_i w_i n_i; the pair's on A is the half
  // difference. Both are the sums evaluate() forms, in another order: round-off of ~100
  // terms of size |F|, 1e-12 |F| is safe.
  Eigen::Vector3d onA = Eigen::Vector3d::Zero();
  int active = 0;
  double deepest = 0.0;
  for (Eigen::Index i = 0; i < field.pressure.size(); ++i) {
    const double p = field.pressure(i);
    REQUIRE(p >= 0.0);
    if (p == 0.0) {
      CHECK(field.normal.row(i).isZero(0.0));
      continue;
    }
    ++active;
    deepest = std::max(deepest, p / opt.penalty);
    CHECK(std::abs(field.normal.row(i).norm() - 1.0) <= 1e-14);
    const double sign = field.role[i] == 0 ? 1.0 : -1.0;
    onA += sign * field.factor * p * field.weight(i) * field.normal.row(i).transpose();
  }
  CHECK(active == st.active_points);
  CHECK(std::abs(deepest - st.max_penetration) <= 1e-15 * st.max_penetration);
  CHECK((onA - st.force).norm() <= 1e-12 * st.force.norm());
  // Positions: where the points are (A's points in A's frame are the undeformed collocation
  // points plus Phi_i q, within the caps' size of the origin).
  CHECK(field.position.cwiseAbs().maxCoeff() < 2.0);
  // An evaluation without diagnostics leaves the field; one with the bodies apart clears it.
  const ContactPressure kept = field;
  pair.evaluate(A, A.pose(spA.data()), B, B.pose(spB.data()), hA.data(), hB.data(), nullptr);
  CHECK(field.pressure == kept.pressure);
  Eigen::VectorXd away = spB;
  away(2) += 10.0;
  REQUIRE(pair.boxGap(A, A.pose(spA.data()), B, B.pose(away.data())) > 1.0);
  ContactState apart;  // evaluate() leaves it as given when apart (the system zeroes it)
  pair.evaluate(A, A.pose(spA.data()), B, B.pose(away.data()), hA.data(), hB.data(), &apart);
  CHECK(field.pressure.isZero(0.0));
}

TEST_CASE("3D contact in time: two tumbling flexible bodies collide, momenta are kept",
          "[contact]") {
  // Cap B (facing -z) falls onto cap A (facing +z) while both tumble; the contact forces
  // are equal and opposite and act along the common normal (x_C - x_T is parallel to n at
  // the closest point), so linear and angular momentum are conserved through the impact.
  auto a = std::make_shared<FlexibleBodySid>(surfaceBody(curvedPatch(1.0, 0.0), 1.0, 2));
  auto b = std::make_shared<FlexibleBodySid>(surfaceBody(curvedPatch(-1.0, 0.6), -1.0, 2));
  MultibodySystem sys;
  sys.addBody(std::make_unique<FloatingBody3d>("A", a));
  sys.addBody(std::make_unique<FloatingBody3d>("B", b));
  ContactOptions opt;
  opt.penalty = 1e5;  // N/m^3: ~1e3 N/m per collocation point of weight 1e-2 m^2
  sys.addForceElement(std::make_unique<ContactPair>("A-B", 0, sys.body(0), 0, 1, sys.body(1), 0, opt));
  const int n = sys.size();
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(n);
  // Positions: r, quaternion, q; velocities: v, w, qdot (body components).
  y0.segment(0, 7) << 0, 0, 0, 1, 0, 0, 0;
  y0.segment(9, 7) << 0.02, -0.01, 0.05, 1, 0.01, 0.02, 0;
  const int va = sys.velocityOffset(0), vb = sys.velocityOffset(1);
  y0.segment(va, 6) << 0, 0, 0.2, 0.3, -0.2, 0.1;
  y0.segment(vb, 6) << 0.05, 0, -0.6, -0.1, 0.2, 0.3;
  Eigen::Vector3d L0, H0, L1, H1;
  sys.normalize(y0.data());
  sys.momentum(y0.data(), L0, H0);
  IntegratorOptions o;
  o.rtol = 1e-10;
  o.atol = Eigen::VectorXd::Constant(n, 1e-12);
  BdfIntegrator integ(sys, 0.0, y0, o);
  Eigen::VectorXd y;
  double maxForce = 0.0;
  for (int k = 1; k <= 20; ++k) {
    integ.advance(0.02 * k, y);
    std::vector<ContactState> st;
    std::vector<Eigen::VectorXd> h;
    sys.contactForces(y.data(), h, &st);
    maxForce = std::max(maxForce, st[0].normal_force);
  }
  sys.momentum(y.data(), L1, H1);
  INFO("max force " << maxForce << " N, L " << (L1 - L0).norm() / L0.norm() << ", H "
                    << (H1 - H0).norm() / H0.norm() << ", steps " << integ.stats().steps);
  REQUIRE(maxForce > 1.0);  // they did collide
  // Integration error of rtol 1e-10 through a penalty impact: 1e-7 relative is safe.
  REQUIRE((L1 - L0).norm() <= 1e-7 * L0.norm());
  REQUIRE((H1 - H0).norm() <= 1e-7 * H0.norm());
}

TEST_CASE("contact pair rejects a surface whose normals point into the body", "[contact]") {
  auto a = std::make_shared<FlexibleBodySid>(surfaceBody(curvedPatch(1.0, 0.0), 1.0, 1));
  auto b = std::make_shared<FlexibleBodySid>(surfaceBody(curvedPatch(-1.0, 0.6), 1.0, 1));
  FloatingBody3d A("A", a), B("B", b);
  ContactOptions opt;
  opt.penalty = 1e4;
  // B's patch has x_s0 x x_s1 along +z, into the body (its outside is -z): sign +1 is wrong.
  REQUIRE_THROWS_WITH(ContactPair("A-B", 0, A, 0, 1, B, 0, opt),
                      Catch::Contains("points toward the centre of mass"));
}

TEST_CASE("contact clearance bound: a pair with history gives the forces of a full search",
          "[contact]") {
  // A persistent pair skips the searches of points its clearance bound proves in front of
  // the target (contact_pair.h); a fresh pair searches every point. Along an approach,
  // contact and separation with tumbling and deformation, their forces, active points and
  // energies must agree; they differ only by the closest-point searches' warm starts
  // (tolerance 1e-12 of the length scale), hence 1e-9 relative, and by round-off in the gap
  // of points just entering contact (whose force is ~0): about 50 ulps of the coordinates,
  // 1e-14 L, on at most the surface's area L^2, with lever arms up to L (L = surface size).
  const auto [a, b] = facingCaps();
  FloatingBody3d A("A", a), B("B", b);
  ContactOptions opt;
  opt.penalty = 1e4;
  ContactPair kept("A-B", 0, A, 0, 1, B, 0, opt);
  int contactStates = 0;
  for (int k = 0; k <= 200; ++k) {
    // B moves down by 0.1 and back up in 200 steps, turning slightly; both deform.
    const double t = k / 200.0, lift = 0.1 * (1.0 - std::sin(M_PI * t)) - 0.03;
    Eigen::VectorXd spA(7 + 3), spB(7 + 3);
    spA << 0.0, 0.0, 0.0, 1.0, 0.02 * t, 0.0, 0.0, 0.01 * std::sin(7 * t), -0.02 * t, 0.01;
    spB << 0.01 * t, -0.01, lift, 1.0, 0.0, 0.03 * t, 0.0, 0.0, 0.02 * std::cos(5 * t), -0.01 * t;
    spA.segment<4>(3).normalize();
    spB.segment<4>(3).normalize();
    ContactPair fresh("A-B", 0, A, 0, 1, B, 0, opt);
    Eigen::VectorXd hA1 = Eigen::VectorXd::Zero(9), hB1 = hA1, hA2 = hA1, hB2 = hA1;
    ContactState s1, s2;
    kept.evaluate(A, A.pose(spA.data()), B, B.pose(spB.data()), hA1.data(), hB1.data(), &s1);
    fresh.evaluate(A, A.pose(spA.data()), B, B.pose(spB.data()), hA2.data(), hB2.data(), &s2);
    INFO("step " << k << ": active " << s1.active_points << " / " << s2.active_points);
    REQUIRE(s1.active_points == s2.active_points);
    REQUIRE(s1.projection_failures == s2.projection_failures);
    const double L = kept.surfaceSize();
    const double scale = std::max(1e-300, hA2.cwiseAbs().maxCoeff());
    const double roundOff = opt.penalty * L * L * 1e-14 * L * std::max(1.0, L);
    CHECK((hA1 - hA2).cwiseAbs().maxCoeff() <= 1e-9 * scale + roundOff);
    CHECK((hB1 - hB2).cwiseAbs().maxCoeff() <= 1e-9 * scale + roundOff);
    CHECK(std::abs(s1.energy - s2.energy) <= 1e-9 * std::max(1e-300, s2.energy));
    if (s2.active_points > 0) ++contactStates;
  }
  INFO("searches " << kept.searches() << ", avoided " << kept.searchesAvoided());
  CHECK(contactStates > 20);
  CHECK(contactStates < 190);  // they also separate
  // The bound pays: most points are not searched at most states.
  CHECK(kept.searchesAvoided() > kept.searches());
}

namespace {

// A flat square face [x0, x0 + 1] x [0, 1] at height z, bilinear with one interior knot per
// direction (Greville points: 4 per direction, the edges included), facing `outward` z.
FlexibleBodySid flatFace(double x0, double z, double outward) {
  std::vector<KnotVector> U = {KnotVector({0, 0, 0, 0.5, 1, 1, 1}, 2),
                               KnotVector({0, 0, 0, 0.5, 1, 1, 1}, 2)};
  const int n = U[0].numBasis();
  Eigen::MatrixXd P(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) P.row(i + n * j) << x0 + i / (n - 1.0), j / (n - 1.0), z;
  const NurbsPatch patch(U, P, Eigen::VectorXd::Ones(n * n));
  // Point masses at the control points and one as heavy as them all behind the face's
  // middle (the body's inside: the pair checks that normals point away from its centre).
  const int N = n * n;
  Eigen::MatrixXd X(N + 1, 3);
  X.topRows(N) = P;
  X.row(N) << x0 + 0.5, 0.5, z - 0.5 * outward;
  Eigen::VectorXd m = Eigen::VectorXd::Ones(N + 1);
  m(N) = N;
  FlexibleBodySid sid;
  test::pointMassInvariants(sid, m, X, 0.05 * Eigen::MatrixXd::Random(3 * (N + 1), 2),
                            Eigen::MatrixXd::Identity(3 * (N + 1), 3 * (N + 1)));
  sid.weights = Eigen::VectorXd::Ones(N + 1);
  ContactSurface cs = test::bezierExtract(patch, outward);
  test::addGrevilleCollocation(patch, cs, 1e-2);
  sid.surfaces.push_back(cs);
  return sid;
}

}  // namespace

TEST_CASE("flat faces end-on: edge points just beside the other face are held by its plane",
          "[contact]") {
  // A faces +z at z = 0; B faces -z at z = -delta (overlap delta), shifted by eps along x, so
  // that A's edge points at x = 0 lie eps beside B's edge x = eps (the lateral mismatch of
  // two equal end faces strained slightly differently).
  const double delta = 1e-6, eps = 2e-4;
  auto a = std::make_shared<FlexibleBodySid>(flatFace(0.0, 0.0, 1.0));
  auto b = std::make_shared<FlexibleBodySid>(flatFace(eps, -delta, -1.0));
  FloatingBody3d A("A", a), B("B", b);
  Eigen::VectorXd s(7 + 2);
  s << 0, 0, 0, 1, 0, 0, 0, 0, 0;  // at the origin, undeformed
  const int nA = static_cast<int>(a->surfaces[0].collocation_weights.size());
  const int edge = 4;  // A's points with x = 0 (Greville 0 of the 4 in x, each row in y)
  for (const double reach : {0.0, 1e-3}) {
    ContactOptions opt;
    opt.penalty = 1e10;
    opt.both_roles = false;  // A's points against B
    opt.edge_reach = reach;
    ContactPair pair("A-B", 0, A, 0, 1, B, 0, opt);
    Eigen::VectorXd hA = Eigen::VectorXd::Zero(8), hB = Eigen::VectorXd::Zero(8);
    ContactState st;
    pair.evaluate(A, A.pose(s.data()), B, B.pose(s.data()), hA.data(), hB.data(), &st);
    if (reach == 0.0) {
      // Only proper foot points: the edge row gets no force and is reported beyond the edge
      // at the overlap's depth (behind both tangent planes).
      CHECK(st.active_points == nA - edge);
      CHECK(std::abs(st.beyond_edge_penetration - delta) <= 1e-12 * delta);
    } else {
      // Held by B's plane: every point at the overlap, the force c_p delta sum w on A, along
      // -z (away from B, into A's inside).
      CHECK(st.active_points == nA);
      CHECK(st.beyond_edge_penetration == 0.0);
      // Depths are differences of unit coordinates: round-off 1e-16 against delta = 1e-6.
      CHECK(std::abs(st.max_penetration - delta) <= 1e-9 * delta);
      const double expected = opt.penalty * delta * a->surfaces[0].collocation_weights.sum();
      CHECK(std::abs(st.force.z() + expected) <= 1e-9 * expected);
      CHECK(std::abs(st.force.x()) + std::abs(st.force.y()) <= 1e-12 * expected);
    }
  }
}

TEST_CASE("contact pair with friction: equal and opposite, Coulomb's bound, terms on both bodies",
          "[contact][friction]") {
  // The overlapping caps of the tests above, pressed 0.04 further together, moving with random
  // velocities, mu = 0.3 and a slip velocity at which some points stick and some slip. Every active
  // point of both roles carries f_t = -mu f_n v_t / s with v_t the relative velocity of its
  // collocation point and its foot point (coulomb_friction.h): the resultants on A and B stay equal
  // and opposite, the tangential one below mu times the normal one, the power >= 0, the traction
  // field's resultant is the tangential force; and the kFrictionDamping terms are d h / d s_v of
  // both bodies exactly (positions held: normals, foot points and normal forces fixed),
  // against central differences with the truncation and round-off of the obstacle's
  // friction test (obstacle_contact_test.cc): 1e-6 of the largest term.
  const auto [a, b] = facingCaps();
  FloatingBody3d A("A", a), B("B", b);
  ContactOptions opt;
  opt.penalty = 1e4;
  opt.friction.coefficient = 0.3;
  opt.friction.slip_velocity = 1e-2;  // m/s: |v_t| 0.008-0.015 here
  ContactPair pair("A-B", 0, A, 0, 1, B, 0, opt);
  const auto [spA, spB0] = overlappingStates();
  Eigen::VectorXd spB = spB0;
  spB(2) -= 0.12;  // pressed further in: more active points
  Eigen::VectorXd sv(18);
  sv << 2e-3, -1e-3, 5e-4, 3e-3, -2e-3, 1e-3, 0.01, -0.02, 0.015,  // A
      2e-3, -1e-3, 5e-4, -2e-3, 1e-3, 2e-2, -0.01, 0.005, 0.02;    // B: spun about z
  auto forces = [&](const Eigen::VectorXd& v, ContactState* st) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(18);
    pair.evaluate(A, A.pose(spA.data()), B, B.pose(spB.data()), h.data(), h.data() + 9, st,
                  v.data(), v.data() + 9);
    return h;
  };
  ContactState s0;
  const Eigen::VectorXd h0 = forces(sv, &s0);
  REQUIRE(s0.active_points > 10);
  REQUIRE(s0.projection_failures == 0);
  CHECK(s0.sticking_points > 0);
  CHECK(s0.slipping_points > 0);
  CHECK(s0.sticking_points + s0.slipping_points == s0.active_points);
  const Eigen::Vector3d FA = A.pose(spA.data()).A * h0.head<3>();
  const Eigen::Vector3d FB = B.pose(spB.data()).A * h0.segment<3>(9);
  CHECK((FA + FB).norm() <= 1e-12 * FA.norm());
  CHECK((FA - s0.force).norm() <= 1e-12 * FA.norm());
  CHECK(s0.tangential_force.norm() > 0.01 * s0.normal_force);
  CHECK(s0.tangential_force.norm() < 0.3 * s0.normal_force);
  CHECK(s0.friction_power > 0.0);
  // The traction field: role r's tangential force on its own body is sum t_i w_i factor.
  const ContactPressure& field = pair.pressureField();
  Eigen::Vector3d tOnA = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < field.pressure.size(); ++i) {
    if (field.pressure(i) == 0.0) CHECK(field.traction.row(i).isZero(0.0));
    CHECK(std::abs(field.traction.row(i).dot(field.normal.row(i))) <= 1e-12 * field.pressure(i));
    const double sign = field.role[i] == 0 ? 1.0 : -1.0;
    tOnA += sign * field.factor * field.weight(i) * field.traction.row(i).transpose();
  }
  CHECK((tOnA - s0.tangential_force).norm() <= 1e-12 * s0.tangential_force.norm());

  const std::vector<StiffnessTerm> terms = pair.stiffnessTerms();
  int damping = 0, load = 0;
  for (const StiffnessTerm& t : terms) {
    damping += t.kind == StiffnessTerm::Kind::kFrictionDamping;
    load += t.kind == StiffnessTerm::Kind::kFrictionLoad;
  }
  CHECK(damping == 2 * s0.active_points);
  CHECK(load == s0.active_points);
  // d h / d s_v from the terms: -k [bvC; -bvT] [bpC; -bpT]^T over the stacked velocities.
  auto stacked = [](int body, const Eigen::VectorXd& c, int other, const Eigen::VectorXd& t) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(18);
    x.segment(9 * body, 9) += c;
    x.segment(9 * other, 9) -= t;
    return x;
  };
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(18, 18);
  for (const StiffnessTerm& t : terms) {
    if (!t.onVelocities()) continue;
    K -= t.k * stacked(t.body_c, t.bvC, t.body_t, t.bvT) *
         stacked(t.body_c, t.bpC, t.body_t, t.bpT).transpose();
  }
  const double step = 1e-7;
  for (int j = 0; j < 18; ++j) {
    INFO("velocity " << j);
    const Eigen::VectorXd d = Eigen::VectorXd::Unit(18, j);
    const Eigen::VectorXd fd =
        (forces(sv + step * d, nullptr) - forces(sv - step * d, nullptr)) / (2.0 * step);
    CHECK((fd - K.col(j)).cwiseAbs().maxCoeff() <= 1e-6 * K.cwiseAbs().maxCoeff());
  }
}
