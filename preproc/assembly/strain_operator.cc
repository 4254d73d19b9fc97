#include "preproc/assembly/strain_operator.h"

#include <cmath>

#include "common/base/error.h"

namespace ffriga {

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

void isotropicStiffness(const Eigen::MatrixXd G[3], const IsotropicMaterial& m, bool axisymmetric,
                        Eigen::MatrixXd& Ke) {
  const double lambda = m.lambda(), mu = m.mu();
  const int nb = static_cast<int>(G[0].cols());
  if (!axisymmetric) {
    Ke.setZero(3 * nb, 3 * nb);
    Eigen::MatrixXd H[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) H[i][j].noalias() = G[i].transpose() * G[j];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < i; ++j) H[i][j] = H[j][i].transpose();
    const Eigen::MatrixXd L = H[0][0] + H[1][1] + H[2][2];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        Eigen::MatrixXd block = lambda * H[i][j] + mu * H[j][i];
        if (i == j) block += mu * L;
        for (int a = 0; a < nb; ++a)
          for (int b = 0; b < nb; ++b) Ke(a * 3 + i, b * 3 + j) = block(a, b);
      }
    }
    return;
  }
  // Strain rows of function a: e_rr = Gr u_r, e_yy = Gy u_y, e_tt = Gt u_r,
  // g_ry = Gy u_r + Gr u_y.
  Ke.setZero(2 * nb, 2 * nb);
  const Eigen::MatrixXd &Gr = G[0], &Gy = G[1], &Gt = G[2];
  const Eigen::MatrixXd rr = Gr.transpose() * Gr, yy = Gy.transpose() * Gy,
                        tt = Gt.transpose() * Gt, ry = Gr.transpose() * Gy,
                        rt = Gr.transpose() * Gt, yt = Gy.transpose() * Gt;
  const double l2m = lambda + 2.0 * mu;
  for (int a = 0; a < nb; ++a) {
    for (int b = 0; b < nb; ++b) {
      Ke(2 * a, 2 * b) =
          l2m * (rr(a, b) + tt(a, b)) + lambda * (rt(a, b) + rt(b, a)) + mu * yy(a, b);
      Ke(2 * a, 2 * b + 1) = lambda * (ry(a, b) + yt(b, a)) + mu * ry(b, a);
      Ke(2 * a + 1, 2 * b) = lambda * (ry(b, a) + yt(a, b)) + mu * ry(a, b);
      Ke(2 * a + 1, 2 * b + 1) = l2m * yy(a, b) + mu * rr(a, b);
    }
  }
}

}  // namespace ffriga
