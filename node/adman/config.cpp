#include "node/adman/config.hpp"

#include <cmath>
#include <memory>

#include "common/config/yaml_reader.hpp"
#include "common/config/yaml_writer.hpp"

namespace wsn::node::adman {
namespace {

/// The lowest Delta2 the model accepts: 10 dB above the floor of its dB arithmetic.
constexpr double kLowestThresholdDb = -290.0;

}  // namespace

Thresholds AdmanSettings::glrtThresholds() const {
  return thresholds(power(), inside_radius, noise_sigma_db, false_alarm_probability);
}

MlmcSettings AdmanSettings::mlmc(std::uint64_t seed) const {
  MlmcSettings m;
  m.power = power();
  m.sigma_db = noise_sigma_db;
  m.inside_radius = inside_radius;
  m.particles = particles;
  m.sweeps = sweeps;
  m.joint = localisation == Localisation::joint;
  m.interaction_range = interaction_range;
  m.neighbours = {sensor_pitch};
  m.seed = seed;
  return m;
}

const common::config::FieldTable<AdmanSettings>& settingsTable() {
  using C = AdmanSettings;
  using namespace common::config;
  static const FieldTable<C> table{
      "sensor_model",
      {
          real<C>("power_db", &C::power_db, closed(-300.0, 300.0), "dB",
                  "Ψ: a target's power at the reference distance (eq. 1). ADMAN §V writes \"4 dB\"; its own Δ1 and Δ2 "
                  "need 40"),
          real<C>("reference_distance", &C::reference_distance, openClosed(0.0, 1e9), "length", "d0 of eq. (1)"),
          real<C>("attenuation", &C::attenuation, closed(1.0, 10.0), "", "α ≥ 1: power falls as d^−α (eq. 1)"),
          real<C>("noise_sigma_db", &C::noise_sigma_db, closed(1e-6, 100.0), "dB",
                  "σ of the reading noise v (eq. 3). ADMAN §V: variance 0.03, σ = 0.17321"),
          real<C>("false_alarm_probability", &C::false_alarm_probability, closed(1e-12, 0.5), "",
                  "P_FA of each GLRT stage: τ32 = Δ1 + σ Q⁻¹(P_FA), τ10 = Δ2 + σ Q⁻¹(P_FA)"),
          derivedDefault(
              real<C>("sensor_pitch", &C::sensor_pitch, openClosed(0.0, 1e9), "length",
                      "the sensors' pitch: N4 neighbours lie within 1.01 pitch, N8 within 1.01 √2 pitch"),
              "the grid's spacing, or sqrt(area / count) for a random layout",
              [](const C&, const common::Scenario& s) {
                if (s.sensors.kind == common::SensorLayoutConfig::Kind::kGrid) return s.sensors.spacing;
                const double area = (s.region.x_max - s.region.x_min) * (s.region.y_max - s.region.y_min);
                return std::sqrt(area / static_cast<double>(std::max<std::uint32_t>(1, s.sensors.count)));
              }),
          derivedDefault(real<C>("inside_radius", &C::inside_radius, openClosed(0.0, 1e9), "length",
                                 "r0: a reading above Δ1 = 10 log10(Ψ d0^α / r0^α) puts a target within r0 (eq. 2)"),
                         "sensor_pitch / 2 (discs of r0 that touch)",
                         [](const C& m, const common::Scenario&) { return m.sensor_pitch / 2.0; }),
          integer<C>("particles", &C::particles, 1, 1e7, "", "P: MLMC particles per target (factorised) or per group (joint)"),
          choice<C>("localisation", &C::localisation, {"factorised", "joint"},
                    "MLMC: factorised places each target on its own 3 × 3 block with the others at their last "
                    "estimate; joint draws every target of a group at once (eq. 15 as written)"),
          integer<C>("sweeps", &C::sweeps, 1, kMaxSweeps, "", "factorised MLMC's sweeps: sweep 1 scores each target on the block sensors nearer its own sensor than any other attached one; each later sweep scores the whole block with the others at the last sweep's estimates"),
          derivedDefault(real<C>("interaction_range", &C::interaction_range, openClosed(0.0, 1e9), "length",
                                 "the targets attached within it of a target's sensor enter its likelihood"),
                         "4 sensor_pitch", [](const C& m, const common::Scenario&) { return 4.0 * m.sensor_pitch; }),
      }};
  return table;
}

SensorModelSettingsSpec settingsSpec() {
  SensorModelSettingsSpec spec;
  spec.keys = settingsTable().sortedKeys();
  spec.read = [](const common::config::Reader& r, const common::config::Section* given, common::Scenario& s) {
    auto settings = std::make_shared<AdmanSettings>();
    if (given != nullptr) r.fields(*given, settingsTable(), *settings);
    common::config::deriveLeftOut(r, given, settingsTable(), *settings, s);
    // Eq. (1) is evaluated in dB down to a floor of -300 dB: a power that puts Delta2 (a target at
    // sqrt2 r0) near it leaves no in-between band and turns noise into inside detections.
    const Thresholds t = settings->glrtThresholds();
    if (!(t.delta2 > kLowestThresholdDb)) {
      const common::config::Entry* at = given != nullptr ? given->find("power_db") : nullptr;
      r.fail(at != nullptr ? common::config::Reader::lineOf(*at) : (given != nullptr ? given->line : 1),
             "'sensor_model.power_db' " + common::config::compactNumber(settings->power_db) + " dB with attenuation " +
                 common::config::compactNumber(settings->attenuation) + " and inside_radius " +
                 common::config::compactNumber(settings->inside_radius) + " gives Delta2 = " +
                 common::config::compactNumber(t.delta2) + " dB at sqrt2 r0; expected above " +
                 common::config::compactNumber(kLowestThresholdDb) + " dB (the model's floor is -300 dB)");
    }
    return std::shared_ptr<const common::SensorModelSettings>(std::move(settings));
  };
  spec.write = [](std::ostream& out, const common::Scenario& s) {
    common::config::writeFields(out, "  ", settingsTable(), common::settingsOf<AdmanSettings>(s.sensor_model), s.derived);
  };
  spec.key_tables = [] {
    return std::vector<common::config::KeyTable>{common::config::keyTable("sensor_model adman", "sensor_model", settingsTable())};
  };
  return spec;
}

}  // namespace wsn::node::adman
