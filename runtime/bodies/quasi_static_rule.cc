#include "runtime/bodies/quasi_static_rule.h"

#include <cmath>
#include <limits>

#include "common/base/error.h"

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

std::vector<std::string> modeBandWarnings(const std::string& name, const Eigen::VectorXd& k,
                                          const Eigen::VectorXd& c, const QuasiStaticModes& qs) {
  std::vector<std::string> w;
  const double f1 = lowestElasticFrequencyHz(k);
  if (f1 <= 0.0) return w;
  const double fDefault = QuasiStaticRule::kDefaultFactor * f1, far = 8.0 * fDefault;
  auto hz = [&](int i) { return std::sqrt(std::max(k(i), 0.0)) / (2.0 * M_PI); };
  if (!qs.empty()) {
    int damped = 0;
    double zetaMax = 0.0;
    for (int i = 0; i < k.size(); ++i) {
      if (hz(i) >= qs.cutoff_hz || !(c(i) > 0.0) || !(k(i) > 0.0)) continue;
      ++damped;
      zetaMax = std::max(zetaMax, c(i) / (2.0 * std::sqrt(k(i))));
    }
    if (damped > 0)
      w.push_back(Str() << "body '" << name << "': " << damped << " dynamic mode(s) below the "
                        << "quasi-static cutoff " << qs.cutoff_hz << " Hz are damped (zeta up to "
                        << zetaMax << "): they dissipate energy; remove the damping (body file "
                        << "'reduction.damping', or the scene's damping: {scale: 0})");
    if (qs.cutoff_hz < f1)
      w.push_back(Str() << "body '" << name << "': the quasi-static cutoff " << qs.cutoff_hz
                        << " Hz is below the lowest elastic frequency " << f1
                        << " Hz: every mode is quasi-static, no elastic wave is represented");
    if (qs.cutoff_hz > far)
      w.push_back(Str() << "body '" << name << "': the quasi-static cutoff " << qs.cutoff_hz
                        << " Hz is far above the default " << fDefault << " Hz (" 
                        << QuasiStaticRule::kDefaultFactor << " x f_1): the dynamic modes up to "
                        << "it set the step size");
  } else {
    int stiff = 0;
    double fmax = 0.0;
    for (int i = 0; i < k.size(); ++i) {
      if (hz(i) <= far || c(i) > 0.0) continue;
      ++stiff;
      fmax = std::max(fmax, hz(i));
    }
    if (stiff > 0)
      w.push_back(Str() << "body '" << name << "': " << stiff << " undamped mode(s) up to " << fmax
                        << " Hz, far above " << fDefault << " Hz (" << QuasiStaticRule::kDefaultFactor
                        << " x f_1), are dynamic: they set the step size (the run may take "
                        << "hours); make them quasi-static (drop 'quasi_static: false') or damp them");
  }
  return w;
}

}  // namespace ffriga
