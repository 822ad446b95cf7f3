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
  const EdgeBounds b = edgeBounds(square100(), 400);
  // 100 + 1.5 + 6 x 0.5
  CHECK(b.margin == Approx(104.5));
  CHECK(b.region.x_min == Approx(-104.5));
  CHECK(b.region.y_max == Approx(154.5));
  CHECK(b.sensors == 400);
  CHECK(b.ticks == 40);
  CHECK(b.max_reports == 400);
}

TEST_CASE("a report inside the region and its margin passes", "[edge]") {
  const EdgeBounds b = edgeBounds(square100(), 400);
  CHECK_FALSE(checkReport(at(50.0, 25.0), b));
  CHECK_FALSE(checkReport(at(-104.0, 154.0), b));
  CHECK_FALSE(checkReport(at(0.0, 0.0, 399), b));
}

TEST_CASE("each kind of bad report is refused for its reason", "[edge]") {
  const EdgeBounds b = edgeBounds(square100(), 400);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(checkReport(at(nan, 1.0), b) == RejectReason::kNotFinite);
  CHECK(checkReport(at(1.0, -inf), b) == RejectReason::kNotFinite);
  CHECK(checkReport(at(1e308, 1.0), b) == RejectReason::kOutOfRegion);
  CHECK(checkReport(at(-105.0, 1.0), b) == RejectReason::kOutOfRegion);
  CHECK(checkReport(at(1.0, 1.0, 400), b) == RejectReason::kSensorOutOfRange);
}

TEST_CASE("a measurement's values must be finite bounded and well formed", "[edge]") {
  const EdgeBounds b = edgeBounds(square100(), 400);
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
  const EdgeBounds b = edgeBounds(square100(), 400);
  std::vector<Report> reports{at(1.0, 1.0, 1), at(std::nan(""), 1.0, 2), at(2.0, 2.0, 3), at(1e308, 0.0, 4),
                              at(3.0, 3.0, 500)};
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

}  // namespace
}  // namespace wsn::common
