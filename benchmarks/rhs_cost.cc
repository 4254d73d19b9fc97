// Cost of the right-hand side against nq (issue 10: it should grow like nq, not nq^2).
//
//   rhs_cost SID.sid.h5 [REPEATS] [NQ ...]
//
// The head-on impact of impact3d_*.yaml: two bodies of the SID, the upper one turned by
// 180 degrees about x, pressed into each other by Hertz's largest approach of the
// 0.2 m/s impact (about 5.6 um for the steel spheres), so that the contact has the active
// points of the force peak. For each NQ (default: 8 values from 50 to the SID's nq) the
// body is reduced to its first NQ coordinates: every invariant of a mode subset is the
// sub-block of the full one (Ct, Cr0 rows, Cr1 and J1 of those modes, Me, Ke, De blocks),
// so each sub-body is a consistent SID of that size. Times, as medians over REPEATS
// evaluations (default 41) at states that differ in q (a new q at every call, as in the
// integrator: random, of size 1e-6 of the approach in mass-normalised units, the change
// between two evaluations of a step), with qdot = 0 beyond the first 10 coordinates (the
// quasi-static ones, runtime/bodies/quasi_static_modes.h):
//   inertial  FloatingBody3d::accelerations of both bodies under the frozen contact load,
//   contact   MultibodySystem::contactForces (both roles, both bodies),
//   rhs       MultibodySystem::rhs (everything),
// in microseconds, and the exponent b of rhs ~ nq^b by least squares over the NQ values.
// The last line is the same data as one JSON object.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "common/sid/sid_file.h"
#include "runtime/bodies/floating_body.h"
#include "runtime/contact/contact_pair.h"
#include "common/mechanics/hertz.h"
#include "runtime/system/multibody_system.h"

namespace {

using ffriga::FlexibleBodySid;

// The SID of the first n coordinates (sub-blocks; sid.h's invariants are per mode).
FlexibleBodySid firstModes(const FlexibleBodySid& s, int n) {
  FlexibleBodySid r = s;
  r.frequencies_hz = s.frequencies_hz.head(n);
  r.Me = s.Me.topLeftCorner(n, n);
  r.Ke = s.Ke.topLeftCorner(n, n);
  r.De = s.De.topLeftCorner(n, n);
  r.Ct = s.Ct.topRows(n);
  r.Cr0 = s.Cr0.topRows(n);
  r.Oe = s.Oe.rows() ? Eigen::MatrixXd(s.Oe.topRows(n)) : s.Oe;
  r.damping_ratio = s.damping_ratio.head(n);
  r.Cr1.resize(n);
  for (int j = 0; j < n; ++j) r.Cr1[j] = s.Cr1[j].leftCols(n);
  r.J1.assign(s.J1.begin(), s.J1.begin() + n);
  r.Phi = s.Phi.leftCols(n);
  for (auto& m : r.markers)
    if (m.Psi.cols()) m.Psi = Eigen::MatrixXd(m.Psi.leftCols(n));
  r.mesh = ffriga::VisualisationMesh();
  r.stress_lines.clear();
  return r;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Row {
  int nq = 0;
  int active = 0;
  double inertial_us = 0.0, contact_us = 0.0, rhs_us = 0.0;
};

Row measure(const FlexibleBodySid& full, int nq, int repeats) {
  using Clock = std::chrono::steady_clock;
  auto sid = std::make_shared<FlexibleBodySid>(firstModes(full, nq));
  ffriga::MultibodySystem sys;
  sys.addBody(std::make_unique<ffriga::FloatingBody3d>("lower", sid));
  sys.addBody(std::make_unique<ffriga::FloatingBody3d>("upper", sid));
  ffriga::ContactOptions opt;
  opt.penalty = 1e17;  // N/m^3, as the scenes
  sys.addForceElement(std::make_unique<ffriga::ContactPair>("impact", 0, sys.body(0), 0, 1,
                                                       sys.body(1), 0, opt));
  // Hertz's largest approach of the 0.2 m/s impact of two such spheres.
  const double R = sid->geometry.radius;
  const ffriga::HertzImpact hz = ffriga::hertzImpact(
      {sid->material.youngs_modulus, sid->material.poisson_ratio, R, sid->mass},
      {sid->material.youngs_modulus, sid->material.poisson_ratio, R, sid->mass}, 0.2);
  const int n = sys.size();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n), ydot(n);
  const int p0 = sys.positionOffset(0), p1 = sys.positionOffset(1);
  const Eigen::Vector3d c = sid->geometry.centre;  // body frame (sid.h)
  // Lower: identity; upper: turned about x by pi, its sphere centre at 2 R - delta above.
  y.segment(p0, 7) << -c(0), -c(1), -c(2), 1, 0, 0, 0;
  const Eigen::Vector3d cu(c(0), -c(1), -c(2));  // centre turned about x
  y.segment(p1, 7) << -cu(0), -cu(1), 2 * R - hz.max_approach - cu(2), 0, 1, 0, 0;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const double qScale = 1e-6 * hz.max_approach * std::sqrt(sid->mass);
  auto perturb = [&] {
    for (int b = 0; b < 2; ++b)
      for (int j = 0; j < nq; ++j) y(sys.positionOffset(b) + 7 + j) = qScale * uni(rng);
  };
  for (int b = 0; b < 2; ++b)
    for (int j = 0; j < std::min(nq, 10); ++j) y(sys.velocityOffset(b) + 6 + j) = 1e-3 * uni(rng);
  Row row;
  row.nq = nq;
  std::vector<double> tin, tco, trhs;
  std::vector<Eigen::VectorXd> h;
  for (int k = 0; k < repeats + 2; ++k) {  // two warm-up evaluations
    perturb();
    auto t0 = Clock::now();
    std::vector<ffriga::ContactState> states;
    sys.contactForces(y.data(), h, &states);
    auto t1 = Clock::now();
    for (int b = 0; b < 2; ++b)
      sys.body(b).accelerations(y.data() + sys.positionOffset(b), y.data() + sys.velocityOffset(b),
                                h[b].data(), Eigen::Vector3d::Zero(),
                                ydot.data() + sys.velocityOffset(b));
    auto t2 = Clock::now();
    perturb();
    auto t3 = Clock::now();
    sys.rhs(0.0, y.data(), ydot.data());
    auto t4 = Clock::now();
    if (k < 2) continue;
    row.active = states[0].active_points;
    tco.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    tin.push_back(std::chrono::duration<double, std::micro>(t2 - t1).count());
    trhs.push_back(std::chrono::duration<double, std::micro>(t4 - t3).count());
  }
  row.inertial_us = median(tin);
  row.contact_us = median(tco);
  row.rhs_us = median(trhs);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: rhs_cost SID.sid.h5 [REPEATS] [NQ ...]\n");
    return 2;
  }
  try {
    const FlexibleBodySid full = ffriga::readSid(argv[1]);
    const int repeats = argc > 2 ? std::atoi(argv[2]) : 41;
    std::vector<int> nqs;
    for (int a = 3; a < argc; ++a) nqs.push_back(std::atoi(argv[a]));
    if (nqs.empty()) {
      const int top = full.nq();
      for (int k = 0; k < 8; ++k)
        nqs.push_back(static_cast<int>(std::lround(50.0 * std::pow(top / 50.0, k / 7.0))));
    }
    std::printf("SID %s: nq = %d, %d evaluations per size (medians, microseconds)\n", argv[1],
                full.nq(), repeats);
    std::printf("%6s %7s %11s %11s %11s\n", "nq", "active", "inertial", "contact", "rhs");
    std::vector<Row> rows;
    for (int nq : nqs) {
      if (nq < 1 || nq > full.nq()) {
        std::fprintf(stderr, "rhs_cost: NQ %d outside 1 .. %d\n", nq, full.nq());
        return 2;
      }
      rows.push_back(measure(full, nq, repeats));
      const Row& r = rows.back();
      std::printf("%6d %7d %11.1f %11.1f %11.1f\n", r.nq, r.active, r.inertial_us, r.contact_us,
                  r.rhs_us);
      std::fflush(stdout);
    }
    // Least-squares slope of log(time) against log(nq).
    auto slope = [&](double Row::*field) {
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      const double m = static_cast<double>(rows.size());
      for (const Row& r : rows) {
        const double x = std::log(r.nq), yv = std::log(r.*field);
        sx += x, sy += yv, sxx += x * x, sxy += x * yv;
      }
      return (m * sxy - sx * sy) / (m * sxx - sx * sx);
    };
    const double bi = slope(&Row::inertial_us), bc = slope(&Row::contact_us),
                 br = slope(&Row::rhs_us);
    std::printf("exponent b (time ~ nq^b, least squares): inertial %.2f, contact %.2f, rhs %.2f\n",
                bi, bc, br);
    std::printf("{\"sid\": \"%s\", \"repeats\": %d, \"exponent_inertial\": %.4f, "
                "\"exponent_contact\": %.4f, \"exponent_rhs\": %.4f, \"rows\": [",
                argv[1], repeats, bi, bc, br);
    for (std::size_t i = 0; i < rows.size(); ++i)
      std::printf("%s{\"nq\": %d, \"active_points\": %d, \"inertial_us\": %.3f, "
                  "\"contact_us\": %.3f, \"rhs_us\": %.3f}",
                  i ? ", " : "", rows[i].nq, rows[i].active, rows[i].inertial_us,
                  rows[i].contact_us, rows[i].rhs_us);
    std::printf("]}\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rhs_cost: %s\n", e.what());
    return 1;
  }
  return 0;
}
