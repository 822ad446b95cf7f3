// The SB-MHT track score (ONERA eqs. 16-18, 21-23, as docs/ONERA.md resolves them with Blackman &
// Popoli ch. 16): kinematic and class log-likelihood ratios, and Wald's SPRT on them.
#pragma once

#include <Eigen/Core>

#include "common/measurement.hpp"

namespace wsn::supernode::sbmht {

/// How a track's score starts at its first report.
enum class InitialScore {
  /// Eq. 18, ln(lambda_fa / (lambda_fa + lambda_nt)): ln P(false), never positive, so a track
  /// needs one more report to confirm than under blackman.
  paper,
  /// Blackman & Popoli's L(1) = ln(PD lambda_nt / lambda_fa), the LLR of a first report (the
  /// default of docs/ONERA.md; MATLAB's trackScoreLogic agrees).
  blackman,
};

/// L(1). lambda_fa and lambda_nt are densities in the first report's own space (per m^2 for a
/// position report) per scan.
double initialScore(InitialScore rule, double detection_probability, double false_alarm_density,
                    double new_target_density);

/// Delta L of a report (eq. 17): ln(Lambda_k / lambda_fa), Lambda_k the IMM's combined likelihood
/// and lambda_fa the reporting sensor's false-alarm density in its measurement space.
double reportScoreIncrement(double combined_likelihood, double false_alarm_density);

/// Delta L of a miss: ln Lambda_k, since no false alarm competes with a missing report (eq. 17
/// would divide a probability by a density). Blackman & Popoli's ln(1 - PD) when only one moving
/// model is possible and Pe = 1.
double missScoreIncrement(double combined_likelihood);

/// Wald's SPRT thresholds (docs/ONERA.md §3).
struct SprtThresholds {
  /// T1 = ln((1 - beta) / alpha): a track at or above it is confirmed.
  double confirm = 0.0;
  /// T2 = ln(beta / (1 - alpha)): a tentative track at or below it is deleted.
  double delete_tentative = 0.0;
  /// A confirmed track that falls more than this below its best score is deleted.
  double drop_confirmed = 10.0;

  /// alpha = P(confirming a false track), beta = P(deleting a true one).
  static SprtThresholds fromErrorRates(double alpha, double beta, double drop_confirmed = 10.0);
};

enum class TrackStatus { tentative, confirmed, deleted };

/// A track's score, its best score so far and the SPRT's verdict on them.
struct TrackScore {
  double score = 0.0;
  double best_score = 0.0;
  TrackStatus status = TrackStatus::tentative;

  /// A new track scoring `initial`, tentative whatever `initial` is: L(1) is the prior odds of a
  /// new target against a false alarm, not evidence yet, and with the proposed densities it lies
  /// below T2 (B&P: ln(.9 * 1e-5 / 1e-4) = -2.408 < -2.302), which would delete every track at birth.
  /// The SPRT judges from the next scan on.
  static TrackScore start(double initial);
  /// The score after a scan's increment, and the SPRT's decision on it. A deleted track stays
  /// deleted; a confirmed one never returns to tentative.
  TrackScore after(double increment, const SprtThresholds& thresholds) const;
};

/// The SPRT's decision for a track of status `current` now at `score`, best so far `best_score`.
TrackStatus decide(TrackStatus current, double score, double best_score, const SprtThresholds& thresholds);

/// A track's class probabilities beta (common/class_evidence.hpp has eqs. 19, 20 and 23) in a
/// vector of fixed capacity, so that copying a leaf allocates nothing for it.
using ClassVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, static_cast<int>(common::kMaxClasses), 1>;

}  // namespace wsn::supernode::sbmht
