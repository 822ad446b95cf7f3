#include "common/measurement.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <catch2/catch.hpp>

#include "common/messages.hpp"

namespace wsn::common {
namespace {

TEST_CASE("every measurement kind has a name that names it back and a dimension", "[measurement]") {
  for (int k = 0; k <= static_cast<int>(MeasurementKind::presence); ++k) {
    const auto kind = static_cast<MeasurementKind>(k);
    const auto name = measurementKindName(kind);
    INFO(std::string(name));
    CHECK(measurementKindNamed(name) == kind);
    REQUIRE(measurementDimension(kind).has_value());
    CHECK(*measurementDimension(kind) <= kMaxMeasurementDimension);
  }
  CHECK(measurementKindName(MeasurementKind::position) == "position");  // the registries' word
  CHECK(*measurementDimension(MeasurementKind::range_bearing_rate) == 3);  // rho, theta, rho_dot
  CHECK_FALSE(measurementKindNamed("sonar").has_value());
  const auto unknown = static_cast<MeasurementKind>(200);
  CHECK(measurementKindName(unknown) == "unknown");
  CHECK_FALSE(measurementDimension(unknown).has_value());
}

TEST_CASE("a report built from a position measures that position and allocates nothing", "[measurement]") {
  const Report r{4, 17, 2.5, -1.0, 3};
  CHECK(r.measurement.get() == nullptr);  // a plain position: no measurement object
  CHECK(r.measurement.kind() == MeasurementKind::position);
  CHECK(wellFormed(r));
  const Observation o = observationOf(r, 6);
  CHECK(o.tick_generated == 4);
  CHECK(o.tick_delivered == 6);
  const Measurement full = measurementOf(o);
  CHECK(full == Measurement::position(2.5, -1.0));
  CHECK(full.dimension() == 2);
  CHECK_FALSE(full.hasNoise());  // the engine's own measurement model applies
}

TEST_CASE("measurement references compare by content with plain positions first", "[measurement]") {
  const MeasurementRef plain;
  const MeasurementRef a(Measurement::position(1.0, 2.0));
  const MeasurementRef same(Measurement::position(1.0, 2.0));
  const MeasurementRef b(Measurement::position(1.0, 3.0));
  CHECK(a == same);  // two objects, one content
  CHECK_FALSE(a == plain);
  CHECK(plain == MeasurementRef{});
  CHECK(plain < a);
  CHECK(a < b);
  CHECK_FALSE(b < a);
}

TEST_CASE("an all-zero noise matrix means the sensor did not give one", "[measurement]") {
  Measurement m = Measurement::position(1.0, 2.0);
  m.noise = {0.0, 0.0, 0.0, 0.0};
  CHECK_FALSE(m.hasNoise());
  CHECK(wellFormed(m));
  m.noise = {1.0, 0.0, 0.0, 1.0};  // R = I (Oh §VIII-style diag(1, 1))
  CHECK(m.hasNoise());
}

TEST_CASE("malformed measurements are told apart from usable ones", "[measurement]") {
  Measurement bearing;
  bearing.kind = MeasurementKind::bearing;
  bearing.values = {0.5};
  bearing.noise = {0.01};
  bearing.sensor = SensorPose{1.0, 2.0, 0.0};
  bearing.class_likelihoods = {0.7, 0.3};
  REQUIRE(wellFormed(bearing));

  auto broken = bearing;
  broken.values = {0.5, 0.1};  // a bearing has dimension 1
  CHECK_FALSE(wellFormed(broken));
  broken = bearing;
  broken.noise = {0.01, 0.0};  // R must be 1 x 1
  CHECK_FALSE(wellFormed(broken));
  broken = bearing;
  broken.sensor.reset();  // a bearing means nothing without where the sensor looked
  CHECK_FALSE(wellFormed(broken));
  broken = bearing;
  broken.values = {std::numeric_limits<double>::infinity()};
  CHECK_FALSE(wellFormed(broken));
  broken = bearing;
  broken.class_likelihoods = {-0.1};
  CHECK_FALSE(wellFormed(broken));
  broken = bearing;
  broken.class_likelihoods.assign(kMaxClasses + 1, 0.1);
  CHECK_FALSE(wellFormed(broken));
  broken = bearing;
  broken.kind = static_cast<MeasurementKind>(200);
  CHECK_FALSE(wellFormed(broken));
  broken = bearing;
  broken.sensor->height = -1.0;  // a mast below the ground
  CHECK_FALSE(wellFormed(broken));
  broken = bearing;
  broken.clutter_density = -1e-3;
  CHECK_FALSE(wellFormed(broken));
  broken = bearing;
  broken.clutter_density = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(wellFormed(broken));

  // A report's x, y must agree with its measurement: the position, or the sensor's position.
  Report r{1, 5, 1.0, 2.0, 0, 0, MeasurementRef(bearing)};
  CHECK(wellFormed(r));
  r.x = 1.5;
  CHECK_FALSE(wellFormed(r));
  Report p{1, 5, 1.0, 2.0, 0, 0, MeasurementRef(Measurement::position(1.0, 2.0))};
  CHECK(wellFormed(p));
  p.x = 3.0;  // assigned after construction without updating the measurement
  CHECK_FALSE(wellFormed(p));
}

}  // namespace
}  // namespace wsn::common
