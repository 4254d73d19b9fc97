// Small vectors of the contact hot path with their storage inside the object: a point or
// direction in the contact space (d = 2 or 3 components) and surface parameters (1 or 2).
// Every collocation point is evaluated at every right-hand side; heap-allocated temporaries
// there cost about a sixth of a run's time in malloc and free (perf, impact2d_h3).
//
// A product of a dynamic matrix with a vector of fixed capacity takes another Eigen kernel
// (coefficient-based instead of GEMV) that rounds differently: such operands enter products
// through dynamic(), a dynamic view of the same storage, and the results keep their bits.
#pragma once

#include <Eigen/Dense>

namespace ffriga {

using SpaceVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
using ParamVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2, 1>;
// A vector argument of any contiguous kind (Eigen::VectorXd, a SpaceVector), taken without a
// copy.
using VectorRef = Eigen::Ref<const Eigen::VectorXd>;

// The vector as a dynamic one (no copy) for products with dynamic matrices.
template <typename Vector>
Eigen::Map<const Eigen::VectorXd> dynamic(const Vector& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), v.size());
}

}  // namespace ffriga
