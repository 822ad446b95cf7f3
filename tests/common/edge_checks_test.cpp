// The edge checks every received report meets (common/edge_checks.hpp): the bounds derived from the
// scenario by hand, each reason a report is refused for, and the counts a role leaves behind.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "common/edge_checks.hpp"

namespace wsn::common {
namespace {

Scenario square100() {
  Scenario s;
  s.region = Rect{0.0, 0.0, 100.0, 50.0};
  s.sensor_model.sensing_range = 1.5;
  s.localisation.sigma = 0.5;
  s.run.ticks = 40;
  return s;
}

Report at(double x, double y, SensorId sensor = 3) {
  Report r;
  r.tick = 5;
  r.sensor = sensor;
  r.x = x;
  r.y = y;
  return r;
}

TEST_CASE("the margin is the region's larger side plus the sensing range and six deviations", "[edge]") {
  const EdgeBounds b = edgeBounds(square100());
  // 100 + 1.5 + 6 x 0.5
  CHECK(b.margin == Approx(104.5));
  CHECK(b.region.x_min == Approx(-104.5));
  CHECK(b.region.y_max == Approx(154.5));
  CHECK(b.sensors == 5000);  // the default grid, spacing 1 over 100 x 50
  CHECK(b.ticks == 40);
  CHECK(b.max_reports == 5000 * kMaxReportsPerSensor);
}

TEST_CASE("a report inside the region and its margin passes", "[edge]") {
  const EdgeBounds b = edgeBounds(square100());
  CHECK_FALSE(checkReport(at(50.0, 25.0), b));
  CHECK_FALSE(checkReport(at(-104.0, 154.0), b));
  CHECK_FALSE(checkReport(at(0.0, 0.0, 4999), b));
}

TEST_CASE("each kind of bad report is refused for its reason", "[edge]") {
  const EdgeBounds b = edgeBounds(square100());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(checkReport(at(nan, 1.0), b) == RejectReason::kNotFinite);
  CHECK(checkReport(at(1.0, -inf), b) == RejectReason::kNotFinite);
  CHECK(checkReport(at(1e308, 1.0), b) == RejectReason::kOutOfRegion);
  CHECK(checkReport(at(-105.0, 1.0), b) == RejectReason::kOutOfRegion);
  CHECK(checkReport(at(1.0, 1.0, 5000), b) == RejectReason::kSensorOutOfRange);
}

TEST_CASE("a measurement's values must be finite bounded and well formed", "[edge]") {
  const EdgeBounds b = edgeBounds(square100());
  Measurement bearing;
  bearing.kind = MeasurementKind::bearing;
  bearing.values = {0.3};
  bearing.sensor = SensorPose{1.0, 2.0, 0.0, 0.0};
  Report r = at(1.0, 2.0);
  r.measurement = MeasurementRef(bearing);
  CHECK_FALSE(checkReport(r, b));

  Measurement nan_value = bearing;
  nan_value.values = {std::numeric_limits<double>::quiet_NaN()};
  r.measurement = MeasurementRef(nan_value);
  CHECK(checkReport(r, b) == RejectReason::kNotFinite);

  Measurement huge_clutter = bearing;
  huge_clutter.clutter_density = 1e300;
  r.measurement = MeasurementRef(huge_clutter);
  CHECK(checkReport(r, b) == RejectReason::kOutOfRegion);

  Measurement no_pose = bearing;
  no_pose.sensor.reset();
  r.measurement = MeasurementRef(no_pose);
  CHECK(checkReport(r, b) == RejectReason::kMalformedMeasurement);
}

TEST_CASE("dropping refused reports keeps the rest in order and counts each", "[edge]") {
  const EdgeBounds b = edgeBounds(square100());
  std::vector<Report> reports{at(1.0, 1.0, 1), at(std::nan(""), 1.0, 2), at(2.0, 2.0, 3), at(1e308, 0.0, 4),
                              at(3.0, 3.0, 5000)};
  RejectionLog log;
  dropRejectedReports(reports, b, "wsn_report_batch", log);
  REQUIRE(reports.size() == 2);
  CHECK(reports[0].sensor == 1);
  CHECK(reports[1].sensor == 3);
  CHECK(log.total() == 3);
  CHECK(log.count("wsn_report_batch", RejectReason::kNotFinite) == 1);
  CHECK(log.count("wsn_report_batch", RejectReason::kOutOfRegion) == 1);
  CHECK(log.count("wsn_report_batch", RejectReason::kSensorOutOfRange) == 1);
}

TEST_CASE("the record of rejections names role topic reason and count", "[edge]") {
  RejectionLog log;
  log.add("wsn_report_batch", RejectReason::kDuplicate, 2);
  log.add("wsn_report_batch", RejectReason::kForeignRun);
  log.add("wsn_report_batch", RejectReason::kDuplicate);
  log.add("wsn_report_batch", RejectReason::kTooLong, 0);  // nothing to count
  CHECK(log.total() == 4);
  CHECK(log.json("network", 0) ==
        "{\"role\": \"network\", \"index\": 0, \"rejected\": ["
        "{\"topic\": \"wsn_report_batch\", \"reason\": \"foreign_run\", \"count\": 1}, "
        "{\"topic\": \"wsn_report_batch\", \"reason\": \"duplicate\", \"count\": 3}]}\n");
  CHECK(RejectionLog().json("node", 2) == "{\"role\": \"node\", \"index\": 2, \"rejected\": []}\n");
}

TEST_CASE("a batch's run id producer and tick are checked first", "[edge]") {
  CHECK_FALSE(checkBatchHeader(7, 7, 2, 3, 1, 40));
  CHECK_FALSE(checkBatchHeader(7, 7, 0, 1, 40, 40));
  CHECK(checkBatchHeader(8, 7, 0, 3, 5, 40) == RejectReason::kForeignRun);
  CHECK(checkBatchHeader(7, 7, 3, 3, 5, 40) == RejectReason::kProducerOutOfRange);
  CHECK(checkBatchHeader(7, 7, 0, 3, 0, 40) == RejectReason::kTickOutOfRange);
  CHECK(checkBatchHeader(7, 7, 0, 3, 41, 40) == RejectReason::kTickOutOfRange);
}

TEST_CASE("an observation was generated no later than delivered", "[edge]") {
  const EdgeBounds b = edgeBounds(square100());
  Observation o;
  o.tick_generated = 4;
  o.tick_delivered = 6;
  o.sensor = 10;
  o.x = 5.0;
  o.y = 5.0;
  CHECK_FALSE(checkObservation(o, b));
  o.tick_generated = 7;
  CHECK(checkObservation(o, b) == RejectReason::kTickOutOfRange);
  o.tick_generated = 0;
  CHECK(checkObservation(o, b) == RejectReason::kTickOutOfRange);
  o.tick_generated = 6;
  o.y = std::numeric_limits<double>::infinity();
  CHECK(checkObservation(o, b) == RejectReason::kNotFinite);
}

TEST_CASE("a track's state covariance and classes must be finite and bounded", "[edge]") {
  const EdgeBounds b = edgeBounds(square100());
  TrackEstimate t;
  t.x = 10.0;
  t.y = 10.0;
  t.vx = 1.0;
  t.last_seen_tick = 40;
  t.class_probabilities = {0.5, 0.5};
  CHECK_FALSE(checkTrack(t, b));
  TrackEstimate bad = t;
  bad.covariance[5] = std::numeric_limits<double>::quiet_NaN();
  CHECK(checkTrack(bad, b) == RejectReason::kNotFinite);
  bad = t;
  bad.vy = 1e300;
  CHECK(checkTrack(bad, b) == RejectReason::kOutOfRegion);
  bad = t;
  bad.x = 300.0;
  CHECK(checkTrack(bad, b) == RejectReason::kOutOfRegion);
  bad = t;
  bad.last_seen_tick = 41;
  CHECK(checkTrack(bad, b) == RejectReason::kTickOutOfRange);
  bad = t;
  bad.stop_probability = std::numeric_limits<double>::infinity();
  CHECK(checkTrack(bad, b) == RejectReason::kNotFinite);
}

TEST_CASE("a handoff goes to a supernode the run has at a tick of the run", "[edge]") {
  const EdgeBounds b = edgeBounds(square100());
  TrackHandoff h;
  h.to_supernode = 3;
  h.last_tick = 12;
  h.state = {20.0, 30.0, 0.5, 0.0};
  CHECK_FALSE(checkHandoff(h, b, 4));
  CHECK(checkHandoff(h, b, 3) == RejectReason::kMisaddressed);
  TrackHandoff bad = h;
  bad.last_tick = 0;
  CHECK(checkHandoff(bad, b, 4) == RejectReason::kTickOutOfRange);
  bad = h;
  bad.covariance[0] = -std::numeric_limits<double>::infinity();
  CHECK(checkHandoff(bad, b, 4) == RejectReason::kNotFinite);
  bad = h;
  bad.state[1] = -500.0;
  CHECK(checkHandoff(bad, b, 4) == RejectReason::kOutOfRegion);
}

TEST_CASE("a boundary reading names a sensor of the run and a finite value", "[edge]") {
  const EdgeBounds b = edgeBounds(square100());
  CHECK_FALSE(checkReading({4999, 0.7}, b));
  CHECK(checkReading({5000, 0.7}, b) == RejectReason::kSensorOutOfRange);
  CHECK(checkReading({1, std::numeric_limits<double>::quiet_NaN()}, b) == RejectReason::kNotFinite);
  CHECK(checkReading({1, 1e200}, b) == RejectReason::kOutOfRegion);
}

}  // namespace
}  // namespace wsn::common
