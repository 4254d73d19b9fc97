#include "runtime/integration/error_weights.h"

#include <algorithm>
#include <cmath>

namespace ffriga {

bool ErrorWeights::anyAlgebraic() const {
  return std::any_of(algebraic.begin(), algebraic.end(), [](bool a) { return a; });
}

int ErrorWeights::evaluate(N_Vector y, N_Vector ewt, const ErrorWeights* weights) {
  const ErrorWeights& w = *weights;
  const sunindextype n = N_VGetLength(y);
  // CVODE's norm divides by all n components; the factor makes it the root mean square over
  // the tested ones, so that rtol and atol mean for them what they mean without algebraic
  // components (else the test loosens by sqrt(n / tested): 2.5 on the Sect. 5 impact).
  const long tested = std::count(w.algebraic.begin(), w.algebraic.end(), false);
  if (tested == 0) return -1;
  const double factor = std::sqrt(static_cast<double>(n) / static_cast<double>(tested));
  for (sunindextype i = 0; i < n; ++i) {
    const double tolerance = w.rtol * std::abs(NV_Ith_S(y, i)) + w.atol(i);
    if (w.algebraic[i]) {
      NV_Ith_S(ewt, i) = 0.0;
    } else {
      if (!(tolerance > 0.0)) return -1;
      NV_Ith_S(ewt, i) = factor / tolerance;
    }
  }
  return 0;
}

void ErrorWeights::differenceScale(N_Vector y, N_Vector ewt, std::vector<double>& scale) const {
  const sunindextype n = N_VGetLength(ewt);
  scale.resize(n);
  for (sunindextype i = 0; i < n; ++i)
    scale[i] =
        algebraic.empty() ? 1.0 / NV_Ith_S(ewt, i) : rtol * std::abs(NV_Ith_S(y, i)) + atol(i);
}

}  // namespace ffriga
