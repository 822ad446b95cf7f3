#include "common/class_evidence.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wsn::common {
namespace {

// A class vector comes out of eq. (19) normalised up to rounding; a sum further from 1 than this
// means a caller built or combined it without normalising, and eq. (23)'s c'beta would be off
// by that factor.
constexpr double kSumTolerance = 1e-9;

void requireLikelihoods(std::span<const double> c, std::size_t class_count, const char* who) {
  if (c.size() != class_count) {
    throw std::invalid_argument(std::string(who) + ": " + std::to_string(c.size()) + " class likelihoods for " +
                                std::to_string(class_count) + " classes");
  }
  bool any_positive = false;
  for (const double v : c) {
    if (!std::isfinite(v) || v < 0.0) {
      throw std::invalid_argument(std::string(who) + ": a class likelihood is negative or not finite");
    }
    any_positive = any_positive || v > 0.0;
  }
  // All zero would say the report cannot come from any class: no sensor model produces that, and
  // eq. (20) and beta_e's c'beta_e would divide by zero.
  if (!any_positive) throw std::invalid_argument(std::string(who) + ": every class likelihood is zero");
}

void requireClassVector(const ClassVector& beta, const char* who) {
  if (beta.size() == 0) throw std::invalid_argument(std::string(who) + ": empty class vector");
  if (!beta.allFinite() || (beta.array() < 0.0).any()) {
    throw std::invalid_argument(std::string(who) + ": a class probability is negative or not finite");
  }
  if (std::abs(beta.sum() - 1.0) > kSumTolerance) {
    throw std::invalid_argument(std::string(who) + ": the class probabilities do not sum to 1");
  }
}

void requireConfusionMatrix(const ConfusionMatrix& cm, const char* who) {
  if (cm.rows() != cm.cols() || cm.rows() == 0) {
    throw std::invalid_argument(std::string(who) + ": a confusion matrix must be square and non-empty");
  }
  for (Eigen::Index i = 0; i < cm.rows(); ++i) {
    double sum = 0.0;
    for (Eigen::Index j = 0; j < cm.cols(); ++j) {
      const double p = cm(i, j);
      if (!std::isfinite(p) || p < 0.0) {
        throw std::invalid_argument(std::string(who) + ": a confusion probability is negative or not finite");
      }
      sum += p;
    }
    if (std::abs(sum - 1.0) > kSumTolerance) {
      throw std::invalid_argument(std::string(who) + ": row " + std::to_string(i) + " does not sum to 1");
    }
  }
}

void requireProbability(double p, const char* who) {
  if (!(p >= 0.0 && p <= 1.0)) throw std::invalid_argument(std::string(who) + ": probability outside [0, 1]");
}

// A c whose entries are all equal favours no class: eq. (19) leaves beta and eq. (23) gives
// ln 1. Returning beta itself and exactly 0 keeps a track that only non-classifying sensors see
// bit for bit what it was, instead of drifting by rounding.
bool carriesNoClassInformation(std::span<const double> c) {
  for (const double v : c) {
    if (v != c.front()) return false;
  }
  return true;
}

bool isVehicle(TargetClass c) {
  return c == TargetClass::kWheeledLight || c == TargetClass::kWheeledHeavy || c == TargetClass::kTracked;
}

}  // namespace

std::optional<std::size_t> classIndex(TargetClass c) {
  if (c == TargetClass::kUnknown) return std::nullopt;
  return static_cast<std::size_t>(c) - 1;
}

TargetClass classAt(std::size_t index) {
  if (index >= kClassCount) throw std::out_of_range("classAt: class index " + std::to_string(index));
  return static_cast<TargetClass>(index + 1);
}

ClassVector uniformClassVector(std::size_t class_count) {
  if (class_count == 0) throw std::invalid_argument("uniformClassVector: no classes");
  const auto n = static_cast<Eigen::Index>(class_count);
  return ClassVector::Constant(n, 1.0 / static_cast<double>(class_count));
}

ClassVector initialClassVector(std::span<const double> c, std::size_t class_count) {
  if (c.empty()) return uniformClassVector(class_count);
  requireLikelihoods(c, class_count, "initialClassVector");
  const Eigen::Map<const ClassVector> likelihoods(c.data(), static_cast<Eigen::Index>(c.size()));
  return likelihoods / likelihoods.sum();
}

ClassUpdate updateClassVector(const ClassVector& beta, std::span<const double> c) {
  requireClassVector(beta, "updateClassVector");
  if (c.empty()) return {beta, 0.0};
  requireLikelihoods(c, static_cast<std::size_t>(beta.size()), "updateClassVector");
  if (carriesNoClassInformation(c)) return {beta, 0.0};

  const Eigen::Map<const ClassVector> likelihoods(c.data(), beta.size());
  const ClassVector product = likelihoods.cwiseProduct(beta);
  // Normalising by the sum of the very product makes beta+ sum to 1 as closely as rounding allows.
  const double predicted = product.sum();  // c'beta: the report's class likelihood under this track
  // c'beta = 0: every class this track can be has likelihood 0 for the report, so it cannot have
  // come from this track. The score says so (ln 0 = -inf: eq. 21 then excludes the branch, as an
  // SPRT deletes it), and beta stays as it was because eq. (19) is 0/0 there: the report holds no
  // evidence about a track it does not belong to. Throwing instead would make an improbable but
  // legal report abort the tracker.
  if (!(predicted > 0.0)) return {beta, -std::numeric_limits<double>::infinity()};
  const double extraneous = likelihoods.sum() / static_cast<double>(beta.size());  // c'beta_e, beta_e uniform
  return {product / predicted, std::log(predicted / extraneous)};
}

std::size_t mostLikelyClass(const ClassVector& beta) {
  if (beta.size() == 0) throw std::invalid_argument("mostLikelyClass: empty class vector");
  if (!beta.allFinite()) throw std::invalid_argument("mostLikelyClass: a class probability is not finite");
  Eigen::Index best = 0;
  beta.maxCoeff(&best);  // Eigen keeps the first maximum
  return static_cast<std::size_t>(best);
}

std::optional<ClassVector> receivedClassVector(std::span<const double> beta, std::size_t class_count) {
  // Looser than kSumTolerance: a vector fused from others, or written by another build, carries
  // the rounding of its normalisation.
  constexpr double kReceivedSumTolerance = 1e-6;
  if (beta.size() != class_count || class_count == 0) return std::nullopt;
  double sum = 0.0;
  for (const double p : beta) {
    if (!std::isfinite(p) || p < 0.0) return std::nullopt;
    sum += p;
  }
  if (std::abs(sum - 1.0) > kReceivedSumTolerance) return std::nullopt;
  return ClassVector(Eigen::Map<const ClassVector>(beta.data(), static_cast<Eigen::Index>(beta.size())));
}

DeclaredClass declaredTrackClass(std::span<const double> beta) {
  const auto valid = receivedClassVector(beta);
  if (!valid || (valid->array() == (*valid)(0)).all()) return {};
  const std::size_t best = mostLikelyClass(*valid);
  return {classAt(best), (*valid)(static_cast<Eigen::Index>(best))};
}

std::vector<double> fuseClassVectors(std::span<const std::span<const double>> members) {
  std::vector<ClassVector> valid;
  for (const auto member : members) {
    if (member.empty()) continue;
    if (auto beta = receivedClassVector(member, member.size())) valid.push_back(std::move(*beta));
  }
  if (valid.empty()) return {};
  const Eigen::Index n = valid.front().size();
  std::erase_if(valid, [n](const ClassVector& beta) { return beta.size() != n; });  // not one class set
  if (valid.size() == 1) return {valid.front().begin(), valid.front().end()};
  // In logs, so that many small probabilities neither underflow nor lose precision.
  // std::log, not Eigen's vectorised log, whose log(0) is a large finite negative number rather than
  // -infinity: a class a member excludes must stay excluded exactly.
  ClassVector log_mean = ClassVector::Zero(n);
  for (const auto& beta : valid)
    for (Eigen::Index i = 0; i < n; ++i) log_mean(i) += std::log(beta(i));
  log_mean /= static_cast<double>(valid.size());
  ClassVector fused = ClassVector::Zero(n);
  const double top = log_mean.maxCoeff();
  if (std::isfinite(top)) {
    for (Eigen::Index i = 0; i < n; ++i) fused(i) = std::exp(log_mean(i) - top);
    fused /= fused.sum();
  } else {
    for (const auto& beta : valid) fused += beta;
    fused /= static_cast<double>(valid.size());
  }
  return {fused.begin(), fused.end()};
}

std::optional<double> fuseStopProbabilities(std::span<const std::optional<double>> members) {
  std::vector<std::array<double, 2>> outcomes;
  for (const auto& p : members)
    if (p && *p >= 0.0 && *p <= 1.0) outcomes.push_back({*p, 1.0 - *p});
  if (outcomes.empty()) return std::nullopt;
  const std::vector<std::span<const double>> vectors(outcomes.begin(), outcomes.end());
  return fuseClassVectors(vectors).front();
}

ConfusionMatrix symmetricConfusionMatrix(double a, std::size_t class_count) {
  requireProbability(a, "symmetricConfusionMatrix");
  if (class_count < 2) throw std::invalid_argument("symmetricConfusionMatrix: fewer than 2 classes");
  const auto n = static_cast<Eigen::Index>(class_count);
  const double off = (1.0 - a) / static_cast<double>(class_count - 1);
  ConfusionMatrix cm = ConfusionMatrix::Constant(n, n, off);
  cm.diagonal().setConstant(a);
  return cm;
}

// Spec §4 PROP says only "vehicle/non-vehicle blocks, 0.9 correct". Built here as: the sensor
// declares one class; the ground vehicles (wheeled light, wheeled heavy, tracked: the ferrous
// masses a magnetometer senses) form one block, human, group and aerial the other. A target's row
// puts `correct` on its own block, spread evenly over that block's members, and 1 - correct on
// the other block, spread evenly over its members. Within a block the sensor cannot tell the
// classes apart, so the declared class inside the right block is uniform.
ConfusionMatrix magneticConfusionMatrix(double correct) {
  requireProbability(correct, "magneticConfusionMatrix");
  std::size_t vehicles = 0;
  for (std::size_t j = 0; j < kClassCount; ++j) vehicles += isVehicle(classAt(j)) ? 1 : 0;
  const std::size_t others = kClassCount - vehicles;
  const auto n = static_cast<Eigen::Index>(kClassCount);
  ConfusionMatrix cm(n, n);
  for (std::size_t i = 0; i < kClassCount; ++i) {
    const bool true_vehicle = isVehicle(classAt(i));
    for (std::size_t j = 0; j < kClassCount; ++j) {
      const bool declared_vehicle = isVehicle(classAt(j));
      const double block_mass = declared_vehicle == true_vehicle ? correct : 1.0 - correct;
      const std::size_t block_size = declared_vehicle ? vehicles : others;
      cm(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = block_mass / static_cast<double>(block_size);
    }
  }
  return cm;
}

ConfusionMatrix confusionMatrix(Classifier classifier) {
  switch (classifier) {
    case Classifier::kNone: return ConfusionMatrix(0, 0);
    case Classifier::kCamera: return symmetricConfusionMatrix(kCameraCorrectClass);
    case Classifier::kAcoustic: return symmetricConfusionMatrix(kAcousticCorrectClass);
    case Classifier::kMagnetic: return magneticConfusionMatrix();
  }
  throw std::invalid_argument("confusionMatrix: unknown classifier");
}

std::size_t declaredClass(const ConfusionMatrix& cm, std::size_t true_index, double u) {
  requireConfusionMatrix(cm, "declaredClass");
  if (true_index >= static_cast<std::size_t>(cm.rows())) {
    throw std::invalid_argument("declaredClass: true class index " + std::to_string(true_index) + " out of range");
  }
  if (!(u >= 0.0 && u < 1.0)) throw std::invalid_argument("declaredClass: u outside [0, 1)");
  const auto row = static_cast<Eigen::Index>(true_index);
  double cumulative = 0.0;
  Eigen::Index last_possible = 0;
  for (Eigen::Index j = 0; j < cm.cols(); ++j) {
    if (cm(row, j) > 0.0) last_possible = j;
    cumulative += cm(row, j);
    if (u < cumulative) return static_cast<std::size_t>(j);
  }
  // The row's rounded sum fell short of 1 and u landed in that sliver: it belongs to the last
  // class the row can declare, never to one of probability 0.
  return static_cast<std::size_t>(last_possible);
}

std::vector<double> reportedClassLikelihoods(const ConfusionMatrix& cm, TargetClass truth, double u) {
  const bool classifies = cm.size() != 0;
  if (classifies && (cm.rows() != static_cast<Eigen::Index>(kClassCount) || cm.cols() != cm.rows())) {
    throw std::invalid_argument("reportedClassLikelihoods: the confusion matrix is not " + std::to_string(kClassCount) +
                                " x " + std::to_string(kClassCount));
  }
  if (!(u >= 0.0 && u < 1.0)) throw std::invalid_argument("reportedClassLikelihoods: u outside [0, 1)");
  const std::optional<std::size_t> true_index = classIndex(truth);
  if (!classifies || !true_index) return {};
  const auto d = static_cast<Eigen::Index>(declaredClass(cm, *true_index, u));
  // The likelihood of the declaration under each class i is P(d | i): column d, not row.
  std::vector<double> c(kClassCount);
  for (std::size_t i = 0; i < kClassCount; ++i) c[i] = cm(static_cast<Eigen::Index>(i), d);
  return c;
}

}  // namespace wsn::common
