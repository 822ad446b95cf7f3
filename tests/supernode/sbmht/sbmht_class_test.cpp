// The sbmht engine's class evidence (ONERA eqs. 19-23, docs/ONERA.md §4): each leaf keeps a class
// vector beta, started by eq. 20 and updated by eq. 19 at every report that carries class
// likelihoods c, and eq. 23's Delta L^c joins the kinematic score increment (eqs. 21-22).
#include "supernode/sbmht/sbmht_engine.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/class_evidence.hpp"
#include "common/rng.hpp"
#include "common/track_id.hpp"
#include "supernode/observation_window.hpp"
#include "tests/supernode/sbmht/sbmht_test_support.hpp"
#include "tests/supernode/test_support.hpp"

namespace wsn::supernode::sbmht {
namespace {

using namespace support;

/// A position report of (x, y) at tick t from `sensor` with the engine's own noise (sigma 0.5) and
/// clutter density (1e-4), carrying class likelihoods c (none when empty): a presence sensor's
/// report, as a beacon or magnetic detector makes.
common::Observation classified(std::int32_t t, common::SensorId sensor, double x, double y, std::vector<double> c,
                               common::TargetId target = 0) {
  common::Measurement m;
  m.kind = common::MeasurementKind::position;
  m.values = {x, y};
  m.noise = {0.25, 0.0, 0.0, 0.25};
  m.clutter_density = 1e-4;
  m.class_likelihoods = std::move(c);
  common::Observation o{t, t, sensor, x, y, target};
  o.measurement = common::MeasurementRef(std::move(m));
  return o;
}

/// The leaf of tree `tree` that took exactly `reports` at `tick`, or nullptr.
const SbmhtEngine::Leaf* leafTaking(const SbmhtEngine& engine, common::TrackId tree, std::int32_t tick,
                                    const std::vector<std::int32_t>& reports) {
  for (const auto& leaf : engine.leaves()) {
    if (leaf.tree != tree) continue;
    const auto took = leaf.reportsAt(tick);
    if (std::vector<std::int32_t>(took.begin(), took.end()) == reports) return &leaf;
  }
  return nullptr;
}

/// c = CM[., d] of a camera (a = .85) declaring `declared`: P(declare d | class i) for each i.
std::vector<double> cameraDeclaring(common::TargetClass declared) {
  const common::ConfusionMatrix cm = common::confusionMatrix(common::Classifier::kCamera);
  const auto d = static_cast<Eigen::Index>(*common::classIndex(declared));
  std::vector<double> c(common::kClassCount);
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = cm(static_cast<Eigen::Index>(i), d);
  return c;
}

/// A camera's report of a target of class `truth` at tick t: d ~ CM[truth, .] from a stream keyed
/// by (target, tick), as the field sensors draw it.
std::vector<double> cameraOf(common::TargetClass truth, common::TargetId target, std::int32_t t) {
  common::Stream draw(11, common::Purpose::kFieldSensorClass, static_cast<std::uint64_t>(target), t);
  return common::reportedClassLikelihoods(common::confusionMatrix(common::Classifier::kCamera), truth,
                                          draw.uniform());
}

TEST_CASE("sbmht classes: a report with class likelihoods adds ln 1.35 to the score as C5", "[sbmht][classes]") {
  // C5 (docs/ONERA.md §4) over 3 classes: beta = (.5, .3, .2), c = (.8, .1, .1), beta_e uniform:
  // c'beta = .4 + .03 + .02 = .45, c'beta_e = 1/3, Delta L^c = ln(.45 / (1/3)) = ln 1.35 = .3001,
  // beta+ = (.4, .03, .02) / .45 = (.8889, .0667, .0444).
  // Over the engine's 6 classes: the tree is born from c0 = (.5, .3, .2, 0, 0, 0), so eq. 20 gives
  // beta = c0 / 1 = (.5, .3, .2, 0, 0, 0). The next report carries c = (.8, .1, .1, .8, .1, .1):
  // c'beta = .45 as in C5 (beta is 0 on the last three), and c'beta_e = sum(c) / 6 = 2 / 6 = 1/3,
  // so again Delta L^c = ln 1.35 and beta+ = (.8889, .0667, .0444, 0, 0, 0). The same report
  // without c takes the same kinematic increment, so the two hit leaves' scores differ by ln 1.35.
  const common::SensorId sensor = 7;
  const common::TrackId tree = common::track_id::birth(0, 1, sensor);
  const std::vector<double> c0{0.5, 0.3, 0.2, 0.0, 0.0, 0.0};
  double score_with = 0.0;
  double score_without = 0.0;
  for (const bool with_c : {true, false}) {
    INFO("with c: " << with_c);
    Harness h(sbmhtScenario());
    h.step(1, {classified(1, sensor, 20.0, 50.0, c0)});
    const auto* born = leafTaking(h.engine, tree, 1, {0});
    REQUIRE(born != nullptr);
    REQUIRE(born->classes.size() == 6);
    for (int i = 0; i < 6; ++i) CHECK(born->classes(i) == Approx(c0[static_cast<std::size_t>(i)]).margin(1e-15));
    const ClassVector born_classes = born->classes;  // the next step replaces the engine's leaves
    const std::vector<double> c = with_c ? std::vector<double>{0.8, 0.1, 0.1, 0.8, 0.1, 0.1} : std::vector<double>{};
    h.step(2, {classified(2, sensor, 20.5, 50.0, c)});
    const auto* hit = leafTaking(h.engine, tree, 2, {0});
    REQUIRE(hit != nullptr);
    (with_c ? score_with : score_without) = hit->score.score;
    if (with_c) {
      CHECK(hit->classes(0) == Approx(0.4 / 0.45).margin(1e-12));   // .8889
      CHECK(hit->classes(1) == Approx(0.03 / 0.45).margin(1e-12));  // .0667
      CHECK(hit->classes(2) == Approx(0.02 / 0.45).margin(1e-12));  // .0444
      for (int i = 3; i < 6; ++i) CHECK(hit->classes(i) == 0.0);
    } else {
      // A report without c changes nothing: beta stays eq. 20's.
      for (int i = 0; i < 6; ++i) CHECK(hit->classes(i) == born_classes(i));
    }
  }
  CHECK(score_with - score_without == Approx(std::log(1.35)).margin(1e-9));
  CHECK(std::log(1.35) == Approx(0.3001).margin(1e-4));
}

TEST_CASE("sbmht classes: a birth without class likelihoods starts uniform", "[sbmht][classes]") {
  Harness h(sbmhtScenario());
  h.step(1, {classified(1, 3, 20.0, 50.0, {})});
  REQUIRE(h.engine.leaves().size() == 1);
  const auto& beta = h.engine.leaves().front().classes;
  REQUIRE(beta.size() == 6);
  for (int i = 0; i < 6; ++i) CHECK(beta(i) == Approx(1.0 / 6.0));
}

TEST_CASE("sbmht classes: a report whose class the track cannot be makes no branch of it", "[sbmht][classes]") {
  // Three reports certain of wheeled_light (c = e1, so beta = e1 from eq. 20 on) confirm a track
  // (confirm_reports 3). At tick 4 a report at its predicted position with c = (0, 1, 1, 1, 1, 1)
  // has c'beta = 0: Delta L^c = -inf, so the tree has no leaf taking it, only its miss branch (the
  // report starts a tree of its own). With c = (.2, 1, 1, 1, 1, 1) the track can explain it
  // (c'beta = .2, c'beta_e = 5.2 / 6, Delta L^c = ln(.2 / .8667) = -1.466) and takes it.
  const common::SensorId sensor = 5;
  const common::TrackId tree = common::track_id::birth(0, 1, sensor);
  const std::vector<double> wheeled_light{1.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  for (const double first : {0.0, 0.2}) {
    INFO("c(0) = " << first);
    Harness h(sbmhtScenario());
    for (std::int32_t t = 1; t <= 3; ++t) h.step(t, {classified(t, sensor, 20.0 + t, 50.0, wheeled_light)});
    REQUIRE(h.engine.confirmedTracks().size() == 1);
    h.step(4, {classified(4, sensor, 24.0, 50.0, {first, 1.0, 1.0, 1.0, 1.0, 1.0})});
    const auto* taken = leafTaking(h.engine, tree, 4, {0});
    if (first == 0.0) {
      CHECK(taken == nullptr);
      CHECK(leafTaking(h.engine, tree, 4, {}) != nullptr);  // its miss branch lives on
      CHECK(leafTaking(h.engine, common::track_id::birth(0, 4, sensor), 4, {0}) != nullptr);
    } else {
      REQUIRE(taken != nullptr);
      CHECK(taken->classes(0) == 1.0);  // c (x) e1 / c'e1 = e1
    }
  }
}

TEST_CASE("sbmht classes: class evidence picks the right one of two reports in the gate", "[sbmht][classes]") {
  // A human walks along y = 50 at 1 per tick, reported by a classifying presence sensor declaring
  // human every tick (camera matrix, c = CM[., human]). At tick 8 two reports lie symmetric about its
  // predicted position, 0.5 above and below: kinematics cannot choose. One declares wheeled_light,
  // the other human; the track's beta is nearly all human (each report multiplies its odds by
  // .85 / .03 = 28.3), so the human report scores Delta L^c = ln(c_h'beta / c_h'beta_e) ~
  // ln(.85 / (1/6)) = 1.63 and the other ln(.03 / (1/6)) = -1.71: 3.3 apart.
  const common::TrackId tree = common::track_id::birth(0, 1, 1);
  auto run = [&](bool human_first) {
    Harness h(sbmhtScenario());
    for (std::int32_t t = 1; t <= 7; ++t)
      h.step(t, {classified(t, 1, 20.0 + t, 50.0, cameraDeclaring(common::TargetClass::kHuman))});
    const std::int32_t t = 8;
    const auto first = human_first ? common::TargetClass::kHuman : common::TargetClass::kWheeledLight;
    const auto second = human_first ? common::TargetClass::kWheeledLight : common::TargetClass::kHuman;
    // Sensors 2 and 3: canonical order puts sensor 2's report first (index 0).
    h.step(t, {classified(t, 2, 28.0, 50.5, cameraDeclaring(first)), classified(t, 3, 28.0, 49.5, cameraDeclaring(second))});
    const auto* best = bestLeaf(h.engine, tree);
    REQUIRE(best != nullptr);
    const auto took = best->reportsAt(t);
    return took.size() == 1 ? took[0] : -1;
  };
  // With classes the track takes the human report, whichever comes first.
  CHECK(run(true) == 0);
  CHECK(run(false) == 1);
}

TEST_CASE("sbmht classes: two targets of different classes keep their identities where they meet",
          "[sbmht][classes]") {
  // A (human) comes from the lower left, B (wheeled_heavy) from the upper left; they meet at
  // (30, 50) at tick 10 and move together along y = 50 for 10 ticks (their reports coincide), so the
  // tracks forget their approach. Then they part, either crossing (A leaves upwards, as it came) or
  // bouncing (A leaves downwards). Two sensors report them, sensor 1 the upper target (A while they
  // coincide) and sensor 2 the lower, so neither a report's sensor nor its order says which target
  // it is. Each report carries a camera's declaration drawn from CM[true class, .] (15 % wrong).
  // Kinematics alone cannot get both partings right; with classes each track follows its target.
  auto a = [](std::int32_t t, bool bounce) -> common::Vec2 {
    if (t <= 10) return {20.0 + t, 40.0 + t};
    if (t <= 20) return {20.0 + t, 50.0};
    return {20.0 + t, 50.0 + (bounce ? -1.0 : 1.0) * (t - 20)};
  };
  auto b = [](std::int32_t t, bool bounce) -> common::Vec2 {
    if (t <= 10) return {20.0 + t, 60.0 - t};
    if (t <= 20) return {20.0 + t, 50.0};
    return {20.0 + t, 50.0 + (bounce ? 1.0 : -1.0) * (t - 20)};
  };
  // At tick 1 sensor 1 reports B (upper) and sensor 2 reports A.
  const common::TrackId id_a = common::track_id::birth(0, 1, 2);
  const common::TrackId id_b = common::track_id::birth(0, 1, 1);
  auto near = [](const std::vector<common::TrackEstimate>& tracks, common::TrackId id, common::Vec2 p) {
    for (const auto& e : tracks)
      if (e.track == id) return std::hypot(e.x - p.x, e.y - p.y) < 1.0;
    return false;
  };
  // Whether both ids are on their own targets over ticks 26..32 (N = 3 scans after the parting
  // shows, and on).
  auto kept = [&](bool with_classes, bool bounce) {
    Harness h(sbmhtScenario());
    bool all = true;
    for (std::int32_t t = 1; t <= 32; ++t) {
      const auto pa = a(t, bounce);
      const auto pb = b(t, bounce);
      const auto ca = with_classes ? cameraOf(common::TargetClass::kHuman, 0, t) : std::vector<double>{};
      const auto cb = with_classes ? cameraOf(common::TargetClass::kWheeledHeavy, 1, t) : std::vector<double>{};
      const bool a_upper = pa.y >= pb.y && !(t <= 10);
      h.step(t, {classified(t, a_upper ? 1 : 2, pa.x, pa.y, ca, 0), classified(t, a_upper ? 2 : 1, pb.x, pb.y, cb, 1)});
      const auto tracks = h.engine.confirmedTracks();
      if (t >= 26) all = all && near(tracks, id_a, pa) && near(tracks, id_b, pb);
      if (with_classes && t == 32) {
        // confirmedClasses() lists the tracks of confirmedTracks(), in its order.
        const auto classes = h.engine.confirmedClasses();
        REQUIRE(classes.size() == tracks.size());
        for (std::size_t k = 0; k < tracks.size(); ++k) {
          CHECK(classes[k].track == tracks[k].track);
          if (tracks[k].track == id_a) CHECK(classes[k].target_class == common::TargetClass::kHuman);
          if (tracks[k].track == id_b) CHECK(classes[k].target_class == common::TargetClass::kWheeledHeavy);
        }
      }
    }
    return all;
  };
  CHECK(kept(true, false));
  CHECK(kept(true, true));
  const bool crossing = kept(false, false);
  const bool bouncing = kept(false, true);
  INFO("without classes: crossing kept " << crossing << ", bouncing kept " << bouncing);
  CHECK_FALSE((crossing && bouncing));
}

TEST_CASE("sbmht classes: a confirmed track's class converges to its target's", "[sbmht][classes]") {
  // A group (class index 4) reported 30 ticks by a camera, d ~ CM[group, .]: every declaration of
  // the true class multiplies its odds against any other class by .85 / .03 = 28.3, one of that
  // other class divides them by 28.3. With about 25 of 30 correct the log-odds are ~ 3.34 x 24, so
  // the class is group with probability above .999. Before any classifying report it is unknown.
  Harness h(sbmhtScenario());
  for (std::int32_t t = 1; t <= 5; ++t) h.step(t, {classified(t, 1, 20.0 + t, 50.0, {})});
  auto classes = h.engine.confirmedClasses();
  REQUIRE(classes.size() == 1);
  CHECK(classes[0].target_class == common::TargetClass::kUnknown);
  CHECK(classes[0].probability == 0.0);
  // The track itself carries its (uniform) class vector, which goes out with it.
  const auto first = h.engine.confirmedTracks();
  REQUIRE(first.size() == 1);
  REQUIRE(first[0].class_probabilities.size() == common::kClassCount);
  for (const double p : first[0].class_probabilities) CHECK(p == Approx(1.0 / 6.0));
  int correct = 0;
  for (std::int32_t t = 6; t <= 35; ++t) {
    const auto c = cameraOf(common::TargetClass::kGroup, 0, t);
    correct += c[4] == 0.85 ? 1 : 0;
    h.step(t, {classified(t, 1, 20.0 + t, 50.0, c)});
  }
  CHECK(correct >= 20);  // the draw is as described
  classes = h.engine.confirmedClasses();
  const auto tracks = h.engine.confirmedTracks();
  REQUIRE(classes.size() == 1);
  REQUIRE(tracks.size() == 1);
  CHECK(classes[0].track == tracks[0].track);
  CHECK(classes[0].target_class == common::TargetClass::kGroup);
  CHECK(classes[0].probability > 0.999);
  CHECK(tracks[0].class_probabilities[4] == classes[0].probability);
}

TEST_CASE("sbmht hands a track over with its class vector", "[sbmht][classes]") {
  // The giver's track learns it is a group from 15 camera reports; the taker continues it with
  // reports that carry no class, so the adopted track's class is exactly what was handed over.
  Harness giver(sbmhtScenario());
  for (std::int32_t t = 1; t <= 15; ++t)
    giver.step(t, {classified(t, 1, 20.0 + t, 50.0, cameraOf(common::TargetClass::kGroup, 0, t))});
  const auto tracks = giver.engine.confirmedTracks();
  REQUIRE(tracks.size() == 1);
  REQUIRE(common::declaredTrackClass(tracks[0].class_probabilities).target_class == common::TargetClass::kGroup);
  const auto handoff = giver.engine.release(tracks[0].track, 1);
  CHECK(handoff.class_probabilities == tracks[0].class_probabilities);

  Harness taker(sbmhtScenario());
  for (std::int32_t t = 1; t <= 15; ++t) taker.step(t);
  taker.engine.adopt(handoff);
  taker.step(16, {classified(16, 1, 36.0, 50.0, {})});
  const auto adopted = taker.engine.confirmedTracks();
  REQUIRE(adopted.size() == 1);
  CHECK(adopted[0].track == handoff.track);
  CHECK(adopted[0].class_probabilities == handoff.class_probabilities);

  // A handoff whose class vector is unusable (another engine's: none; or malformed) starts from no
  // evidence instead of being refused.
  auto malformed = handoff;
  malformed.class_probabilities = {0.9, 0.9};
  Harness other(sbmhtScenario());
  for (std::int32_t t = 1; t <= 15; ++t) other.step(t);
  other.engine.adopt(malformed);
  other.step(16, {classified(16, 1, 36.0, 50.0, {})});
  const auto restarted = other.engine.confirmedTracks();
  REQUIRE(restarted.size() == 1);
  CHECK(common::declaredTrackClass(restarted[0].class_probabilities) == common::DeclaredClass{});
}

}  // namespace
}  // namespace wsn::supernode::sbmht
