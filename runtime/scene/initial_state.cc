#include "runtime/scene/initial_state.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace ffriga {

namespace {

// Body b's entries of y0 and atol.
void assembleBody(const BodyModel& body, bool axisymmetric, const InitialPose& in,
                  const AbsoluteTolerances& tol, double* sp, double* sv, double* ap, double* av) {
  const int nr = body.numRigidPositions(), nv = body.numRigidVelocities();
  const double sq = std::sqrt(body.sid().mass);
  if (axisymmetric) {
    sp[0] = in.r(1);
    sv[0] = in.v(1);  // the state of an axisymmetric body is the inertial V_y
    ap[0] = tol.position;
    av[0] = tol.velocity;
  } else {
    // State velocities in body components (Eq. 1).
    const Eigen::Vector3d vb = in.A.transpose() * in.v, wb = in.A.transpose() * in.w;
    const Eigen::Quaterniond quat(in.A);
    const double p[4] = {quat.w(), quat.x(), quat.y(), quat.z()};
    for (int i = 0; i < 3; ++i) {
      sp[i] = in.r(i), sv[i] = vb(i), sv[3 + i] = wb(i);
      ap[i] = tol.position, av[i] = tol.velocity, av[3 + i] = tol.angular_velocity;
    }
    for (int i = 0; i < 4; ++i) sp[3 + i] = p[i], ap[3 + i] = tol.rotation;
  }
  // Elastic coordinates: atol * sqrt(m) in q units (kg^(1/2) m), except for quasi-static
  // coordinates, whose tolerances are displacements of the body's points (m): coordinate
  // j gets atol / max |Phi_j| (Phi_j in m per unit q_j). A quasi-static coordinate moves
  // the contact surface directly, with no inertia to filter its error, and a local
  // interface mode moves it by 1e4-1e6 m per unit q (sphere2d_h3; a global mode by ~10):
  // with the q-unit tolerance the local modes could move the surface by nanometres, a
  // tenth of the penetration, and jittered at that level from step to step. The dynamic
  // coordinates keep the q-unit tolerance: the displacement tolerance gives them the
  // same force peak (-0.05 % from Hertz on sphere2d_h3, damped) at 7 times the steps.
  const QuasiStaticModes& qs = body.quasiStatic();
  for (int j = 0; j < body.nq(); ++j) {
    sp[nr + j] = in.q(j), sv[nv + j] = in.qd(j);
    ap[nr + j] = tol.position * sq, av[nv + j] = tol.velocity * sq;
  }
  for (int s = 0; s < qs.size(); ++s) {
    const double phi = qs.reach(s);
    if (phi > 0.0) ap[nr + qs.index[s]] = tol.position / phi, av[nv + qs.index[s]] = tol.velocity / phi;
  }
}

}  // namespace

void assembleInitialState(const MultibodySystem& sys, const std::vector<InitialPose>& poses,
                          bool axisymmetric, const AbsoluteTolerances& tol, double rtol,
                          Eigen::VectorXd& y0, Eigen::VectorXd& atol) {
  y0.resize(sys.size());
  atol.resize(sys.size());
  for (int b = 0; b < sys.numBodies(); ++b) {
    const int po = sys.positionOffset(b), vo = sys.velocityOffset(b);
    assembleBody(sys.body(b), axisymmetric, poses[b], tol, y0.data() + po,
                 y0.data() + vo, atol.data() + po, atol.data() + vo);
  }
  // Stick anchors (world positions, m) on their points. Their tolerance is not the points'
  // atol_position: an anchor's error moves the tangential force of its point as the
  // position error of the body's rigid motion moves the normal one, and that error is held
  // to rtol |r| (m) with |r| of the order of the body's size. The anchors get rtol times
  // their contact surface's size (SurfaceContact::surfaceSize), the same order, independent
  // of where the origin lies (measured on the 20-degree oblique impact of
  // schemas/contact_friction.md: 1e-9 m took 15,737 steps, 1e-8 m 6,692, the rebound
  // angle 0.13 % apart).
  for (int c = 0; c < sys.numContacts(); ++c)
    atol.segment(sys.anchorOffset(c), sys.contact(c).numAnchors())
        .setConstant(std::max(tol.position, rtol * sys.contact(c).surfaceSize()));
  sys.placeAnchors(y0.data());
}

// Two spheres placed 5 mm into each other once ran to `completed` with zero force: their
// contact surfaces' boxes were apart, so no point was ever evaluated.
void checkInitialPenetration(const YamlDocument& doc, const MultibodySystem& sys,
                             const Eigen::VectorXd& y0) {
  for (int c = 0; c < sys.numContacts(); ++c) {
    const SurfaceContact& pair = sys.contact(c);
    const Penetration p = sys.deepestPenetration(y0.data(), c);
    const double tol = pair.penetrationTolerance();
    if (p.depth <= tol) continue;
    const std::string k = Str() << "contacts[" << c << "]";
    throw inputError(doc, doc.root["contacts"][c], k,
                     Str() << "'" << sys.contactSideName(c, 0) << "' and '"
                           << sys.contactSideName(c, 1) << "' start " << p.depth
                           << " m into each other (a point of '"
                           << sys.body(p.contact_body).name() << "' at (" << p.point.transpose()
                           << ") m); at most " << tol
                           << " m is accepted (key penetration_tolerance): move them apart");
  }
}

}  // namespace ffriga
