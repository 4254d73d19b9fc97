// CVODE's error weights w_i (the local error test and the Newton iteration's convergence test
// both measure in the norm sqrt(mean((w_i x_i)^2)) over all n components), with algebraic
// components left out.
//
// An algebraic component gets w_i = 0, as IDA's IDASetSuppressAlg leaves algebraic
// variables out of its error test: in an index-1 DAE they are functions of the differential
// ones, and so are their errors (Hairer & Wanner, Solving ODEs II, Sect. VI.1). A
// differential one gets CVODE's usual weight times sqrt(n / m), m the number of differential
// components: w_i = sqrt(n / m) / (rtol |y_i| + atol_i), so that the norm is their own root
// mean square and rtol and atol mean what they mean without algebraic components.
//
// The algebraic components here are the quasi-static elastic coordinates
// (runtime/bodies/quasi_static_modes.h): CVODE integrates them as a stiff relaxation, but the
// projection after every step (runtime/system/quasi_static_projection.cc) puts them on their
// manifold a_s(y) = 0 exactly, as functions of the differential state. Their local error
// estimate (corrector minus predictor) measures how well a polynomial extrapolates q_s(t),
// not how accurate the solution is; where a collocation point enters or leaves contact the
// contact force, and so q_s, has a kink (Hertz's pressure even grows like sqrt(t - t_enter)
// at a point the contact edge passes), and the test rejected step after step there
// (benchmarks/step_control.py).
#pragma once

#include <vector>

#include <nvector/nvector_serial.h>
#include <Eigen/Dense>

namespace ffriga {

struct ErrorWeights {
  double rtol = 1e-6;           // dimensionless
  Eigen::VectorXd atol;         // per component (units of y)
  std::vector<bool> algebraic;  // per component; empty: none

  bool anyAlgebraic() const;

  // The weights at y into ewt (for a CVEwtFn, CVodeWFtolerances); 0, or -1 where a
  // differential component's tolerance is not positive.
  static int evaluate(N_Vector y, N_Vector ewt, const ErrorWeights* weights);

  // The increment scale of difference quotients at the state y: the tolerance
  // rtol |y_i| + atol_i of each component (1 / w_i from CVODE's weights ewt where no
  // component is algebraic, as before this class).
  void differenceScale(N_Vector y, N_Vector ewt, std::vector<double>& scale) const;
};

}  // namespace ffriga
