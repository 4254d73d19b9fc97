// Pressure patches: the loads a contact puts on a contact region, as generalized forces on the
// Craig-Bampton interface, whose static responses span what the contact does to the region
// (interface reduction, characteristic_constraint_modes.h; issue 32: "static responses to
// smooth pressure patches of the sizes the impact will produce").
//
// A patch of radius a around the centre x_c (a point of the region's surface, with outward
// normal n_c and tangents t_1, t_2) is Hertz's pressure shape times a polynomial moment,
//   p(x) = sqrt(1 - r^2 / a^2) u^i v^j   (r = |x - x_c| < a, else 0),
//   u = (x - x_c).t_1 / a,  v = (x - x_c).t_2 / a,   i + j <= degree,
// (axisymmetric bodies: the patch is a ring load about the axis, the moments (r / a)^i,
// i <= degree) for the radii a_k = radius k / radii, k = 1 .. radii (or those halfway
// between, for the accuracy guard of characteristic_constraint_modes.h). Each patch loads the
// region as a normal traction p n and, with `tangential`, as tangential tractions p t_1,
// p t_2 (axisymmetric: p t, the meridian tangent). The generalized force on the DOF
// (control point k, component c) is the runtime's collocation rule (paper Eq. 18),
//   f = sum over collocation points g of w_g R_k(s_g) traction_c(x_g)
// (axisymmetric: w_g times 2 pi r_g), in N per unit pressure.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "common/splines/contact_surface.h"
#include "common/splines/spline_space.h"
#include "preproc/assembly/dof_map.h"

namespace ffriga {

struct PressurePatchOptions {
  double radius = 0.0;           // the largest patch radius, m
  int radii = 8;                 // patch radii radius (k - radius_offset) / radii, k = 1 .. radii
  double radius_offset = 0.0;    // 0.5: the radii halfway between (the accuracy guard's)
  double smallest_radius = 0.0;  // radii below this are left out
  int degree = 2;                // polynomial moments up to this total degree
  bool tangential = true;        // tangential tractions besides the normal one
  std::vector<double> centre;    // surface parameters of x_c; empty: the region's centre
                                 // (axisymmetric: the end of the region nearer the axis)
};

struct PressurePatchLoads {
  Eigen::MatrixXd F;       // interface DOFs x patches, N per unit pressure
  Eigen::VectorXd centre;  // x_c, geometry coordinates (s)
};

// `interface_index`: per DOF its interface index or -1. Throws InputError if the centre lies
// outside the surface's elements or a patch loads a DOF off the interface.
PressurePatchLoads pressurePatchLoads(const SplineSpace& space, const DofMap& dofs,
                                      const ContactSurface& surface, bool axisymmetric,
                                      const std::vector<int>& interface_index,
                                      const PressurePatchOptions& options);

}  // namespace ffriga
