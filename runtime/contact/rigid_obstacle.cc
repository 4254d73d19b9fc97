#include "runtime/contact/rigid_obstacle.h"

#include <cmath>

#include "common/base/error.h"

namespace ffriga {

RigidObstacle RigidObstacle::plane(std::string name, const Eigen::Vector3d& point,
                                   const Eigen::Vector3d& normal, double radius) {
  const double length = normal.norm();
  FFRIGA_CHECK(length > 0.0 && std::isfinite(length),
               "obstacle '" << name << "': plane normal (" << normal.transpose() << ")");
  return RigidObstacle(std::move(name), Shape::kPlane, point, normal / length,
                       radius > 0.0 ? radius : 0.0);
}

RigidObstacle RigidObstacle::sphere(std::string name, const Eigen::Vector3d& centre,
                                    double radius) {
  FFRIGA_CHECK(radius > 0.0, "obstacle '" << name << "': sphere radius " << radius);
  return RigidObstacle(std::move(name), Shape::kSphere, centre, Eigen::Vector3d::UnitY(), radius);
}

const char* RigidObstacle::shapeName() const {
  return shape_ == Shape::kPlane ? "plane" : "sphere";
}

ObstaclePoint RigidObstacle::nearest(const Eigen::Vector3d& x) const {
  ObstaclePoint p;
  if (shape_ == Shape::kPlane) {
    p.gap = normal_.dot(x - point_);
    p.normal = normal_;
    if (radius_ > 0.0) p.covered = (x - p.gap * normal_ - point_).norm() <= radius_;
    return p;
  }
  const Eigen::Vector3d r = x - point_;
  const double d = r.norm();
  p.gap = d - radius_;
  // At the centre every direction is nearest: any unit normal (the point is radius_ deep).
  p.normal = d > 0.0 ? Eigen::Vector3d(r / d) : Eigen::Vector3d::UnitY();
  return p;
}

double RigidObstacle::boxGap(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
  const Eigen::Vector3d centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  if (shape_ == Shape::kPlane)  // the box's lowest corner along n
    return normal_.dot(centre - point_) - normal_.cwiseAbs().dot(half);
  // The distance from c to the box, minus R.
  const Eigen::Vector3d outside = ((point_ - centre).cwiseAbs() - half).cwiseMax(0.0);
  return outside.norm() - radius_;
}

bool RigidObstacle::axisymmetric() const {
  const bool onAxis = point_(0) == 0.0 && point_(2) == 0.0;
  if (shape_ == Shape::kSphere) return onAxis;
  // A plane normal to the axis is {y = p_y}; a finite one is a disk about the axis.
  return normal_(0) == 0.0 && normal_(2) == 0.0 && (radius_ <= 0.0 || onAxis);
}

}  // namespace ffriga
