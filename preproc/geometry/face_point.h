// The differential geometry of a boundary face at one of its points: position, outward
// unit normal and principal curvatures (do Carmo, "Differential Geometry of Curves and
// Surfaces" (1976), Sect. 3-2 and 3-3). With the face's tangents t_a = dx/du_a, the first
// and second fundamental forms
//   I_ab = t_a . t_b,   II_ab = -n . d2x/du_a du_b   (n the outward normal)
// give the principal curvatures as the eigenvalues of I^-1 II: positive where the face
// bends away from its outward normal (a convex point: a sphere of radius R has 1/R, 1/R),
// negative where it is concave, zero where flat; the generalised eigenvectors c give the
// principal directions c_a t_a (t_a = dx/du_a). A 2D section's edge has one curvature,
// -n . x_uu / |x_u|^2; an axisymmetric body's surface on the axis has that one twice.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "common/splines/nurbs_patch.h"

namespace ffriga {

struct FacePoint {
  Eigen::VectorXd x;                      // position, m
  Eigen::VectorXd normal;                 // outward unit normal
  std::vector<double> curvatures;         // principal curvatures, 1/m, ascending (convex > 0)
  std::vector<Eigen::VectorXd> directions;  // 3D: their unit principal directions (2D: none)
  std::vector<Eigen::VectorXd> tangents;  // dx/du_a along the face, m per knot, direction order
  double jacobian = 0.0;                  // |x_u| (2D) or |x_u x x_w| (3D): 0 at a degenerate point
  double size = 0.0;                      // the patch's bounding-box diagonal, m (the scale of
                                          // "degenerate": jacobian <= 1e-9 size^(d-1))
  bool degenerate() const;
};

// The point xi (one knot coordinate per direction; xi[face_direction] is taken as the face's
// own bound) of the face {xi[face_direction] = lower or upper end}. Derivatives on a knot
// line are taken from the elements on the body's side (the lower element at an upper bound).
FacePoint facePoint(const NurbsPatch& patch, int face_direction, bool face_upper,
                    std::vector<double> xi);

}  // namespace ffriga
