#include "common/mechanics/isotropic_material.h"

namespace ffriga {

double IsotropicMaterial::lambda() const {
  const double nu = poisson_ratio;
  return youngs_modulus * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

double IsotropicMaterial::mu() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }

}  // namespace ffriga
