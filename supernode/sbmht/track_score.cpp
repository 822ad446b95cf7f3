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

ClassVector initialClassProbabilities(const ClassVector& likelihoods) {
  const double total = likelihoods.sum();
  if (!(total > 0.0)) return uniformClassProbabilities(static_cast<int>(likelihoods.size()));
  return likelihoods / total;
}

ClassUpdate updateClass(const ClassVector& probabilities, const ClassVector& likelihoods,
                        const ClassVector& extraneous_probabilities) {
  ClassUpdate out{probabilities, 0.0};
  if (likelihoods.size() == 0) return out;  // the sensor does not classify
  if (likelihoods.size() != probabilities.size() || likelihoods.size() != extraneous_probabilities.size())
    throw std::invalid_argument("updateClass: c, beta and beta_e must have one entry per class");
  if (!(likelihoods.sum() > 0.0)) return out;
  if (!(likelihoods.dot(extraneous_probabilities) > 0.0))
    throw std::invalid_argument("updateClass: beta_e gives the report's class likelihoods no weight");
  const double track_evidence = likelihoods.dot(probabilities);
  if (!(track_evidence > 0.0)) {
    out.score_increment = -std::numeric_limits<double>::infinity();
    return out;
  }
  out.probabilities = likelihoods.cwiseProduct(probabilities) / track_evidence;
  out.score_increment = std::log(track_evidence / likelihoods.dot(extraneous_probabilities));
  return out;
}

ClassVector uniformClassProbabilities(int classes) {
  return ClassVector::Constant(classes, classes > 0 ? 1.0 / classes : 0.0);
}

int mostProbableClass(const ClassVector& probabilities) {
  if (probabilities.size() == 0) return -1;
  Eigen::Index best = 0;
  for (Eigen::Index i = 1; i < probabilities.size(); ++i)
    if (probabilities(i) > probabilities(best)) best = i;
  return static_cast<int>(best);
}

}  // namespace wsn::supernode::sbmht
