#include "runtime/contact/rigid_obstacle.h"

#include <cmath>

#include "common/base/error.h"

namespace ffriga {

namespace {

// v / |v| for a nonzero finite v (what: the obstacle and its vector, for the message).
Eigen::Vector3d unit(const Eigen::Vector3d& v, const std::string& name, const char* what) {
  const double length = v.norm();
  FFRIGA_CHECK(length > 0.0 && std::isfinite(length),
               "obstacle '" << name << "': " << what << " (" << v.transpose() << ")");
  return v / length;
}

}  // namespace

RigidObstacle RigidObstacle::plane(std::string name, const Eigen::Vector3d& point,
                                   const Eigen::Vector3d& normal, double radius) {
  const Eigen::Vector3d n = unit(normal, name, "plane normal");
  return RigidObstacle(std::move(name), Shape::kPlane, point, n, radius > 0.0 ? radius : 0.0);
}

RigidObstacle RigidObstacle::sphere(std::string name, const Eigen::Vector3d& centre,
                                    double radius) {
  FFRIGA_CHECK(radius > 0.0, "obstacle '" << name << "': sphere radius " << radius);
  return RigidObstacle(std::move(name), Shape::kSphere, centre, Eigen::Vector3d::UnitY(), radius);
}

RigidObstacle RigidObstacle::cylinder(std::string name, const Eigen::Vector3d& point,
                                      const Eigen::Vector3d& axis, double radius) {
  const Eigen::Vector3d d = unit(axis, name, "cylinder axis");
  FFRIGA_CHECK(radius > 0.0, "obstacle '" << name << "': cylinder radius " << radius);
  return RigidObstacle(std::move(name), Shape::kCylinder, point, d, radius);
}

const char* RigidObstacle::shapeName() const {
  switch (shape_) {
    case Shape::kPlane: return "plane";
    case Shape::kSphere: return "sphere";
    case Shape::kCylinder: return "cylinder";
  }
  return "";
}

ObstaclePoint RigidObstacle::nearest(const Eigen::Vector3d& x) const {
  ObstaclePoint p;
  if (shape_ == Shape::kPlane) {
    p.gap = normal_.dot(x - point_);
    p.normal = normal_;
    if (radius_ > 0.0) p.covered = (x - p.gap * normal_ - point_).norm() <= radius_;
    return p;
  }
  Eigen::Vector3d r = x - point_;
  double scale = 0.0;  // m: the size of round-off in r
  if (shape_ == Shape::kCylinder) {  // off the axis
    const double along = normal_.dot(r);
    scale = 1e-14 * (std::abs(along) + radius_);
    r -= along * normal_;
  }
  const double d = r.norm();
  p.gap = d - radius_;
  // At the centre (on the axis, within round-off) every direction is nearest: any unit
  // normal (the point is radius_ deep), perpendicular to a cylinder's axis.
  if (d > scale) {
    p.normal = r / d;
  } else if (shape_ == Shape::kCylinder) {
    p.normal = normal_.unitOrthogonal();
  } else {
    p.normal = Eigen::Vector3d::UnitY();
  }
  return p;
}

double RigidObstacle::boxGap(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) const {
  const Eigen::Vector3d centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  if (shape_ == Shape::kPlane)  // the box's lowest corner along n
    return normal_.dot(centre - point_) - normal_.cwiseAbs().dot(half);
  if (shape_ == Shape::kCylinder)  // g is 1-Lipschitz: at the box centre less half its diagonal
    return nearest(centre).gap - half.norm();
  // The distance from c to the box, minus R.
  const Eigen::Vector3d outside = ((point_ - centre).cwiseAbs() - half).cwiseMax(0.0);
  return outside.norm() - radius_;
}

bool RigidObstacle::axisymmetric() const {
  const bool onAxis = point_(0) == 0.0 && point_(2) == 0.0;
  if (shape_ == Shape::kSphere) return onAxis;
  if (shape_ == Shape::kCylinder) return onAxis && normal_(0) == 0.0 && normal_(2) == 0.0;
  // A plane normal to the axis is {y = p_y}; a finite one is a disk about the axis.
  return normal_(0) == 0.0 && normal_(2) == 0.0 && (radius_ <= 0.0 || onAxis);
}

}  // namespace ffriga
