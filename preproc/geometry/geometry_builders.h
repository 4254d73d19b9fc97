// Exact NURBS geometries of the paper's bodies. Lengths in metres.
//
// halfDisk(r)  paper Eq. (19): the meridian section of a sphere of radius r for an
//              axisymmetric model, x = radial coordinate >= 0, y = axis of symmetry.
//              Degrees (2, 1), knots [0 0 0 1 1 1] x [0 0 1 1]. Edge xi = 0 is the axis
//              (x = 0, u_r = 0 there), edges eta = 0 / eta = 1 are the lower / upper
//              quarter arcs, edge xi = 1 collapses into the point (r, 0) (two coincident
//              control points). The poles (0, -r), (0, r) are regular corners: the contact
//              point of the axisymmetric impact is the upper pole (xi, eta) = (0, 1).
//
// solidSphere(r) the half-disk revolved about its axis (a full circle of four rational
//              quarter arcs, knots [0 0 0 .25 .25 .5 .5 .75 .75 1 1 1]); directions
//              (xi, eta, zeta) = (axis -> equator, lower -> upper hemisphere, angle).
//              Degenerate points: the axis (xi = 0), the equator (xi = 1) and the seam
//              zeta = 0 = 1, all with coincident control points. The boundary consists
//              of the faces eta = 0 and eta = 1. The patch is rotated rigidly so that the
//              surface point (xi, eta, zeta) = (1/2, 1, 1/8), 45 degrees away from the
//              axis, from the equator and from the C0 knot lines in zeta, lies at r times
//              the unit `direction` (default +z: (0, 0, r)): a contact region around it
//              contains no degenerate point (DESIGN.md).
//
// solidRod(a, L) a straight circular cylinder of radius a along z from 0 to L: the disk
//              as one 3 x 3 quadratic patch whose four edges are 90-degree rational arcs
//              (no coincident control points; the Jacobian vanishes at the four arc
//              junctions on the boundary only), extruded linearly along z.
#pragma once

#include "common/splines/nurbs_patch.h"

namespace ffriga {

NurbsPatch halfDisk(double r);
NurbsPatch solidSphere(double r, const Eigen::Vector3d& direction = Eigen::Vector3d::UnitZ());
NurbsPatch solidRod(double radius, double length);

// Parametric coordinates of the designated contact point of solidSphere (on face eta = 1).
inline constexpr double kSphereContactXi[3] = {0.5, 1.0, 0.125};

}  // namespace ffriga
