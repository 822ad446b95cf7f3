#include "supernode/sbmht/track_score.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace wsn::supernode::sbmht {

double initialScore(InitialScore rule, double detection_probability, double false_alarm_density,
                    double new_target_density) {
  switch (rule) {
    case InitialScore::paper:
      return std::log(false_alarm_density / (false_alarm_density + new_target_density));
    case InitialScore::blackman:
      return std::log(detection_probability * new_target_density / false_alarm_density);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double reportScoreIncrement(double combined_likelihood, double false_alarm_density) {
  return std::log(combined_likelihood / false_alarm_density);
}

double missScoreIncrement(double combined_likelihood) { return std::log(combined_likelihood); }

SprtThresholds SprtThresholds::fromErrorRates(double alpha, double beta, double drop_confirmed) {
  return {std::log((1.0 - beta) / alpha), std::log(beta / (1.0 - alpha)), drop_confirmed};
}

TrackStatus decide(TrackStatus current, double score, double best_score, const SprtThresholds& thresholds) {
  switch (current) {
    case TrackStatus::deleted:
      return TrackStatus::deleted;
    case TrackStatus::confirmed:
      return best_score - score > thresholds.drop_confirmed ? TrackStatus::deleted : TrackStatus::confirmed;
    case TrackStatus::tentative:
      if (score >= thresholds.confirm) return TrackStatus::confirmed;
      if (score <= thresholds.delete_tentative) return TrackStatus::deleted;
      return TrackStatus::tentative;
  }
  return current;
}

TrackScore TrackScore::start(double initial) { return {initial, initial, TrackStatus::tentative}; }

TrackScore TrackScore::after(double increment, const SprtThresholds& thresholds) const {
  TrackScore next;
  next.score = score + increment;
  next.best_score = std::max(best_score, next.score);
  next.status = decide(status, next.score, next.best_score, thresholds);
  return next;
}

}  // namespace wsn::supernode::sbmht
