// Penalty contact between the contact surfaces of two bodies by collocation (paper Sect. 4).
//
// For a contact body C and a target body T: every collocation (Botella) point i of C, fixed
// in surface parameters, is at x_C = origin_C + A_C (x0_i + Phi_i q_C) with x0_i and
// Phi_i = sum_k R_k(xi_i) Phi_k precomputed once. Its closest point x_T(s) on T's deformed
// surface solves Eq. (15) (runtime/contact/closest_point.h); the normal gap is (Eq. 16)
//   g_n = n^T (x_C - x_T(s)),  n the unit outward normal of T at s,
// and for g_n < 0 the penalty force on C at x_C is (Eq. 17)
//   f_i = -c_p g_n w_i n,   w_i the collocation weight (m^2; axisymmetric: the weight along
//                           the meridian (m) times 2 pi r_i, the ring of radius r_i (m)),
// with -f_i on T at x_T. UNITS: c_p is a pressure per unit penetration, N/m^3 (= Pa/m).
// Roles are switched and the two results averaged (factor 1/2 each). Generalised forces
// (Eq. 18): translational A^T f, rotational x x A^T f, elastic Phi(x)^T A^T f for the body
// point x; on T the elastic part is sum_k R_k(s) Phi_k^T A_T^T (-f).
// Pre-check: if the world bounding boxes of the two surfaces' control points (which hold
// the surfaces, NURBS convex hull property), inflated by `search_margin`, do not overlap,
// nothing is evaluated; single points outside the target's inflated box are skipped.
// Clearance bound (candidate points kept between evaluations): a point whose last search
// found it in front of the target, g_e > 0, with a proper foot point, keeps g > 0 while
//   g_e - |y - y_e| - (d_T + d_T,e) > 0,
// y the point in the target's body frame (distances are frame-invariant), y_e its value at
// that search, and d_T + d_T,e a bound on how far the target surface has moved in its
// frame since: its control points' largest displacement change against a snapshot
// (convex hull property: the surface moves no more than its control points), d_T now and
// d_T,e at the search; the last kSnapshots snapshots are kept, for older ones the moves
// between the snapshots are added (the triangle inequality). The signed gap is
// 1-Lipschitz in the point and in the surface, so such a point is not searched: it cannot
// carry force (only by passing round the surface's edge, which the searched points report
// as beyond-edge). The forces are those of searching every point.
// The searches run in parallel (OpenMP) when there are at least kParallelPoints of them;
// the sums are formed serially afterwards in a fixed order, so results do not depend on
// the number of threads.
// The pair keeps its per-evaluation records (points, sums, stiffness terms) between
// evaluations and reuses their storage: a right-hand side allocates nothing once the
// active set has settled.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "runtime/bodies/body_model.h"
#include "runtime/bodies/space_vector.h"
#include "runtime/contact/closest_point.h"
#include "runtime/contact/collocated_surface.h"
#include "runtime/contact/surface_contact.h"

namespace ffriga {

// A contact pair (runtime/contact/surface_contact.h) with stiffness terms: one per active
// collocation point, its linearisation for the Newton matrix (Eq. 17-18) with
// k = c_p w_i (role factor included).
class ContactPair : public SurfaceContact {
 public:
  ContactPair(std::string name, int a, const BodyModel& A, int surfaceA, int b, const BodyModel& B,
              int surfaceB, const ContactOptions& options);

  // evaluate() at the context's poses, its state into states.contacts[slot()].
  void addForces(const ForceContext& at, std::vector<Eigen::VectorXd>& h,
                 const ForceStates& states) override;
  double boxGap(const ForceContext& at) const override;
  Penetration deepestPenetration(const ForceContext& at) const override;
  const std::string& regionName(int side) const override { return side_[side].name; }

  // Separation of the two surfaces' bounding boxes (deformed control points, world
  // coordinates; the largest gap over the axes, m, <= 0 when they overlap), and the size of
  // the larger contact surface (the diagonal of its undeformed box, m).
  double boxGap(const BodyModel& A, const BodyPose& pa, const BodyModel& B,
                const BodyPose& pb) const;
  // The deepest penetration over every collocation point of both roles, without the
  // bounding-box pre-check: -g_n where the closest point on the other surface is a proper
  // foot point, beyondEdgeDepth where it is on the edge. Also bodies placed deep into each
  // other (whose surfaces' boxes may be apart, or coincident centres) are found. For the
  // initial state (a full closest-point search per point: not for every step).
  Penetration deepestPenetration(const BodyModel& A, const BodyPose& pa, const BodyModel& B,
                                 const BodyPose& pb) const;
  // Linearisation of the active points of the last evaluate(), formed on the first call
  // after it (O(nq) per point and body: right-hand sides that need no Jacobian skip it).
  const std::vector<StiffnessTerm>& stiffnessTerms() const override;
  // Adds the generalised contact forces to hA and hB (layout of the bodies' velocities) and
  // fills `state` if given. svA, svB: the bodies' velocities (needed with friction only).
  void evaluate(const BodyModel& A, const BodyPose& pa, const BodyModel& B, const BodyPose& pb,
                double* hA, double* hB, ContactState* state, const double* svA = nullptr,
                const double* svB = nullptr);

 private:
  // A collocated surface, as the contact side and as the target of the other.
  struct Side : CollocatedSurface {
    std::vector<SurfaceProjection> cache;  // warm starts, one per collocation point
    double edge_reach = 0.0;  // m, as a target: edgeReach() if planar(), else 0
    // Clearance bound (header comment), one per collocation point as a contact point.
    struct Clearance {
      bool valid = false;
      double gap = 0.0;                               // g_e, m
      Eigen::Vector3d y = Eigen::Vector3d::Zero();    // target frame, m (2D: 2 entries)
      long snapshot = 0;                              // the target's snapshot at the search
      double snapshot_moves = 0.0;                    // its D_s, m
      double motion = 0.0;                            // d_T,e against it, m
    };
    std::vector<Clearance> clearance;
    // This side as a target: its last kSnapshots snapshot displacements of the surface
    // control points (body frame), each with its number and D_s, the sum of the moves of
    // the snapshots before it (m).
    struct Snapshot {
      long id = 0;
      Eigen::VectorXd u;
      double moves = 0.0;
    };
    std::deque<Snapshot> snapshots;
    long next_snapshot = 0;
  };
  static constexpr int kSnapshots = 16;
  // The target's motion against its snapshots at displacements u (PhiSt^T q): the largest
  // control point displacement change against each (m); a new snapshot is taken when the
  // change against the newest exceeds `renew`.
  struct TargetMotion {
    long first = 0;              // number of snapshots.front()
    std::vector<double> change;  // against each snapshot, oldest first
    double moves = 0.0;          // D of the newest snapshot
    // Bound on the target's surface motion since a search with record `cl` (m).
    double since(const Side::Clearance& cl) const;
  };
  void targetMotion(Side& target, const Eigen::VectorXd& u, double renew, TargetMotion& tm);
  struct World {
    Eigen::VectorXd u;       // cps.size() * d, body-frame displacements of the surface points
    Eigen::MatrixXd points;  // ncp x d, deformed control points in world coordinates
    Eigen::VectorXd lo, hi;  // bounding box of the surface's points
    // The surface point at the centre of its parameter domain and its world normal.
    Eigen::VectorXd mid_x, mid_n;
    // With friction: the surface control points' elastic velocities PhiSt^T qdot (body
    // frame, cps order; empty for a body without elastic coordinates).
    Eigen::VectorXd udot;
  };
  // Depth of x behind the surface for a closest point p on the edge (not orthogonal): behind
  // both the tangent plane at p and the one at the surface's centre (a point beside the
  // surface is in front of one of them), else 0.
  double beyondEdgeDepth(const World& wt, const Eigen::VectorXd& n_edge, const VectorRef& x,
                         const SurfaceProjection& p) const;
  // Whether x, whose closest point p on the target st is on its edge, lies within st's edge
  // reach of the tangent plane at p, off the surface: then the plane holds it as if the
  // surface went on. Only planar targets reach (flat faces of equal size meeting end-on);
  // beside the edge of a curved region the surface would go on curving, and a contact that
  // outgrows such a region must stop the run as before.
  static bool withinEdgeReach(const Side& st, const Eigen::VectorXd& n_edge, const VectorRef& x,
                              const SurfaceProjection& p);
  // Each role's share of a point's force: 1/2 where the two roles are averaged, else 1.
  double roleFactor() const { return options_.both_roles ? 0.5 : 1.0; }
  World worldPoints(const Side& side, const BodyPose& pose) const;
  void worldPoints(const Side& side, const BodyPose& pose, World& w) const;
  // Side c's collocation points against the other side as the target: adds the generalised
  // forces times `factor` to hC and hT and the diagnostics to `state` if given, in three
  // phases: which points need a search (serial), the searches (parallel), the sums (serial);
  // with `record`, role c of pressure_ too.
  // svC, svT: the two bodies' velocities (friction).
  void collocate(int c, const BodyModel& C, const BodyPose& pc, const World& wc, const BodyModel& T,
                 const BodyPose& pt, const World& wt, double* hC, double* hT, double factor,
                 const TargetMotion& motion, ContactState* state, bool record, const double* svC,
                 const double* svT);
  // One collocation point's outcome in collocate().
  struct PointResult {
    bool active = false;
    bool failed = false;
    double gap = 0.0;
    double beyond_edge = 0.0;  // penetration behind the edge's tangent plane (m)
    SpaceVector x, y;          // world point, and in the target's frame (if near)
    SpaceVector f, xb, xt, n;  // force on C (world), body points of C and T, normal
    int element = -1;
    ParamVector s;
    PointFriction friction;  // with friction (addFriction): the law's values
  };
  // Sums of collocate()'s active points, formed serially in point order.
  struct ForceSums {
    Eigen::VectorXd fbSum;      // C's elastic forces, sum_i Phi_i^T A_C^T f_i
    Eigen::MatrixXd FT;         // body-frame forces on T's surface control points (cps order)
    std::vector<char> touched;  // which of those carry force
    Eigen::MatrixXd R;          // workspace: the target surface's basis at a foot point
  };
  // Phase 1, point i of contact side sc: its body point r.xb (from the control points'
  // displacements), world position r.x and, if near the target's inflated box, its position
  // r.y in the target's frame; true if it needs a closest-point search (not near: false;
  // cleared by the clearance bound of the header comment: false, counted as avoided).
  bool needsSearch(const Side& sc, int i, const BodyModel& C, const BodyPose& pc, const World& wc,
                   const BodyPose& pt, const World& wt, const TargetMotion& motion, PointResult& r);
  // Phase 2, candidate i at r.x (r.y in the target's frame): its closest point on the target
  // (Eq. 15, warm-started from and stored in sc.cache[i]), the normal gap (Eq. 16) and, for
  // g_n < 0, the penalty force on C (Eq. 17); a point in front gets a clearance record in
  // sc.clearance[i], one beyond the edge its depth. Writes only point i's entries.
  void searchPoint(Side& sc, const Side& st, int i, const BodyPose& pt, const World& wt,
                   double orientT, double factor, const TargetMotion& motion, PointResult& r) const;
  // The side's surface control points' elastic velocities (World::udot) at velocities sv.
  Eigen::VectorXd elasticVelocities(const Side& side, const BodyModel& body,
                                    const double* sv) const;
  // Target side st's modes at a foot point, transposed (T.nq() x d), into PhiTt: the surface
  // basis `basis` of `element` over st's control points.
  void footModes(const Side& st, const BodyModel& T, int element, const double* basis,
                 Eigen::MatrixXd& PhiTt) const;
  // Phase 3, friction at active point i of side c (runtime/contact/coulomb_friction.h): the
  // relative velocity of the collocation point and the foot point (BodyModel::pointVelocity
  // with the sides' World::udot; R: the target surface's basis at the foot point), and the
  // tangential force added to r.f (on C; -r.f on T). The force's normal part is the
  // penalty's f_n = |r.f| (role factor included).
  void addFriction(int c, int i, PointResult& r, const BodyModel& C, const BodyPose& pc,
                   const World& wc, const BodyModel& T, const BodyPose& pt, const World& wt,
                   const Eigen::MatrixXd& R, const double* svC, const double* svT) const;
  // Phase 3, one point's diagnostics: a failed search, its depth beyond the edge and, if
  // active, its force, penetration and penalty energy 1/2 c_p g_n^2 w_i (times `factor`).
  void addDiagnostics(const PointResult& r, double weight, double factor,
                      ContactState& state) const;
  // Phase 3, active point i of side c (Eq. 18): the rigid parts of f on C and of -f on T
  // into hC and hT, C's elastic part Phi_i^T A_C^T f into sums.fbSum, T's body-frame force
  // spread over its surface control points by the basis at s (sums.R, formed by the caller;
  // into sums.FT); recorded in active_.
  void addPointForces(int c, int i, const PointResult& r, double factor, const BodyModel& C,
                      const BodyPose& pc, const BodyModel& T, const BodyPose& pt, double* hC,
                      double* hT, ForceSums& sums);
  // Phase 3, the elastic parts of the sums: sums.fbSum into hC, and on target side st
  // Phi_k^T FT_k of each surface control point k that carries force into hT.
  void addElasticForces(const Side& st, const BodyModel& C, const BodyModel& T, double* hC,
                        double* hT, const ForceSums& sums) const;
  // What stiffnessTerms() needs of each active point of the last evaluate(): the contact
  // side c, collocation point i, the foot point's element on the target and its basis
  // values there (active_basis_ from `basis`), body points, normal and k; and the bodies
  // and poses of that evaluation.
  struct ActivePoint {
    int c = 0, i = 0, element = -1;
    double k = 0.0;
    std::size_t basis = 0;  // offset of its basis values in active_basis_
    SpaceVector xb, xt, n;
    PointFriction friction;  // friction: its law's values at the point
  };
  std::vector<ActivePoint> active_;
  std::vector<double> active_basis_;
  const BodyModel* bodies_[2] = {nullptr, nullptr};
  BodyPose poses_[2];
  mutable std::vector<StiffnessTerm> terms_;
  mutable bool terms_formed_ = true;
  // Storage reused from one evaluation to the next: the terms of earlier formations (their
  // vectors), the modes at a point, each side's world points, target motion, point results
  // and sums as the contact side (index c), and the candidates of a collocate().
  mutable std::vector<StiffnessTerm> spare_terms_;
  // A spare term reset to a new one's fields (or a new one if none is spare).
  StiffnessTerm spareTerm() const;
  mutable Eigen::MatrixXd PhiTt_, PhiC_, PhiT_;
  World world_[2];
  TargetMotion motion_[2];
  std::vector<PointResult> results_[2];
  ForceSums sums_[2];
  std::vector<int> search_;
  Side side_[2];
  int dim_ = 3;
  double margin_ = 0.0;
};

}  // namespace ffriga
