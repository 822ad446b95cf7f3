#include "node/magnetometer/config.hpp"

#include <cmath>

#include "common/config/yaml_reader.hpp"
#include "common/config/yaml_writer.hpp"

namespace wsn::node::magnetometer {
namespace {

using common::Scenario;
using common::config::compactNumber;
using common::config::Reader;
using common::config::Section;

constexpr double kMaxSamplesPerTick = 100000;

/// A tick holds a whole number of samples (at least one): a sensor reports per tick, from its
/// samples in it.
void tickIsWholeSamples(const Reader& r, const MagnetometerSettings& s, int line) {
  const double samples = s.tick_s * s.sample_rate_hz;
  if (samples < 1.0 - 1e-9 || std::abs(samples - std::round(samples)) > 1e-6 * samples ||
      std::round(samples) > kMaxSamplesPerTick)
    r.fail(line, "'sensor_model.tick_s' " + compactNumber(s.tick_s) + " at 'sensor_model.sample_rate_hz' " +
                     compactNumber(s.sample_rate_hz) + " gives " + compactNumber(std::round(samples * 1e6) / 1e6) +
                     " samples per tick; expected a whole number from 1 to " + compactNumber(kMaxSamplesPerTick));
}

}  // namespace

std::int32_t MagnetometerSettings::samplesPerTick() const {
  return static_cast<std::int32_t>(std::lround(tick_s * sample_rate_hz));
}

const common::config::FieldTable<MagnetometerSettings>& settingsTable() {
  using C = MagnetometerSettings;
  using namespace common::config;
  static const FieldTable<C> table{
      "sensor_model",
      {
          real<C>("sample_rate_hz", &C::sample_rate_hz, openClosed(0.0, 1e6), "Hz", "f_s: samples per second and axis"),
          withNotes(real<C>("tick_s", &C::tick_s, openClosed(0.0, 1e4), "s",
                            "seconds per tick: a sensor reports at most once a tick, when eq. (11) fires at any "
                            "of its samples. Velocities stay per tick"),
                    "(0, 10^4], a whole number of samples"),
          integer<C>("window", &C::window, 1, 1000, "samples", "W of Oh eq. (11): the change is averaged over W samples"),
          real<C>("threshold", &C::threshold, kNonNegative, "counts",
                  "η of Oh eq. (11): a sensor detects when the mean change exceeds it (strictly)"),
          real<C>("magnet_height", &C::magnet_height, openClosed(0.0, 1e3), "pitches",
                  "ĥ: height of a target's magnet (a vertical dipole) above the sensor plane"),
          real<C>("magnet_strength", &C::magnet_strength, kNonNegative, "counts·pitch³",
                  "K̂: the horizontal field at horizontal distance ρ is 3 K̂ ĥ ρ / (ρ² + ĥ²)^(5/2) counts, along the "
                  "magnet-sensor line"),
          real<C>("offset_spread", &C::offset_spread, closed(0.0, 1e6), "counts",
                  "each sensor's constant offset per axis is 512 + U(−spread, spread)"),
          real<C>("noise_sigma", &C::noise_sigma, closed(0.0, 1e6), "counts", "σn: read noise per axis and sample"),
          real<C>("drift_sigma", &C::drift_sigma, closed(0.0, 1e6), "counts",
                  "the bias drifts as a random walk with steps N(0, σ²) per axis and sample"),
          real<C>("jump_rate_hz", &C::jump_rate_hz, closed(0.0, 1e3), "1/s",
                  "λj: bias jumps (offset re-centring) per sensor and second, the source of false alarms"),
          real<C>("jump_max", &C::jump_max, closed(0.0, 1e6), "counts",
                  "a jump's size is U(0, jump_max) in a random direction"),
          real<C>("adc_max", &C::adc_max, openClosed(0.0, 1e9), "counts", "readings are clipped to [0, adc_max] per axis"),
      }};
  return table;
}

SensorModelSettingsSpec settingsSpec() {
  SensorModelSettingsSpec spec;
  spec.keys = settingsTable().sortedKeys();
  spec.read = [](const Reader& r, const Section* given, Scenario&) {
    auto settings = std::make_shared<MagnetometerSettings>();
    if (given == nullptr) return std::shared_ptr<const common::SensorModelSettings>(std::move(settings));
    r.fields(*given, settingsTable(), *settings);
    const common::config::Entry* at = given->find("tick_s") != nullptr ? given->find("tick_s") : given->find("sample_rate_hz");
    tickIsWholeSamples(r, *settings, at != nullptr ? Reader::lineOf(*at) : given->line);
    return std::shared_ptr<const common::SensorModelSettings>(std::move(settings));
  };
  spec.write = [](std::ostream& out, const Scenario& s) {
    common::config::writeFields(out, "  ", settingsTable(), common::settingsOf<MagnetometerSettings>(s.sensor_model),
                                s.derived);
  };
  spec.key_tables = [] {
    return std::vector<common::config::KeyTable>{
        common::config::keyTable("sensor_model magnetometer", "sensor_model", settingsTable())};
  };
  return spec;
}

}  // namespace wsn::node::magnetometer
