// The field sensors' class likelihoods (ONERA eqs. 19-20, spec §4 PROP): a classifying type reports
// c = CM[., d] with its declared class d ~ CM[true class, .]; radar and PIR report none.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "common/class_evidence.hpp"
#include "common/sensor_layout.hpp"
#include "common/truth.hpp"
#include "node/field_sensors/field_sensors.hpp"
#include "node/tiling.hpp"
#include "scenario/loader.hpp"

namespace wsn::node::field_sensors {
namespace {

/// A 4000 x 4000 m field, `ticks` long, with the given sensors and targets lines (YAML list items)
/// and sensor_model lines.
common::Scenario field(const std::string& sensors, const std::string& targets, const std::string& model = "",
                       int ticks = 300, std::uint64_t seed = 1) {
  return scenario::parseScenario(
      "region: {x_min: -2000, y_min: -2000, x_max: 2000, y_max: 2000}\n"
      "sensors:\n  layout: list\n  list:\n" + sensors +
          "sensor_model:\n  kind: field_sensors\n  sensing_range: 100\n" + model +
          "dynamics: {delta: 1, process_noise_sigma: 0}\n"
          "targets:\n  scripted:\n" + targets +
          "run: {ticks: " + std::to_string(ticks) + ", seed: " + std::to_string(seed) + "}\n",
      "field_sensor_classes_test.yaml");
}

/// Every report of ticks 1..ticks, in tick then sensor order.
std::vector<common::Report> reportsOf(const common::Scenario& s, std::int32_t ticks) {
  const common::SensorLayout layout(common::sensorFieldConfig(s));
  const common::Truth truth(common::truthConfig(s));
  const FieldSensors sensors(common::settingsOf<FieldSensorsSettings>(s.sensor_model), s.run.seed, layout,
                             makeTiles(layout, 1).front(), truth);
  std::vector<common::Report> all;
  for (std::int32_t t = 1; t <= ticks; ++t) {
    const auto reports = sensors.detect(t);
    all.insert(all.end(), reports.begin(), reports.end());
  }
  return all;
}

/// The columns of cm equal to c (exactly: c is copied out of the matrix).
std::vector<std::size_t> columnsEqualTo(const common::ConfusionMatrix& cm, const std::vector<double>& c) {
  std::vector<std::size_t> out;
  if (c.size() != static_cast<std::size_t>(cm.rows())) return out;
  for (Eigen::Index d = 0; d < cm.cols(); ++d) {
    bool equal = true;
    for (Eigen::Index i = 0; i < cm.rows(); ++i) equal = equal && cm(i, d) == c[static_cast<std::size_t>(i)];
    if (equal) out.push_back(static_cast<std::size_t>(d));
  }
  return out;
}

/// A target of class `cls` along y = 1 from x = -150 at 1 per tick: within 200 m of the origin (and
/// 2 m of a magnetic detector at (x, 0) at the tick it passes) for 300 ticks.
std::string walker(const std::string& cls) {
  return "    - {appear_tick: 1, x: -150, y: 1, vx: 1, vy: 0, class: " + cls + "}\n";
}

TEST_CASE("field sensors: a classifying type's class likelihoods are a column of its confusion matrix",
          "[field_sensors][classes]") {
  // PD 1, no false alarms. Cameras a = 0.85 and acoustic types a = 0.6 (symmetric CM), magnetic the
  // 0.9 vehicle/non-vehicle blocks: every detection's c is one column of its type's PROP matrix.
  const auto s = field(
      "    - {name: c, type: camera, x: 0, y: 0, heading: 0, fov: 360, range: 400}\n"
      "    - {name: a, type: acoustic_antenna, x: 0, y: 50}\n"
      "    - {name: b, type: acoustic_beacon, x: 0, y: -50}\n"
      "    - {name: m, type: magnetic, x: 0, y: 0}\n",
      walker("tracked"),
      "  camera: {detection_probability: 1, false_alarms_per_tick: 0}\n"
      "  acoustic_antenna: {detection_probability: 1, false_alarms_per_tick: 0}\n"
      "  acoustic_beacon: {detection_probability: 1, false_alarms_per_tick: 0}\n"
      "  magnetic: {detection_probability: 1}\n");
  const common::ConfusionMatrix cms[] = {common::confusionMatrix(common::Classifier::kCamera),
                                         common::confusionMatrix(common::Classifier::kAcoustic),
                                         common::confusionMatrix(common::Classifier::kAcoustic),
                                         common::confusionMatrix(common::Classifier::kMagnetic)};
  CHECK(cms[0](0, 0) == 0.85);
  CHECK(cms[1](0, 0) == 0.6);
  std::vector<int> count(4, 0);
  for (const auto& r : reportsOf(s, 300)) {
    REQUIRE(r.target == 0);
    REQUIRE(r.measurement);
    INFO("sensor " << r.sensor << " tick " << r.tick);
    CHECK(r.measurement->class_likelihoods.size() == common::kClassCount);
    CHECK_FALSE(columnsEqualTo(cms[r.sensor], r.measurement->class_likelihoods).empty());
    ++count[r.sensor];
  }
  // Every type saw the target (the magnetic detector over the 5 ticks it is within 2 m).
  CHECK(count[0] == 300);
  CHECK(count[1] == 300);
  CHECK(count[2] == 300);
  CHECK(count[3] >= 3);
}

TEST_CASE("field sensors: a camera's declared classes follow the row of its confusion matrix",
          "[field_sensors][classes]") {
  // A camera seeing all round to 2000 m, PD 1, and a human (class index 3) crossing it for N = 3000
  // ticks: each tick one independent declaration d ~ CM[3, .] = (.03, .03, .03, .85, .03, .03).
  // A declared class is the argmax of c (a = .85 sits on the diagonal of column d). Counts are
  // binomial: the true class N .85 = 2550, σ = sqrt(N .85 .15) = 19.6; each other class N .03 = 90,
  // σ = sqrt(N .03 .97) = 9.3. Accept 4 σ: 2550 ± 80 and 90 ± 38.
  constexpr int kTicks = 3000;
  const auto s = field("    - {name: c, type: camera, x: 0, y: 0, heading: 0, fov: 360, range: 2000}\n",
                       "    - {appear_tick: 1, x: -1500, y: 1, vx: 1, vy: 0, class: human}\n",
                       "  camera: {detection_probability: 1, false_alarms_per_tick: 0}\n", kTicks);
  std::vector<int> declared(common::kClassCount, 0);
  int reports = 0;
  for (const auto& r : reportsOf(s, kTicks)) {
    const auto& c = r.measurement->class_likelihoods;
    REQUIRE(c.size() == common::kClassCount);
    ++declared[static_cast<std::size_t>(std::max_element(c.begin(), c.end()) - c.begin())];
    ++reports;
  }
  REQUIRE(reports == kTicks);
  const std::size_t human = *common::classIndex(common::TargetClass::kHuman);
  for (std::size_t d = 0; d < common::kClassCount; ++d) {
    INFO("declared class " << d << ": " << declared[d]);
    if (d == human)
      CHECK(std::abs(declared[d] - 2550) <= 80);
    else
      CHECK(std::abs(declared[d] - 90) <= 38);
  }
}

TEST_CASE("field sensors: radar and PIR reports carry no class likelihoods", "[field_sensors][classes]") {
  const auto s = field(
      "    - {name: r, type: radar, x: -100, y: 1, heading: 0}\n"
      "    - {name: p, type: pir, x: 0, y: -50, heading: 90, fov: 20}\n",
      walker("wheeled_heavy"),
      "  radar: {detection_probability: 1}\n"
      "  pir: {detection_probability: 1}\n");
  std::vector<int> count(2, 0);
  for (const auto& r : reportsOf(s, 300)) {
    CHECK(r.measurement->class_likelihoods.empty());
    ++count[r.sensor];
  }
  CHECK(count[0] > 50);  // the radar's plots, false ones included
  CHECK(count[1] > 0);   // the PIR's beam crossed
}

TEST_CASE("field sensors: a target of unknown class and a false alarm carry no class likelihoods",
          "[field_sensors][classes]") {
  // A camera with many false alarms; the target has no class.
  const auto s = field("    - {name: c, type: camera, x: 0, y: 0, heading: 0, fov: 360, range: 400}\n",
                       "    - {appear_tick: 1, x: -150, y: 1, vx: 1, vy: 0}\n",
                       "  camera: {detection_probability: 1, false_alarms_per_tick: 1}\n");
  int detections = 0;
  int false_alarms = 0;
  for (const auto& r : reportsOf(s, 100)) {
    CHECK(r.measurement->class_likelihoods.empty());
    (r.target == common::kFalseAlarm ? false_alarms : detections) += 1;
  }
  CHECK(detections == 100);
  CHECK(false_alarms > 50);
  // With a class, the false alarms still carry none and the detections do.
  const auto classed = field("    - {name: c, type: camera, x: 0, y: 0, heading: 0, fov: 360, range: 400}\n",
                             walker("group"), "  camera: {detection_probability: 1, false_alarms_per_tick: 1}\n");
  for (const auto& r : reportsOf(classed, 100))
    CHECK(r.measurement->class_likelihoods.size() == (r.target == common::kFalseAlarm ? 0u : common::kClassCount));
}

TEST_CASE("field sensors: class likelihoods are reproducible and draw on a stream of their own",
          "[field_sensors][classes]") {
  // PD 1 and no false alarms: each sensor reports the target every tick, so runs align report by report.
  const std::string sensors =
      "    - {name: c, type: camera, x: 0, y: 0, heading: 0, fov: 360, range: 400}\n"
      "    - {name: a, type: acoustic_antenna, x: 0, y: 50}\n";
  const std::string model =
      "  camera: {detection_probability: 1, false_alarms_per_tick: 0}\n"
      "  acoustic_antenna: {detection_probability: 1, false_alarms_per_tick: 0}\n";
  const auto one = reportsOf(field(sensors, walker("aerial"), model), 200);
  REQUIRE(one.size() == 400);
  // Same seed, same reports, c included.
  CHECK(one == reportsOf(field(sensors, walker("aerial"), model), 200));
  // Another seed declares other classes at some ticks (at a = .6 the antenna errs 40 % of the time).
  const auto other = reportsOf(field(sensors, walker("aerial"), model, 300, 2), 200);
  REQUIRE(other.size() == 400);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < std::min(one.size(), other.size()); ++k)
    differ += one[k].measurement->class_likelihoods != other[k].measurement->class_likelihoods ? 1 : 0;
  CHECK(differ > 0);
  // Classifying draws nothing from the detection stream: without a class, the same detections with
  // the same values.
  const auto unclassed =
      reportsOf(field(sensors, "    - {appear_tick: 1, x: -150, y: 1, vx: 1, vy: 0}\n", model), 200);
  REQUIRE(unclassed.size() == one.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    CHECK(unclassed[k].target == one[k].target);
    CHECK(unclassed[k].measurement->values == one[k].measurement->values);
  }
}

}  // namespace
}  // namespace wsn::node::field_sensors
