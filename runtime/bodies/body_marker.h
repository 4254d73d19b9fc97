// A marker: a material point of a body with the small rotation of the material there, as
// joints, force elements and sensors use it (DESIGN.md "Multibody").
//
//   position (body frame)    p(q) = x0 + Phi q                      (Phi: 3 x nq, m per unit q)
//   rotation of the material theta(q) = Psi q,  Psi = 1/2 curl Phi   (3 x nq, rad per unit q)
// A vector u0 attached to the material at the marker (a joint axis) becomes, to first order
// in q like the SID's invariants (common/sid/sid.h), u(q) = u0 + (Psi q) x u0.
//
// Markers of a SID body come from the SID (common/sid/sid.h Marker: Phi from the basis values
// and the control points' modes); a rigid or frozen body's markers are fixed points (Phi,
// Psi with no columns). The ground's "marker" is a fixed inertial point.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "common/sid/sid.h"

namespace ffriga {

struct BodyMarker {
  std::string name;
  Eigen::Vector3d x0 = Eigen::Vector3d::Zero();  // undeformed, body frame, m
  Eigen::MatrixXd Phi;                           // 3 x nq translation modes
  Eigen::MatrixXd Psi;                           // 3 x nq rotation modes
  bool rotation_modes = true;  // false: the SID gives no Psi (then nothing may use the
                               // marker's rotation while the body has nq > 0)
};

// Marker `m` of a SID with nq elastic coordinates (nq = 0 for a frozen body). A 2D
// (axisymmetric) SID's marker lies in the meridian plane: x0 = (r, y, 0), Phi's third row
// zero, no rotation modes; only sensors use such markers.
BodyMarker markerFromSid(const FlexibleBodySid& sid, const Marker& m, int nq);

class FloatingBody3d;

// One end of a joint or force element: a marker of a body, or a point of the ground.
struct MarkerEnd {
  int body = -1;                          // index in the system; -1: the ground
  const FloatingBody3d* model = nullptr;  // nullptr for the ground
  BodyMarker marker;                      // the ground's: x0 is an inertial point
  // Joints only: the joint axes, columns e1 e2 e3, in body-frame components (ground:
  // inertial), set by Joint::setAxes.
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  // Joints only: the translation modes of the body's quasi-static coordinates, taken out of
  // marker.Phi by detachQuasiStatic (3 x nq, zero in the other columns; empty if none).
  Eigen::MatrixXd quasi_static_Phi;
};

// A joint's end on a body with quasi-static coordinates (runtime/bodies/quasi_static_modes.h)
// -- schemas/multibody.md "Joints and quasi-static coordinates":
//
// jointHeldCoordinates: the quasi-static coordinates `qs` (stiffness diagonal k of all
// elastic coordinates, 1/s^2) that carry the marker's flexibility, so that the joint must
// hold them and they keep their inertia. The marker's static flexibility is the trace of
// its compliance, sum_i |Phi_i|^2 / k_i over the elastic coordinates (Me = E), and the
// same with Psi for rotations (rotations: the joint constrains them). The quasi-static
// coordinates with the largest shares are returned until those left carry at most
// kJointOmittedFlexibility of it, translations and rotations each.
constexpr double kJointOmittedFlexibility = 1e-3;
std::vector<int> jointHeldCoordinates(const BodyMarker& marker, const Eigen::VectorXd& k,
                                      const std::vector<int>& qs, bool rotations);

// detachQuasiStatic: the joint holds the marker as the body's dynamic coordinates move it,
// so the remaining quasi-static coordinates' (elastic indices `index`) columns of
// marker.Phi and marker.Psi become zero (kept in quasi_static_Phi for the offset the result
// file reports).
void detachQuasiStatic(MarkerEnd& end, const std::vector<int>& index);

// A fixed point of a rigid body (or of the ground): no modes.
BodyMarker fixedMarker(const std::string& name, const Eigen::Vector3d& x0);

}  // namespace ffriga
