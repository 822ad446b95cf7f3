// Process noise that follows the normalised innovation squared (An et al. 2014 §4.1, after their
// single-target filter [37]): a track whose innovations grow too large for its filter gets a
// larger q (a manoeuvre), one whose innovations stay small gets a smaller q (straight motion).
#pragma once

#include <algorithm>

namespace wsn::supernode::rulebased {

/// Bounds and thresholds of the adaptation; q in length per tick^2 (the sigma of Oh eq. 8's w).
struct NisAdaptationConfig {
  double q_initial = 0.05;
  double q_min = 0.0025;
  double q_max = 5.0;
  /// The smoothed NIS above which q doubles: chi^2 with 2 degrees of freedom, 95 %.
  double nis_high = 5.99;
  /// The smoothed NIS below which q halves: chi^2 with 2 degrees of freedom, 20 %.
  double nis_low = 0.446;
  /// Weight of the newest NIS in the exponential average: 1 / (the number of updates it spans).
  double smoothing = 0.2;
};

/// The adaptive q of one track. A consistent filter has E[NIS] = 2 (the measurement dimension,
/// Bar-Shalom et al. 2001 §5.4); the smoothed NIS is compared with chi^2 bounds and q is scaled
/// by 2 in the direction that restores consistency, clamped to [q_min, q_max].
class NisAdaptation {
 public:
  explicit NisAdaptation(const NisAdaptationConfig& config) : config_(config), q_(config.q_initial) {}
  /// q to use in the next prediction.
  double q() const { return q_; }
  /// The smoothed NIS (starts at its expectation, 2).
  double smoothedNis() const { return nis_; }
  /// Takes the NIS nu^T S^-1 nu of the latest update.
  void observe(double nis) {
    nis_ += config_.smoothing * (nis - nis_);
    if (nis_ > config_.nis_high)
      q_ = std::min(2.0 * q_, config_.q_max);
    else if (nis_ < config_.nis_low)
      q_ = std::max(0.5 * q_, config_.q_min);
  }

 private:
  NisAdaptationConfig config_;
  double q_;
  double nis_ = 2.0;
};

}  // namespace wsn::supernode::rulebased
