// A linear elastic, isotropic, homogeneous material (Hooke's law, the paper's Sect. 2): the
// one material type of the project, from the body file (key `material`) through assembly
// and the SID (/material) to stresses and Hertz's reference.
#pragma once

namespace ffriga {

struct IsotropicMaterial {
  double youngs_modulus = 0.0;  // E, Pa
  double poisson_ratio = 0.0;   // nu, 1, -1 < nu < 1/2
  double density = 0.0;         // rho, kg/m^3
  // Lame's constants: lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)), Pa.
  double lambda() const;
  double mu() const;
};

}  // namespace ffriga
