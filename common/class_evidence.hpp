// ONERA classification (Pannetier, Dezert, Sella, FUSION 2014, eqs. 1, 19-23): a track's class
// vector, its update and score from a report's class likelihoods, and the sensors' confusion matrices.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "common/measurement.hpp"
#include "common/scenario_config.hpp"

namespace wsn::common {

/// Eq. (1)'s classes made exclusive (docs/ONERA.md §4, §9): TargetClass without kUnknown, in the
/// enum's order, so that class index i is TargetClass(i + 1). kUnknown is what the truth says
/// when a target has no class, not a hypothesis a track can hold.
inline constexpr std::size_t kClassCount = 6;
static_assert(kClassCount <= kMaxClasses, "a report's class likelihoods must fit the wire's sequence");
static_assert(static_cast<std::size_t>(TargetClass::kAerial) == kClassCount,
              "TargetClass gained or lost a class: kClassCount and the magnetic blocks must follow");

/// The index of `c` in a class vector; nullopt for kUnknown.
std::optional<std::size_t> classIndex(TargetClass c);
/// The class at `index`; throws std::out_of_range for index >= kClassCount.
TargetClass classAt(std::size_t index);

/// beta: a probability over the exclusive classes (non-negative, summing to 1). Its size is the
/// number of classes; the functions take it from their arguments, so a toy set of 3 works too.
using ClassVector = Eigen::VectorXd;
/// Row = true class, column = declared class; every row sums to 1.
using ConfusionMatrix = Eigen::MatrixXd;

/// The uniform vector: the track's class before any classifying report, and beta_e (PROP).
ClassVector uniformClassVector(std::size_t class_count = kClassCount);

/// Eq. (20): beta0 = c / sum(c). An empty c (a sensor that does not classify) gives the uniform
/// vector. Throws std::invalid_argument for a c of another size than class_count, a negative or
/// non-finite entry, or an all-zero c.
ClassVector initialClassVector(std::span<const double> c, std::size_t class_count = kClassCount);

/// A track's class vector after a report, and the report's class term in the score.
struct ClassUpdate {
  ClassVector beta;
  double score_increment = 0.0;  ///< Delta L^c of eq. (23), natural log
};

/// Eq. (19) and (23): beta+ = c (x) beta / (c'beta), Delta L^c = ln(c'beta / c'beta_e), beta_e
/// uniform. An empty c or a constant c (c = 1) returns beta itself and exactly 0. When c'beta = 0
/// the report is impossible for this track: Delta L^c = -infinity and beta is returned unchanged.
/// Throws std::invalid_argument for a beta that is empty, has a negative or non-finite entry or does
/// not sum to 1 (within 1e-9), or a c of another size, with a negative or non-finite entry, or all
/// zero.
ClassUpdate updateClassVector(const ClassVector& beta, std::span<const double> c);

/// The index of the most probable class (argmax beta); the lowest index on a tie. Throws
/// std::invalid_argument for an empty beta or one with a non-finite entry.
std::size_t mostLikelyClass(const ClassVector& beta);

/// A class vector that arrived from elsewhere (the wire, a handoff) as a ClassVector: nullopt unless
/// it has class_count entries, each finite and non-negative, summing to 1 within 1e-6.
std::optional<ClassVector> receivedClassVector(std::span<const double> beta, std::size_t class_count = kClassCount);

/// What a track's class vector declares: its most likely class and that class's probability.
struct DeclaredClass {
  /// kUnknown for no evidence: beta empty, not a valid class vector, or uniform (no classifying
  /// report yet). Then probability is 0.
  TargetClass target_class = TargetClass::kUnknown;
  double probability = 0.0;
  friend bool operator==(const DeclaredClass&, const DeclaredClass&) = default;
};
DeclaredClass declaredTrackClass(std::span<const double> beta);

/// One target's class vectors from several trackers, fused into one. How much evidence they share
/// is unknown (a handed-over track carries its beta along; neighbouring supernodes may hear one
/// sensor), so the product of independent opinions would count shared reports twice. The fusion is
/// the normalised geometric mean, beta(i) ~ prod_k beta_k(i)^(1/n): the discrete form of covariance
/// intersection with equal weights (docs/ONERA.md §4), never more certain than the most certain
/// member. Invalid members (receivedClassVector) are left out; none left gives an empty vector. When
/// every class is excluded by some member, the members contradict each other and their arithmetic
/// mean is returned. The result depends on the order of `members` only through rounding.
std::vector<double> fuseClassVectors(std::span<const std::span<const double>> members);

/// Several trackers' probabilities that one target is stopped, fused by the same rule as the class
/// vectors above, on the two outcomes (stopped, moving). Members that are none or no probability
/// are left out; none left gives none.
std::optional<double> fuseStopProbabilities(std::span<const std::optional<double>> members);

/// PROP: the probability a camera declares the true class (spec §4).
inline constexpr double kCameraCorrectClass = 0.85;
/// PROP: the same for an acoustic antenna or beacon.
inline constexpr double kAcousticCorrectClass = 0.6;
/// PROP: the probability a magnetic sensor puts a target on the right side of vehicle/non-vehicle.
inline constexpr double kMagneticCorrectBlock = 0.9;

/// CM = a I + (1 - a)/(N - 1) (11' - I): the true class with probability a, any other one alike.
/// Throws std::invalid_argument for a outside [0, 1] or class_count < 2.
ConfusionMatrix symmetricConfusionMatrix(double a, std::size_t class_count = kClassCount);

/// The magnetic sensor's block matrix over the kClassCount classes (spec §4 PROP); see the .cpp
/// for which classes are vehicles. Throws std::invalid_argument for correct outside [0, 1].
ConfusionMatrix magneticConfusionMatrix(double correct = kMagneticCorrectBlock);

/// What a type of sensor can tell about a target's class.
enum class Classifier { kNone, kCamera, kAcoustic, kMagnetic };
/// Its PROP confusion matrix; 0 x 0 for kNone (radar, PIR), whose reports carry an empty c.
ConfusionMatrix confusionMatrix(Classifier classifier);

/// The sensor's declared class d ~ CM[true_index, .] by the inverse CDF at u: the first d whose
/// cumulative row sum exceeds u. Deterministic in u, so the caller's random stream decides.
/// Throws std::invalid_argument for a matrix that is not square, or a row with a negative or
/// non-finite entry or not summing to 1 (within 1e-9), true_index out of range, or u outside [0, 1).
std::size_t declaredClass(const ConfusionMatrix& cm, std::size_t true_index, double u);

/// The likelihood vector a report carries: c = CM[., d] with d = declaredClass(cm, true index, u),
/// i.e. P(declare d | class i) for every i. Empty when cm is 0 x 0 (the sensor does not classify)
/// or the truth is kUnknown (the model has no row for it). Throws as declaredClass, and for a cm
/// of another size than kClassCount.
std::vector<double> reportedClassLikelihoods(const ConfusionMatrix& cm, TargetClass truth, double u);

}  // namespace wsn::common
