// What a sensor report measured: its kind, its values and their noise, and what an engine needs to
// use them (the sensor's pose, class likelihoods). Pure C++; idl/wsntrack.idl holds the wire form.
#pragma once

#include <compare>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace wsn::common {

/// What a measurement's values are: ONERA eq. 3's measurement functions, plus the kinds of the
/// seed papers' own sensors. The names (measurementKindName) are the ones sensor models list in
/// SensorModelSpec::measurement_kinds and engines in EngineSpec::accepts.
///
/// Adding a kind: append an enumerator here (never renumber: the value goes on the wire), give it a
/// row in measurement.cpp's table (name, dimension), append the same enumerator to MeasurementKind
/// in idl/wsntrack.idl, and name it in the sensor model's measurement_kinds and in the `accepts` of
/// every engine that can use it. Nothing in between (network model, window, codec) changes.
enum class MeasurementKind : std::uint8_t {
  position = 0,            ///< (x, y) in the field frame (Oh eq. 6, a magnetometer's h_mag)
  bearing = 1,             ///< (theta): direction of arrival (acoustic antenna, PIR)
  range_bearing_rate = 2,  ///< (rho, theta, rho_dot): radar
  azimuth_elevation = 3,   ///< (theta, phi): camera
  signal_strength = 4,     ///< (z): received signal strength at the sensor (Oh eq. 5)
  presence = 5,            ///< (): a target is within the sensor's coverage (magnetic, beacon)
};

/// Largest dimension of any kind; bounds the wire's sequences.
inline constexpr std::size_t kMaxMeasurementDimension = 4;
/// A clutter density is never below one false report per this many ticks over its space, so that a
/// tracker's score ln(PD Lambda / lambda) stays finite for a sensor without false alarms: the field
/// sensors floor the density their reports carry, and sbmht its own density per area.
inline constexpr double kClutterFloorTicks = 100.0;
/// Most class likelihoods a measurement carries (ONERA's exclusive set has kClassCount = 6, in
/// common/class_evidence.hpp; the spec's proposal of 7 also fits).
inline constexpr std::size_t kMaxClasses = 8;

/// Where a sensor stood and where it looked, in the field frame. Angles of a measurement (theta,
/// phi) are radians counter-clockwise from the heading, so a sensor reports in its own frame and
/// the engine, not the sensor, brings them into the field frame.
struct SensorPose {
  double x = 0.0;        ///< believed position
  double y = 0.0;
  double heading = 0.0;  ///< radians counter-clockwise from the field's +x axis
  /// Height above the targets' ground (a camera's mast): an elevation phi is atan2(-height, range).
  /// Carried with the report so that a supernode needs no sensor list to read it.
  double height = 0.0;
  friend bool operator==(const SensorPose&, const SensorPose&) = default;
  friend auto operator<=>(const SensorPose&, const SensorPose&) = default;
};

/// One measurement z = h(x) + b, b ~ N(0, R) (ONERA eq. 2).
struct Measurement {
  MeasurementKind kind = MeasurementKind::position;
  /// z in the kind's order; their count is the dimension.
  std::vector<double> values;
  /// R, row-major dimension x dimension. Empty (or all zero) when the sensor does not know it: the
  /// engine's own measurement model applies, which is what the position engines always do.
  std::vector<double> noise;
  /// The sensor's pose; every kind but position needs it to relate z to the field.
  std::optional<SensorPose> sensor;
  /// c_k over the scenario's classes (ONERA eq. 19–20); empty when the sensor does not classify.
  std::vector<double> class_likelihoods;
  /// This sensor's false reports per unit volume of its measurement space per tick (per radian for
  /// a bearing, per m x rad x m/s for a radar): the clutter term lambda_fa of a report's score
  /// (ONERA eq. 17) in the space the report lives in. 0 when the sensor does not say; the engine's
  /// own density (per area) applies, which only a position can use.
  double clutter_density = 0.0;

  std::size_t dimension() const { return values.size(); }
  /// True when the sensor gave R (a non-zero one).
  bool hasNoise() const;

  /// A position (x, y) whose noise the engine models.
  static Measurement position(double x, double y) { return {MeasurementKind::position, {x, y}, {}, {}, {}}; }

  friend bool operator==(const Measurement&, const Measurement&) = default;
  /// Lexicographic over the members: only breaks ties in canonical orders.
  friend std::partial_ordering operator<=>(const Measurement&, const Measurement&) = default;
};

/// What a report or observation measured, beyond where it lies: null for a position (x, y) whose
/// noise the engine models, which is every report of the signal-strength and acoustic models, so
/// those carry one null pointer and allocate nothing (the position engines' benchmarks keep their
/// speed); otherwise a shared, immutable Measurement, so copies along the pipeline stay cheap.
class MeasurementRef {
 public:
  MeasurementRef() = default;
  explicit MeasurementRef(Measurement m) : m_(std::make_shared<const Measurement>(std::move(m))) {}

  /// The measurement, or nullptr for a plain position.
  const Measurement* get() const { return m_.get(); }
  explicit operator bool() const { return m_ != nullptr; }
  const Measurement& operator*() const { return *m_; }
  const Measurement* operator->() const { return m_.get(); }
  MeasurementKind kind() const { return m_ ? m_->kind : MeasurementKind::position; }

  /// Equal in content; a plain position equals only a plain position.
  friend bool operator==(const MeasurementRef& a, const MeasurementRef& b) {
    return a.m_ == b.m_ || (a.m_ && b.m_ && *a.m_ == *b.m_);
  }
  /// Plain positions first, then by content: only breaks ties in canonical orders.
  friend std::partial_ordering operator<=>(const MeasurementRef& a, const MeasurementRef& b) {
    if (!a.m_ || !b.m_) return (a.m_ != nullptr) <=> (b.m_ != nullptr);
    return *a.m_ <=> *b.m_;
  }

 private:
  std::shared_ptr<const Measurement> m_;
};

/// "position", "bearing", ...; "unknown" for a value no kind has (a malformed sample).
std::string_view measurementKindName(MeasurementKind kind);
/// The kind called `name`, or nullopt.
std::optional<MeasurementKind> measurementKindNamed(std::string_view name);
/// The dimension every measurement of `kind` has, or nullopt for a value no kind has.
std::optional<std::size_t> measurementDimension(MeasurementKind kind);

/// True when an engine can use `m`: a known kind with its dimension, finite values, R empty or
/// dimension x dimension and finite, a finite pose (height >= 0) wherever the kind needs one, at most
/// kMaxClasses finite, non-negative class likelihoods, and a finite, non-negative clutter density.
bool wellFormed(const Measurement& m);

}  // namespace wsn::common
