#include "runtime/constraints/joint.h"

#include "common/base/error.h"
#include "common/base/spelling.h"
#include "runtime/bodies/marker_kinematics.h"
#include "runtime/bodies/rotation.h"

namespace ffriga {

namespace {

// A vector-valued quantity and its derivatives split over the two ends: rate = Ga za + Gb zb.
struct Factor {
  Eigen::Vector3d value, rate, bias;
  Eigen::MatrixXd Ga, Gb;
};

Factor fromEnd(const MarkerKinematics& k, int side, int nva, int nvb) {
  Factor f{k.value, k.rate, k.bias, Eigen::MatrixXd::Zero(3, nva), Eigen::MatrixXd::Zero(3, nvb)};
  (side == 0 ? f.Ga : f.Gb) = k.G;
  return f;
}

// g = X . Y (header comment).
void dotRow(const Factor& X, const Factor& Y, int row, JointRows& r) {
  r.g(row) = X.value.dot(Y.value);
  r.bias(row) = X.bias.dot(Y.value) + 2.0 * X.rate.dot(Y.rate) + X.value.dot(Y.bias);
  r.Ja.row(row) = X.value.transpose() * Y.Ga + Y.value.transpose() * X.Ga;
  r.Jb.row(row) = X.value.transpose() * Y.Gb + Y.value.transpose() * X.Gb;
}

}  // namespace

namespace {

// The scene's spelling of JointType (schemas/scene.schema.json, joints[].type).
const Spelling<JointType> kJointTypes[] = {{"spherical", JointType::kSpherical},
                                           {"revolute", JointType::kRevolute},
                                           {"fixed", JointType::kFixed},
                                           {"prismatic", JointType::kPrismatic}};

}  // namespace

const char* jointTypeName(JointType t) { return spell(kJointTypes, t); }
bool parseKind(std::string_view text, JointType* type) {
  return parseSpelling(kJointTypes, text, type);
}

Joint::Joint(std::string name, JointType type, JointEnd a, JointEnd b)
    : name_(std::move(name)), type_(type), a_(std::move(a)), b_(std::move(b)) {
  FFRIGA_CHECK(b_.model != nullptr, "joint '" << name_ << "': end b must be a body");
  FFRIGA_CHECK((a_.model == nullptr) == (a_.body < 0), "joint '" << name_ << "': end a");
}

int Joint::numEquations() const {
  switch (type_) {
    case JointType::kSpherical:
      return 3;
    case JointType::kRevolute:
      return 5;
    case JointType::kFixed:
      return 6;
    case JointType::kPrismatic:
      return 5;
  }
  return 0;
}

void Joint::setAxes(const Eigen::Matrix3d& E, const Eigen::Matrix3d& Aa,
                     const Eigen::Matrix3d& Ab) {
  a_.axes = a_.model ? Eigen::Matrix3d(Aa.transpose() * E) : E;
  b_.axes = Ab.transpose() * E;
}

void Joint::evaluate(const double* spA, const double* svA, const double* spB, const double* svB,
                     JointRows& r) const {
  const int m = numEquations();
  const int nva = a_.model ? a_.model->numVelocities() : 0;
  const int nvb = b_.model->numVelocities();
  r.g.resize(m);
  r.bias.resize(m);
  r.Ja.setZero(m, nva);
  r.Jb.setZero(m, nvb);
  MarkerKinematics k;
  auto point = [&](int side) {
    if (side == 0 && !a_.model) {
      groundKinematics(a_.marker.x0, k);
    } else {
      const JointEnd& e = side == 0 ? a_ : b_;
      markerPoint(*e.model, side == 0 ? spA : spB, side == 0 ? svA : svB, e.marker, k);
    }
    return fromEnd(k, side, nva, nvb);
  };
  auto axis = [&](int side, int i) {
    const JointEnd& e = side == 0 ? a_ : b_;
    if (side == 0 && !a_.model) {
      groundKinematics(e.axes.col(i), k);
    } else {
      markerVector(*e.model, side == 0 ? spA : spB, side == 0 ? svA : svB, e.marker, e.axes.col(i),
                   k);
    }
    return fromEnd(k, side, nva, nvb);
  };
  const Factor Ra = point(0), Rb = point(1);
  const Factor d{Rb.value - Ra.value, Rb.rate - Ra.rate, Rb.bias - Ra.bias, Rb.Ga - Ra.Ga,
                 Rb.Gb - Ra.Gb};
  int row = 0;
  if (type_ != JointType::kPrismatic) {
    for (int i = 0; i < 3; ++i, ++row) {
      r.g(row) = d.value(i);
      r.bias(row) = d.bias(i);
      r.Ja.row(row) = d.Ga.row(i);
      r.Jb.row(row) = d.Gb.row(i);
    }
  } else {
    dotRow(axis(0, 0), d, row++, r);
    dotRow(axis(0, 1), d, row++, r);
  }
  if (type_ == JointType::kRevolute) {
    const Factor b3 = axis(1, 2);
    dotRow(axis(0, 0), b3, row++, r);
    dotRow(axis(0, 1), b3, row++, r);
  } else if (type_ == JointType::kFixed || type_ == JointType::kPrismatic) {
    dotRow(axis(0, 1), axis(1, 2), row++, r);
    dotRow(axis(0, 2), axis(1, 0), row++, r);
    dotRow(axis(0, 0), axis(1, 1), row++, r);
  }
  FFRIGA_ASSERT(row == m, "joint '" << name_ << "': " << row << " of " << m << " equations");
}

JointReaction Joint::reaction(const double* spB, const JointRows& rows,
                              const Eigen::VectorXd& lambda) const {
  const Eigen::VectorXd Q = rows.Jb.transpose() * lambda;  // generalised force on body b
  const int nq = b_.model->nq();
  Eigen::Vector3d p = b_.marker.x0;
  if (nq > 0) p += b_.marker.Phi * Eigen::Map<const Eigen::VectorXd>(spB + 7, nq);
  const Eigen::Matrix3d A = rotationMatrix(spB + 3);
  const Eigen::Vector3d F = Q.head<3>(), N = Q.segment<3>(3);  // body components, about r_R
  JointReaction out;
  out.force = A * F;
  out.moment = A * (N - p.cross(F));
  out.violation = rows.g.lpNorm<Eigen::Infinity>();
  return out;
}

}  // namespace ffriga
