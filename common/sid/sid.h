// The reduced flexible body: everything ffrsim needs about one body, written by igaprep
// into an SID file (HDF5; layout in schemas/sid_format.md) and read back by ffrsim.
// Named after the Standard Input Data of Wallrapp / Schwertassek ("Dynamik flexibler
// Mehrkörpersysteme", 1999, Sect. 6.4); paper Sect. 2, Eq. (1).
//
// Frames and coordinates. The body frame K_R has its origin and axes where igaprep's
// geometry has them (for a Buckens frame the origin is moved to the centre of mass and the
// rigid content of the modes is removed in the mass metric). A material point with
// undeformed body-frame position x0 moves to
//
//   r = r_R + A (x0 + Phi(x0) q),        Phi(x0) = sum_k R_k(x0) Phi_k  (3 x nq),
//
// where Phi_k are the rows of the mode shapes at control point k (displacements of the
// control points, Eq. 14: u = Phi q). All quantities are SI: m, kg, s, and per unit of the
// elastic coordinates q (which are mass-normalised: units kg^(1/2) m).
//
// Axisymmetric bodies (model = axisymmetric) store 2D data: control points (x = radius,
// y = axis), modes with (u_r, u_y) per control point, and rigid motion along y only; the
// inertia invariants are those of the full body of revolution.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "common/mechanics/isotropic_material.h"
#include "common/sid/body_kinds.h"
#include "common/splines/contact_surface.h"

namespace ffriga {

// Named physical point whose displacement is a linear combination of control point
// displacements: u(marker) = sum_k R_k(xi) u_k (joints and outputs).
struct Marker {
  std::string name;
  Eigen::VectorXd position;    // undeformed, body frame, m
  std::vector<int> functions;  // control points with non-zero basis value
  Eigen::VectorXd values;      // R_k(xi) of those control points
  // Rotation modes: the small rotation of the material at the marker per unit q,
  // Psi = 1/2 curl Phi (3 x nq, rad per unit q); empty when the SID carries none.
  Eigen::MatrixXd Psi;
};

// The exact geometry the body was built from (body file key geometry): its type and, for
// the spheres (half_disk, sphere) and the rod, the radius; the rod's length.
struct SidGeometry {
  std::string type;     // half_disk | sphere | rod | nurbs
  double radius = 0.0;  // m, 0 where the type has none
  double length = 0.0;  // m, rod only
  // Centre of the sphere (half_disk, sphere) in the body frame, m.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

// Points of the body with their displacement and stress modes: the displacement at point i
// is u_i = Phi.block(s i, 0, s, nq) q (m, body frame) and its stress
// sigma_i = S.block(6 i, 0, 6, nq) q (Pa, Cartesian body-frame components xx, yy, zz, xy,
// yz, xz; axisymmetric bodies in the meridian plane with z the hoop direction), exact for
// the reduced model (sigma = D B Phi q, preproc/assembly/strain_operator.h).
struct SampledModes {
  Eigen::MatrixXd points;      // np x s, undeformed, body frame, m
  Eigen::MatrixXd parameters;  // np x d, parametric coordinates
  Eigen::MatrixXd Phi;         // (np * s) x nq, kg^(-1/2)
  Eigen::MatrixXd stress;      // (np * 6) x nq, Pa kg^(-1/2) m^(-1)
};

// Visualisation mesh of the whole body: every element of the (hierarchical) spline space
// split into `subdivisions` cells per parametric direction, points sampled on the exact
// geometry and shared between cells by their parameters. Cells are quadrilaterals (2D) or
// hexahedra (3D) with VTK/XDMF corner order; degenerate corners (poles, axis) may repeat.
struct VisualisationMesh {
  int subdivisions = 0;   // 0: the SID has no mesh
  SampledModes samples;
  Eigen::MatrixXi cells;  // nc x 4 or nc x 8, point numbers
  bool empty() const { return subdivisions == 0; }
};

// A line of points through the body (body file key visualisation.stress_lines), e.g. the
// symmetry axis under the contact point: `from` and `to` in the body frame.
struct StressLine {
  std::string name;
  Eigen::VectorXd from, to;  // s, m, body frame
  SampledModes samples;      // points evenly spaced from `from` to `to`
};

// The design a designed body was built from (body file key `design`, schemas/body_design.md;
// SID group /design). Hand-made bodies have none (present = false).
struct SidDesign {
  bool present = false;
  double contact_radius = 0.0;               // a, m: what the model resolves
  double elements_per_contact_radius = 0.0;  // N: finest elements at most a / N
  double finest_element = 0.0;               // m: the finest span at the contact point
  double approach_speed = 0.0;               // m/s of the designed impact; 0: a was given
  double max_pressure = 0.0;                 // Pa, Hertz's p0 of that impact; 0: a was given
  // Where (optional: SIDs before 2026-12-07 lack them; 0 / empty then): the surface's radius
  // of curvature at the contact point (m), the point and its outward normal in the body's
  // geometry coordinates (m; unit).
  double surface_radius = 0.0;
  Eigen::VectorXd contact_point, contact_normal;
  // The ellipse's semi-minor axis b (m; = contact_radius for a circle) and the designed
  // impact's Hertz force peak (N) and duration (s) (0: a was given). Same vintage.
  double contact_minor_radius = 0.0;
  double hertz_max_force = 0.0, hertz_duration = 0.0;
  double mode_cutoff_hz = 0.0;  // the normal modes' cutoff (Hz); 0: a count was given
  // The surface's principal curvatures at the contact point (1/m, ascending: 2 values) and
  // the unit direction of the first (3 components, geometry coordinates; written only where
  // they differ by more than 1 %: an elliptical contact). Optional: empty when absent.
  Eigen::VectorXd principal_curvatures, principal_direction;
};

struct FlexibleBodySid {
  // Identity and provenance.
  std::string name;
  ModelKind model = ModelKind::kSolid;
  int space_dim = 3;  // 2 for axisymmetric, 3 for solid
  int ndof = 0;       // displacement DOFs of the full (unreduced) model
  int nlvl = 1;       // hierarchical levels
  int n_elements = 0;
  int n_interface_control_points = 0;
  FrameKind frame = FrameKind::kBuckens;
  std::string input_yaml;       // the body file's text
  std::string input_path;       // the body file as given to igaprep
  std::string input_overrides;  // igaprep's --set KEY=VALUE, one per line ("" for none)
  std::string created_by;       // program and version, e.g. "igaprep 0.1.0"
  ReductionMethod reduction = ReductionMethod::kCraigBampton;
  int normal_modes = 0;         // fixed-interface (CB) or free-free (modal) modes in the basis
  int constraint_modes = 0;     // CB constraint modes (interface DOFs)
  int rigid_modes_dropped = 0;  // zero-frequency directions removed (1 axisymmetric, 6 3D)
  // Interface reduction (root attributes added within version 3, read where present): the
  // DOFs on the Craig-Bampton interface and, where the contact regions' constraint modes were
  // replaced by characteristic constraint modes, how many of those the basis holds (zero and
  // elastic ones) and how many pressure patch directions (constraint_modes = their sum plus
  // the interface markers' retained DOFs; 0 and 0: the full interface) with every
  // eigenfrequency of the regions' condensed interface, Hz (/sid/characteristic_frequencies_hz).
  int interface_dofs = 0;
  int characteristic_modes = 0;
  int patch_modes = 0;  // directions added by pressure patches' static responses
  // Pressure patches' accuracy guard: the largest share of static compliance the reduced
  // interface misses for normal patches halfway between the patch radii; -1: not computed.
  double interface_compliance_error = -1.0;
  Eigen::VectorXd characteristic_frequencies_hz;
  // Origin of the body frame in the coordinates of the body file's geometry, m (Buckens:
  // the centre of mass; tangent: the frame marker). Control points, markers and surfaces
  // below are in the body frame: x_body = x_geometry - frame_origin.
  Eigen::Vector3d frame_origin = Eigen::Vector3d::Zero();
  double preprocessing_time_s = 0.0;                          // wall time of igaprep, s
  std::vector<std::pair<std::string, double>> stage_times_s;  // (stage, wall time in s)

  // Rigid-body invariants (body frame). For an axisymmetric body: of the full body of
  // revolution, with the axis along y.
  double mass = 0.0;                                       // m, kg
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();  // m c = int rho x0 dV, kg m
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // J0 = int rho (x0.x0 E - x0 x0^T) dV, kg m^2

  // Elastic invariants (nq elastic coordinates).
  Eigen::VectorXd frequencies_hz;  // nq, omega_i / (2 pi)
  Eigen::MatrixXd Me;              // nq x nq, = E (Eq. 13)
  Eigen::MatrixXd Ke;              // nq x nq, = diag(omega^2), N/m per unit q^2
  Eigen::MatrixXd De;              // nq x nq, = diag(2 zeta omega)
  Eigen::MatrixXd Ct;              // nq x 3: Ct^T = int rho Phi dV (translational coupling)
  Eigen::MatrixXd Cr0;             // nq x 3: Cr^T = int rho x0~ Phi dV at q = 0
  // First-order terms in q (kept: they carry the gyroscopic coupling and the inertia
  // change of the deformed body, which rotating bodies need):
  //   Cr(q)^T = Cr0^T + sum_j q_j Cr1_j,  Cr1_j(:, i) = int rho Phi_j~ Phi_i dV     (3 x nq)
  //   J(q)    = J0 + sum_j q_j J1_j,      J1_j = -int rho (x0~ Phi_j~ + Phi_j~ x0~) dV (3 x 3)
  std::vector<Eigen::MatrixXd> Cr1;  // nq matrices 3 x nq
  std::vector<Eigen::Matrix3d> J1;   // nq matrices
  // Centrifugal load on the elastic coordinates (SID "Oe", zeroth order in q):
  //   int rho Phi^T w~ w~ x0 dV = Oe [w1^2, w2^2, w3^2, w1 w2, w2 w3, w1 w3]^T      (nq x 6)
  // The Coriolis term int rho Phi^T w~ Phi dV qdot follows from Cr1:
  //   (int rho Phi_i^T w~ Phi_j dV) = w . Cr1_j(:, i).
  Eigen::MatrixXd Oe;
  // Modal damping ratio zeta_i of each elastic coordinate from the body file's rule
  // (De = diag(2 zeta omega)).
  Eigen::VectorXd damping_ratio;  // nq, dimensionless
  // Second-order terms int rho Phi_i^T Phi_j dV = Me and the q^2 part of J are dropped
  // (small deformations, paper Sect. 2).

  // Modes at every control point: row block k (space_dim rows) = Phi_k.
  Eigen::MatrixXd control_points;  // ncp x space_dim, undeformed, body frame, m
  Eigen::VectorXd weights;         // ncp
  Eigen::MatrixXd Phi;             // (ncp * space_dim) x nq

  std::vector<ContactSurface> surfaces;
  std::vector<Marker> markers;

  IsotropicMaterial material;  // the body file's, for stresses and Hertz's reference
  SidGeometry geometry;
  SidDesign design;
  VisualisationMesh mesh;
  std::vector<StressLine> stress_lines;

  int nq() const { return static_cast<int>(frequencies_hz.size()); }
};

}  // namespace ffriga
