// A body's contact surface as the contact side of a pair (paper Sect. 4, Eq. 17-18): its
// collocation (Botella) points, fixed in surface parameters, each at body point
//   x_i = x0_i + Phi_i q,   Phi_i = sum_k R_k(xi_i) Phi_k,
// with its collocation weight w_i (m^2; axisymmetric: the weight along the meridian (m)
// times 2 pi r_i, the ring of radius r_i (m)). Built once from the SID; the points'
// displacements come from those of the surface's control points (O(nc), no product with
// Phi per point).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/splines/extracted_surface.h"
#include "runtime/bodies/body_model.h"

namespace ffriga {

struct CollocatedSurface {
  std::string name;                   // the SID contact surface's (the body file's region)
  ExtractedSurface surface;
  std::vector<int> cps;               // body control points of the surface
  Eigen::MatrixXd P0;                 // ncp x d, all body control points (undeformed)
  Eigen::MatrixXd PhiSt;              // nq x (cps.size() * d): Phi of the surface points,
                                      // transposed (a point's d columns are contiguous)
  Eigen::MatrixXd xc0;                // nc x d, collocation points, undeformed body frame
  Eigen::MatrixXd PhiCt;              // nq x (nc * d): Phi at collocation point i in columns
                                      // i d .. i d + d - 1 (transposed, contiguous); read
                                      // for active points and the initial penetration scan
  // Collocation point i as a combination of the surface's control points (cps order):
  // u_i = sum_k R_k(xi_i) u_k over k in [combo_offset[i], combo_offset[i + 1]).
  std::vector<int> local;             // body control point -> its index in cps (-1: none)
  std::vector<int> combo_offset, combo_local;
  std::vector<double> combo_value;
  Eigen::VectorXd weight;             // nc, collocation weight incl. the ring factor (m^2)
  int dim = 3;

  // SID contact surface `surface` of `body`. Bad input (InputError) when the SID's
  // collocation data are inconsistent or its outward normal points into the body at every
  // collocation point (a wrong sign turns the penalty force into an attraction).
  void setup(const BodyModel& body, int surface);
  int numPoints() const { return static_cast<int>(xc0.rows()); }
  // The surface's control points' body-frame displacements Phi_S q (cps order, d each).
  Eigen::VectorXd displacements(const Eigen::VectorXd& q) const { return PhiSt.transpose() * q; }
  // Collocation point i in the body frame, from the control points' displacements u; the
  // second form into xb (no allocation: every point at every right-hand side).
  Eigen::VectorXd bodyPoint(int i, const Eigen::VectorXd& u) const;
  void bodyPoint(int i, const Eigen::VectorXd& u, SpaceVector& xb) const;
  // Collocation point i's displacement (or velocity) from the control points' ones u
  // (zero for empty u): bodyPoint less the undeformed point (bodyPoint keeps its own sum,
  // from the undeformed point on: the frictionless results' bits).
  Eigen::VectorXd pointDisplacement(int i, const Eigen::VectorXd& u) const;
  // The diagonal of the surface's undeformed control points' box (m).
  double size() const;
  // Whether the undeformed surface is planar (a straight meridian in 2D): its control points
  // lie within 1e-12 of its size of the tangent plane at its centre (convex hull property:
  // then the whole surface does).
  bool planar() const;
  // The surface point at the centre of its parameter domain, with first derivatives, for
  // control points `points` (one row per body control point: undeformed, or deformed world).
  SurfacePoint centre(const Eigen::MatrixXd& points) const;
  void centre(const Eigen::MatrixXd& points, SurfacePoint& sp) const;  // into sp (reused)
};

}  // namespace ffriga
