// ONERA classification (eqs. 19-23) and the proposed confusion matrices, against hand-computed
// values and spec check C5.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/class_evidence.hpp"

using namespace wsn::common;

namespace {

ClassVector vec(std::vector<double> values) {
  return Eigen::Map<const ClassVector>(values.data(), static_cast<Eigen::Index>(values.size()));
}

std::vector<double> column(const ConfusionMatrix& cm, Eigen::Index d) {
  std::vector<double> c(static_cast<std::size_t>(cm.rows()));
  for (Eigen::Index i = 0; i < cm.rows(); ++i) c[static_cast<std::size_t>(i)] = cm(i, d);
  return c;
}

const std::vector<double> kNoClass;

}  // namespace

TEST_CASE("class indices cover every class but unknown", "[class]") {
  CHECK_FALSE(classIndex(TargetClass::kUnknown).has_value());
  CHECK(classIndex(TargetClass::kWheeledLight) == 0u);
  CHECK(classIndex(TargetClass::kAerial) == kClassCount - 1);
  for (std::size_t i = 0; i < kClassCount; ++i) CHECK(classIndex(classAt(i)) == i);
  CHECK_THROWS_AS(classAt(kClassCount), std::out_of_range);
}

TEST_CASE("check C5: a report of class likelihoods sharpens beta and scores ln 1.35", "[class]") {
  // By hand: c'beta = .8 x .5 + .1 x .3 + .1 x .2 = .4 + .03 + .02 = .45, so
  // beta+ = (.4, .03, .02) / .45 = (8/9, 1/15, 2/45) = (.8889, .0667, .0444).
  // beta_e = (1/3, 1/3, 1/3): c'beta_e = (.8 + .1 + .1) / 3 = 1/3, so
  // Delta L^c = ln(.45 / (1/3)) = ln 1.35 = .30010. The spec's numbers agree.
  const std::vector<double> c{0.8, 0.1, 0.1};
  const ClassUpdate up = updateClassVector(vec({0.5, 0.3, 0.2}), c);
  REQUIRE(up.beta.size() == 3);
  CHECK(up.beta(0) == Approx(8.0 / 9.0).epsilon(1e-12));
  CHECK(up.beta(1) == Approx(1.0 / 15.0).epsilon(1e-12));
  CHECK(up.beta(2) == Approx(2.0 / 45.0).epsilon(1e-12));
  CHECK(up.beta(0) == Approx(0.8889).margin(5e-5));
  CHECK(up.beta(1) == Approx(0.0667).margin(5e-5));
  CHECK(up.beta(2) == Approx(0.0444).margin(5e-5));
  CHECK(up.beta.sum() == Approx(1.0).epsilon(1e-15));
  CHECK(up.score_increment == Approx(std::log(1.35)).epsilon(1e-12));
  CHECK(up.score_increment == Approx(0.3001).margin(5e-5));
  CHECK(mostLikelyClass(up.beta) == 0u);
}

TEST_CASE("a sensor that does not classify leaves beta and the score alone", "[class]") {
  const ClassVector beta = vec({0.5, 0.3, 0.2});
  const ClassUpdate none = updateClassVector(beta, kNoClass);
  CHECK(none.beta == beta);
  CHECK(none.score_increment == 0.0);
  const std::vector<double> ones{1.0, 1.0, 1.0};
  const ClassUpdate flat = updateClassVector(beta, ones);
  CHECK(flat.beta == beta);
  CHECK(flat.score_increment == 0.0);
  // Eq. (19) and (23) do not depend on the scale of c: any constant c is c = 1.
  const std::vector<double> thirds{0.3, 0.3, 0.3};
  CHECK(updateClassVector(beta, thirds).beta == beta);
  CHECK(updateClassVector(beta, thirds).score_increment == 0.0);
}

TEST_CASE("eq. 20 normalises the first report's class likelihoods", "[class]") {
  const std::vector<double> c{0.8, 0.1, 0.1};
  const ClassVector b0 = initialClassVector(c, 3);
  CHECK(b0(0) == Approx(0.8));
  CHECK(b0(1) == Approx(0.1));
  CHECK(b0(2) == Approx(0.1));
  const std::vector<double> unnormalised{2.0, 1.0, 1.0};
  const ClassVector half = initialClassVector(unnormalised, 3);
  CHECK(half(0) == Approx(0.5));
  CHECK(half(1) == Approx(0.25));
  CHECK(half(2) == Approx(0.25));
  // No class information: the uniform vector, over the default six classes.
  const ClassVector uniform = initialClassVector(kNoClass);
  REQUIRE(uniform.size() == static_cast<Eigen::Index>(kClassCount));
  for (Eigen::Index i = 0; i < uniform.size(); ++i) CHECK(uniform(i) == Approx(1.0 / 6.0));
  const std::vector<double> ones(kClassCount, 1.0);
  CHECK(initialClassVector(ones) == uniform);
  CHECK(uniformClassVector() == uniform);
}

TEST_CASE("a report impossible for the track scores minus infinity and leaves beta", "[class]") {
  // c'beta = 0: beta+ would be 0/0; the branch pairing this report with this track must lose.
  const ClassVector beta = vec({1.0, 0.0, 0.0});
  const std::vector<double> c{0.0, 0.5, 0.5};
  const ClassUpdate up = updateClassVector(beta, c);
  CHECK(up.beta == beta);
  CHECK(std::isinf(up.score_increment));
  CHECK(up.score_increment < 0.0);
}

TEST_CASE("the confusion matrices have unit rows and the proposed diagonals", "[class]") {
  const ConfusionMatrix camera = confusionMatrix(Classifier::kCamera);
  const ConfusionMatrix acoustic = confusionMatrix(Classifier::kAcoustic);
  const ConfusionMatrix magnetic = confusionMatrix(Classifier::kMagnetic);
  CHECK(confusionMatrix(Classifier::kNone).size() == 0);
  const auto n = static_cast<Eigen::Index>(kClassCount);
  for (const ConfusionMatrix* cm : {&camera, &acoustic, &magnetic}) {
    REQUIRE(cm->rows() == n);
    REQUIRE(cm->cols() == n);
    for (Eigen::Index i = 0; i < n; ++i) CHECK(cm->row(i).sum() == Approx(1.0).epsilon(1e-15));
  }
  // Off the diagonal: (1 - a)/(N - 1) = .15/5 = .03 (camera), .4/5 = .08 (acoustic).
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      CHECK(camera(i, j) == Approx(i == j ? 0.85 : 0.03));
      CHECK(acoustic(i, j) == Approx(i == j ? 0.6 : 0.08));
    }
  }
  // Magnetic: vehicles {wheeled light, wheeled heavy, tracked}, others {human, group, aerial}; .9 on
  // the right block over 3 members gives .3 each (the diagonal), .1 on the other block .1/3 each.
  const auto isVehicle = [](Eigen::Index i) { return i < 3; };
  for (Eigen::Index i = 0; i < n; ++i) {
    CHECK(magnetic(i, i) == Approx(0.3));
    double right_block = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) {
      const bool same = isVehicle(i) == isVehicle(j);
      CHECK(magnetic(i, j) == Approx(same ? 0.3 : 0.1 / 3.0));
      if (same) right_block += magnetic(i, j);
    }
    CHECK(right_block == Approx(0.9));
  }
  CHECK(symmetricConfusionMatrix(0.85, 3)(0, 1) == Approx(0.075));
}

TEST_CASE("the declared class over a fine grid of u follows the confusion row", "[class]") {
  // Grid points (k + 1/2)/K: the count in an interval of length p differs from K p by at most 1.
  constexpr int kGrid = 100000;
  for (const Classifier kind : {Classifier::kCamera, Classifier::kAcoustic, Classifier::kMagnetic}) {
    const ConfusionMatrix cm = confusionMatrix(kind);
    for (std::size_t t = 0; t < kClassCount; ++t) {
      std::vector<int> counts(kClassCount, 0);
      for (int k = 0; k < kGrid; ++k) {
        ++counts[declaredClass(cm, t, (k + 0.5) / kGrid)];
      }
      for (std::size_t d = 0; d < kClassCount; ++d) {
        const double expected = cm(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(d));
        CHECK(static_cast<double>(counts[d]) / kGrid == Approx(expected).margin(1.0 / kGrid + 1e-12));
      }
    }
  }
  // The inverse CDF's ends: u = 0 declares the first class of positive probability.
  const ConfusionMatrix camera = confusionMatrix(Classifier::kCamera);
  CHECK(declaredClass(camera, 3, 0.0) == 0u);
  CHECK(declaredClass(camera, 3, std::nextafter(1.0, 0.0)) == kClassCount - 1);
}

TEST_CASE("a sensor reports the confusion column of the class it declares", "[class]") {
  const ConfusionMatrix camera = confusionMatrix(Classifier::kCamera);
  // Row wheeled_heavy accumulates .03, .88, ...: u = .5 declares wheeled_heavy itself.
  const std::vector<double> c = reportedClassLikelihoods(camera, TargetClass::kWheeledHeavy, 0.5);
  CHECK(c == column(camera, 1));
  CHECK(c[1] == Approx(0.85));
  // u = .01 < .03 declares wheeled_light: the report then favours the wrong class.
  CHECK(reportedClassLikelihoods(camera, TargetClass::kWheeledHeavy, 0.01) == column(camera, 0));
  // A target without a class, and a sensor without a classifier, give an empty c.
  CHECK(reportedClassLikelihoods(camera, TargetClass::kUnknown, 0.5).empty());
  CHECK(reportedClassLikelihoods(confusionMatrix(Classifier::kNone), TargetClass::kHuman, 0.5).empty());
  // Column, not row: in a matrix that is not symmetric the two differ. Here wheeled_light is
  // declared wheeled_heavy half the time, so declaring wheeled_heavy is likelier from it.
  ConfusionMatrix skewed = camera;
  skewed.row(0) << 0.5, 0.5, 0.0, 0.0, 0.0, 0.0;
  const std::vector<double> s = reportedClassLikelihoods(skewed, TargetClass::kWheeledLight, 0.7);
  CHECK(s == column(skewed, 1));
  CHECK(s[0] == 0.5);  // the row would give .03 here
  CHECK(s[1] == Approx(0.85));
  // The magnetic sensor's report only separates vehicles from the rest, 9 to 1.
  const std::vector<double> m = reportedClassLikelihoods(confusionMatrix(Classifier::kMagnetic), TargetClass::kHuman, 0.5);
  REQUIRE(m.size() == kClassCount);
  CHECK(m[0] / m[3] == Approx(1.0 / 9.0));
  CHECK(m[4] == Approx(m[3]));
}

TEST_CASE("repeated reports of the true class drive beta to it", "[class]") {
  // A camera that always declares the truth: beta(t) after k reports is
  // .85^k / (.85^k + 5 x .03^k), and the first report, against a uniform beta = beta_e, scores 0.
  const std::size_t truth = *classIndex(TargetClass::kTracked);
  const ConfusionMatrix camera = confusionMatrix(Classifier::kCamera);
  const std::vector<double> c = column(camera, static_cast<Eigen::Index>(truth));
  ClassVector beta = uniformClassVector();
  double previous = beta(static_cast<Eigen::Index>(truth));
  for (int k = 1; k <= 6; ++k) {
    const ClassUpdate up = updateClassVector(beta, c);
    if (k == 1) CHECK(up.score_increment == Approx(0.0).margin(1e-15));
    else CHECK(up.score_increment > 0.0);
    beta = up.beta;
    const double p = beta(static_cast<Eigen::Index>(truth));
    CHECK(p > previous);
    CHECK(p == Approx(std::pow(0.85, k) / (std::pow(0.85, k) + 5.0 * std::pow(0.03, k))));
    previous = p;
  }
  CHECK(previous > 0.9999);
  CHECK(mostLikelyClass(beta) == truth);

  // An acoustic sensor that errs 40% of the time, its declarations drawn at the golden-ratio
  // sequence (equidistributed in [0, 1)): the truth still wins.
  ClassVector heard = uniformClassVector();
  const ConfusionMatrix acoustic = confusionMatrix(Classifier::kAcoustic);
  double u = 0.0;
  for (int k = 0; k < 100; ++k) {
    u = std::fmod(u + 0.6180339887498949, 1.0);
    heard = updateClassVector(heard, reportedClassLikelihoods(acoustic, TargetClass::kTracked, u)).beta;
  }
  CHECK(mostLikelyClass(heard) == truth);
  CHECK(heard(static_cast<Eigen::Index>(truth)) > 0.99);
}

TEST_CASE("malformed class likelihoods or class vectors or draws are rejected", "[class]") {
  const ClassVector beta = vec({0.5, 0.3, 0.2});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const std::vector<double>& bad : std::vector<std::vector<double>>{
           {0.8, -0.1, 0.1}, {0.8, nan, 0.1}, {0.8, inf, 0.1}, {0.0, 0.0, 0.0}, {0.5, 0.5}, {0.2, 0.2, 0.2, 0.2}}) {
    CHECK_THROWS_AS(updateClassVector(beta, bad), std::invalid_argument);
    CHECK_THROWS_AS(initialClassVector(bad, 3), std::invalid_argument);
  }
  const std::vector<double> c{0.8, 0.1, 0.1};
  CHECK_THROWS_AS(updateClassVector(vec({0.5, 0.3, 0.3}), c), std::invalid_argument);  // sums to 1.1
  CHECK_THROWS_AS(updateClassVector(vec({1.2, -0.1, -0.1}), c), std::invalid_argument);
  CHECK_THROWS_AS(updateClassVector(vec({nan, 0.5, 0.5}), c), std::invalid_argument);
  CHECK_THROWS_AS(updateClassVector(ClassVector(), kNoClass), std::invalid_argument);
  CHECK_THROWS_AS(mostLikelyClass(ClassVector()), std::invalid_argument);
  CHECK_THROWS_AS(uniformClassVector(0), std::invalid_argument);

  CHECK_THROWS_AS(symmetricConfusionMatrix(1.1), std::invalid_argument);
  CHECK_THROWS_AS(symmetricConfusionMatrix(-0.1), std::invalid_argument);
  CHECK_THROWS_AS(symmetricConfusionMatrix(nan), std::invalid_argument);
  CHECK_THROWS_AS(symmetricConfusionMatrix(0.9, 1), std::invalid_argument);
  CHECK_THROWS_AS(magneticConfusionMatrix(2.0), std::invalid_argument);

  const ConfusionMatrix camera = confusionMatrix(Classifier::kCamera);
  CHECK_THROWS_AS(declaredClass(camera, 0, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(declaredClass(camera, 0, -0.1), std::invalid_argument);
  CHECK_THROWS_AS(declaredClass(camera, 0, nan), std::invalid_argument);
  CHECK_THROWS_AS(declaredClass(camera, kClassCount, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(declaredClass(ConfusionMatrix::Constant(2, 3, 0.5), 0, 0.5), std::invalid_argument);
  ConfusionMatrix leaky = camera;
  leaky(2, 2) = 0.5;  // row 2 sums to .65
  CHECK_THROWS_AS(declaredClass(leaky, 2, 0.5), std::invalid_argument);
  ConfusionMatrix negative = camera;
  negative(1, 0) = -0.03;
  negative(1, 1) = 0.91;
  CHECK_THROWS_AS(declaredClass(negative, 1, 0.5), std::invalid_argument);
  CHECK_THROWS_AS(reportedClassLikelihoods(symmetricConfusionMatrix(0.85, 3), TargetClass::kHuman, 0.5),
                  std::invalid_argument);
  CHECK_THROWS_AS(reportedClassLikelihoods(camera, TargetClass::kHuman, 1.0), std::invalid_argument);
}

TEST_CASE("a class vector from the wire is used only when it is one", "[class]") {
  const std::vector<double> good{0.5, 0.25, 0.25};
  REQUIRE(receivedClassVector(good, 3).has_value());
  CHECK(receivedClassVector(good, 3)->isApprox(vec(good)));
  CHECK_FALSE(receivedClassVector(good).has_value());  // 3 entries, 6 classes
  CHECK_FALSE(receivedClassVector(std::vector<double>{0.5, 0.25, 0.2}, 3).has_value());  // sums to 0.95
  CHECK_FALSE(receivedClassVector(std::vector<double>{1.5, -0.25, -0.25}, 3).has_value());
  CHECK_FALSE(receivedClassVector(std::vector<double>{std::nan(""), 0.5, 0.5}, 3).has_value());
  CHECK_FALSE(receivedClassVector(std::vector<double>{}, 0).has_value());
}

TEST_CASE("a track declares its most likely class, and none without evidence", "[class]") {
  CHECK(declaredTrackClass(std::vector<double>{0.05, 0.05, 0.1, 0.6, 0.15, 0.05}) ==
        DeclaredClass{TargetClass::kHuman, 0.6});
  CHECK(declaredTrackClass(std::vector<double>(6, 1.0 / 6.0)) == DeclaredClass{});  // uniform: no report yet
  CHECK(declaredTrackClass(std::vector<double>{}) == DeclaredClass{});              // an engine that does not classify
  CHECK(declaredTrackClass(std::vector<double>{0.5, 0.5}) == DeclaredClass{});      // not the run's class set
  // A tie names the first class, as mostLikelyClass does.
  CHECK(declaredTrackClass(std::vector<double>{0.4, 0.4, 0.05, 0.05, 0.05, 0.05}).target_class ==
        TargetClass::kWheeledLight);
}

TEST_CASE("fused class vectors are their normalised geometric mean", "[class]") {
  using Span = std::span<const double>;
  const std::vector<double> sure{0.8, 0.2};
  const std::vector<double> undecided{0.5, 0.5};
  // sqrt(.8 x .5) : sqrt(.2 x .5) = sqrt(4) = 2 : 1, so (2/3, 1/3).
  std::vector<Span> members{sure, undecided};
  auto fused = fuseClassVectors(members);
  REQUIRE(fused.size() == 2);
  CHECK(fused[0] == Approx(2.0 / 3.0).epsilon(1e-12));
  CHECK(fused[1] == Approx(1.0 / 3.0).epsilon(1e-12));
  // Two copies of one opinion (a handed-over track reported by both supernodes) fuse to that
  // opinion, where the product of independent ones would give .64 / .04 = .941 / .059.
  members = {sure, sure};
  fused = fuseClassVectors(members);
  CHECK(fused[0] == Approx(0.8).epsilon(1e-12));
  // A member that excludes a class excludes it from the fusion...
  const std::vector<double> not_first{0.0, 1.0};
  members = {undecided, not_first};
  fused = fuseClassVectors(members);
  REQUIRE(fused.size() == 2);
  CHECK(fused[0] == 0.0);
  CHECK(fused[1] == Approx(1.0).epsilon(1e-12));
  // ... and members excluding every class between them contradict: their arithmetic mean.
  const std::vector<double> first_only{1.0, 0.0};
  members = {first_only, not_first};
  CHECK(fuseClassVectors(members) == std::vector<double>{0.5, 0.5});
  // Empty (an engine that does not classify) and malformed members are left out.
  const std::vector<double> none;
  const std::vector<double> malformed{0.9, 0.9};
  members = {none, sure, malformed};
  CHECK(fuseClassVectors(members) == sure);
  members = {none, malformed};
  CHECK(fuseClassVectors(members).empty());
  CHECK(fuseClassVectors({}).empty());
}

TEST_CASE("fused stop probabilities follow the class vectors rule on stopped or moving", "[class]") {
  using Maybe = std::optional<double>;
  // .9 and .6: sqrt(.9 x .6) = .734847 against sqrt(.1 x .4) = .2, so .734847 / .934847 = .786062.
  std::vector<Maybe> members{0.9, 0.6};
  REQUIRE(fuseStopProbabilities(members));
  CHECK(*fuseStopProbabilities(members) == Approx(0.786062).epsilon(1e-6));
  // Opposite opinions cancel: sqrt(.8 x .2) on both sides.
  members = {0.8, 0.2};
  CHECK(*fuseStopProbabilities(members) == Approx(0.5).epsilon(1e-12));
  // Copies of one opinion fuse to it.
  members = {0.8, 0.8, 0.8};
  CHECK(*fuseStopProbabilities(members) == Approx(0.8).epsilon(1e-12));
  // A track of an engine without a stop model, and a value that is no probability, are left out.
  members = {std::nullopt, 0.3, 1.5};
  CHECK(*fuseStopProbabilities(members) == Approx(0.3).epsilon(1e-12));
  members = {std::nullopt, -0.1};
  CHECK_FALSE(fuseStopProbabilities(members));
  CHECK_FALSE(fuseStopProbabilities({}));
}
