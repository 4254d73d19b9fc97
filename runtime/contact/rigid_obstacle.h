// A rigid obstacle fixed in space, its surface evaluated exactly: the target of an obstacle
// contact (runtime/contact/obstacle_contact.h). Shapes:
//   * plane: a point p and a unit normal n pointing out of the obstacle (toward the bodies):
//       g(x) = n . (x - p),  foot point x - g n;
//     infinite, or finite: a disk of radius R about p (a point whose foot lies beyond R is
//     beside the plate and gets no force: the plate has no thickness and no edge force);
//   * sphere: centre c and radius R, outside the sphere:
//       g(x) = |x - c| - R,  n = (x - c) / |x - c|;
//   * cylinder: infinite, circular, about the axis through p along the unit d, radius R,
//     outside it (a post, a roller, a shaft):
//       r = (x - p) - (d . (x - p)) d,  g(x) = |r| - R,  n = r / |r|.
// Axisymmetric scenes (points (r, y) of the meridian plane): a plane must be normal to the
// axis (n = (0, +-1, 0)), a sphere centred on it and a cylinder coaxial with it; the scene
// checks it.
// g < 0 is a penetration; the penalty force on a body's collocation point is
// f = -c_p g w n (Eq. 17), with n the obstacle's normal at the foot point.
#pragma once

#include <string>

#include <Eigen/Dense>

namespace ffriga {

// The nearest point of an obstacle's surface to a point x.
struct ObstaclePoint {
  double gap = 0.0;                                  // g, m (< 0: inside)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // n at the foot point, out of the obstacle
  bool covered = true;  // false: x is beside a finite plane (its foot beyond the radius)
};

class RigidObstacle {
 public:
  enum class Shape { kPlane, kSphere, kCylinder };

  // A plane through `point` with outward `normal` (normalised here; zero is an error),
  // infinite for radius <= 0, else a disk of that radius (m) about `point`.
  static RigidObstacle plane(std::string name, const Eigen::Vector3d& point,
                             const Eigen::Vector3d& normal, double radius);
  // A sphere of `radius` (m, > 0) about `centre`.
  static RigidObstacle sphere(std::string name, const Eigen::Vector3d& centre, double radius);
  // An infinite cylinder of `radius` (m, > 0) about the axis through `point` along `axis`
  // (normalised here; zero is an error).
  static RigidObstacle cylinder(std::string name, const Eigen::Vector3d& point,
                                const Eigen::Vector3d& axis, double radius);

  const std::string& name() const { return name_; }
  Shape shape() const { return shape_; }
  // plane: p; sphere: c; cylinder: a point of its axis (m)
  const Eigen::Vector3d& point() const { return point_; }
  const Eigen::Vector3d& normal() const { return normal_; }  // plane: n; cylinder: d
  double radius() const { return radius_; }                  // plane: <= 0 infinite (m)
  // "plane", "sphere", "cylinder": the result file's word for the shape.
  const char* shapeName() const;

  // The nearest surface point of x (world, m).
  ObstaclePoint nearest(const Eigen::Vector3d& x) const;
  // A lower bound of g over the box [lo, hi] (world, m).
  double boxGap(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const;
  // Whether the obstacle is symmetric about the y axis (an axisymmetric scene's axis).
  bool axisymmetric() const;

 private:
  RigidObstacle(std::string name, Shape shape, const Eigen::Vector3d& point,
                const Eigen::Vector3d& normal, double radius)
      : name_(std::move(name)), shape_(shape), point_(point), normal_(normal), radius_(radius) {}
  std::string name_;
  Shape shape_ = Shape::kPlane;
  Eigen::Vector3d point_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_ = Eigen::Vector3d::UnitY();
  double radius_ = 0.0;
};

}  // namespace ffriga
