#include "runtime/bodies/quasi_static_rule.h"

#include <cmath>
#include <limits>

namespace ffriga {

double lowestElasticFrequencyHz(const Eigen::VectorXd& k) {
  double kmin = std::numeric_limits<double>::infinity();
  for (int i = 0; i < k.size(); ++i)
    if (k(i) > 0.0) kmin = std::min(kmin, k(i));
  return std::isfinite(kmin) ? std::sqrt(kmin) / (2.0 * M_PI) : 0.0;
}

double quasiStaticCutoffHz(const Eigen::VectorXd& k, const QuasiStaticRule& rule) {
  const double inf = std::numeric_limits<double>::infinity();
  const double f1 = lowestElasticFrequencyHz(k);
  switch (rule.kind) {
    case QuasiStaticRule::Kind::kNone:
      return inf;
    case QuasiStaticRule::Kind::kAboveHz:
      return rule.value;
    case QuasiStaticRule::Kind::kAboveFirstElastic:
      return f1 > 0.0 ? rule.value * f1 : inf;
    case QuasiStaticRule::Kind::kDefault:
      return f1 > 0.0 ? QuasiStaticRule::kDefaultFactor * f1 : inf;
  }
  return inf;
}

}  // namespace ffriga
