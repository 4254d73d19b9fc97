// Which elastic coordinates of a body are quasi-static (runtime/bodies/quasi_static_modes.h):
// a cutoff frequency f_cut, given in the scene in Hz or relative to the body, or by default
// relative to the body's lowest elastic frequency f_1:
//
//   f_cut = kDefaultFactor * f_1.
//
// Why relative to f_1: the loads that matter here (impacts) last about as long as the
// body's slowest elastic response or longer. Hertz's contact time of two equal spheres is
// t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5) while their lowest free vibration is f_1 ~ 0.84 c_s
// / (2 R) (Lamb's spheroidal mode): both scale with the radius, so f_1 t_c depends only
// weakly on size and speed (v^(-1/5)); for the steel spheres of Sect. 5 (r = 1 cm, 0.1 m/s)
// f_1 = 135 kHz, t_c = 82.7 us, f_1 t_c = 11. A fixed number of Hz does not scale: the same
// 1 MHz on a sphere twice as large leaves its interface modes dynamic (the complaint about
// Sect. 5's damping rule). Modes up to kDefaultFactor f_1 keep their inertia (they carry
// the elastic waves that put the elastodynamic force peak above Hertz's); above it the
// dynamic amplification under such a load is below (1 / (kDefaultFactor f_1 t_c))^2 ~ 5e-4.
// The factor 4 keeps the global normal modes of the Sect. 5 spheres (1 .. 2.7 f_1) dynamic
// and makes the first localised one (7.5 f_1, 1.0 MHz) and every constraint mode (>= 32 f_1)
// quasi-static: the force peak is 146.69 N, 0.01 % below the elastodynamic reference's
// 146.7-147.0 N, in ~1,130 steps; with the 7.5 f_1 mode dynamic (factor 8) it is 147.02 N
// in ~3,980 steps (benchmarks/quasi_static.py sweeps the cutoff and the number of normal
// modes).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "runtime/bodies/quasi_static_modes.h"

namespace ffriga {

struct QuasiStaticRule {
  static constexpr double kDefaultFactor = 4.0;
  enum class Kind { kDefault, kNone, kAboveHz, kAboveFirstElastic };
  Kind kind = Kind::kDefault;
  double value = 0.0;  // Hz (kAboveHz) or a factor on f_1 (kAboveFirstElastic)
};

// The cutoff f_cut in Hz for the stiffness diagonal k (1/s^2, elastic coordinates of Me = E);
// +infinity for none (kNone, or no elastic coordinate with k > 0).
double quasiStaticCutoffHz(const Eigen::VectorXd& k, const QuasiStaticRule& rule);

// Warnings about modes in a band the treatment handles badly, one line each (empty if none),
// for the body `name` with stiffness and damping diagonals k (1/s^2), c (1/s) and its
// quasi-static coordinates qs (empty: all dynamic):
//   * quasi-static coordinates present: dynamic modes below the cutoff that are damped
//     (they dissipate energy the quasi-static treatment would keep); a cutoff below f_1
//     (no elastic wave left) or above 8 x the default (dynamic modes far above it set
//     the step size);
//   * none: undamped modes above 8 x the default cutoff (their periods, shorter than the
//     load by orders of magnitude, set the step: the run may take hours).
std::vector<std::string> modeBandWarnings(const std::string& name, const Eigen::VectorXd& k,
                                          const Eigen::VectorXd& c, const QuasiStaticModes& qs);

// The body's lowest elastic frequency sqrt(min k_i) / (2 pi) over k_i > 0 (Hz; 0 if none).
double lowestElasticFrequencyHz(const Eigen::VectorXd& k);

}  // namespace ffriga
