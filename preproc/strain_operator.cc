#include "preproc/strain_operator.h"

#include <cmath>

#include "common/error.h"

namespace ffriga {

double IsotropicMaterial::lambda() const {
  const double nu = poisson_ratio;
  return youngs_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

double IsotropicMaterial::mu() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }

Eigen::MatrixXd constitutiveMatrix(const IsotropicMaterial& m, bool axisymmetric) {
  const double l = m.lambda(), mu = m.mu();
  const int n = strainComponents(axisymmetric);
  const int normal = 3;  // e_xx, e_yy, e_zz or e_rr, e_yy, e_tt come first in both
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < normal; ++i) {
    for (int j = 0; j < normal; ++j) D(i, j) = l;
    D(i, i) = l + 2.0 * mu;
  }
  for (int i = normal; i < n; ++i) D(i, i) = mu;
  return D;
}

void strainOperator(const Eigen::MatrixXd& grad, const Eigen::Ref<const Eigen::RowVectorXd>& values,
                    bool axisymmetric, double radius, bool on_axis, Eigen::MatrixXd& B) {
  const int nb = static_cast<int>(values.size());
  const int s = axisymmetric ? 2 : 3;
  FFRIGA_ASSERT(grad.rows() >= s && grad.cols() == nb,
                "gradient table " << grad.rows() << " x " << grad.cols() << " for " << nb
                                  << " functions");
  B.setZero(strainComponents(axisymmetric), s * nb);
  for (int j = 0; j < nb; ++j) {
    if (!axisymmetric) {
      const double gx = grad(0, j), gy = grad(1, j), gz = grad(2, j);
      const int c = 3 * j;
      B(0, c) = gx;
      B(1, c + 1) = gy;
      B(2, c + 2) = gz;
      B(3, c) = gy, B(3, c + 1) = gx;      // g_xy
      B(4, c + 1) = gz, B(4, c + 2) = gy;  // g_yz
      B(5, c) = gz, B(5, c + 2) = gx;      // g_xz
    } else {
      const double gr = grad(0, j), gy = grad(1, j);
      const int c = 2 * j;
      B(0, c) = gr;                                      // e_rr
      B(1, c + 1) = gy;                                  // e_yy
      B(2, c) = on_axis ? gr : values(j) / radius;       // e_tt = u_r / r
      B(3, c) = gy, B(3, c + 1) = gr;                    // g_ry
    }
  }
}

}  // namespace ffriga
