#include "node/signal_strength/config.hpp"

#include <cmath>

#include "common/config/yaml_writer.hpp"

namespace wsn::node::signal_strength {

const common::config::FieldTable<SignalStrengthSettings>& settingsTable() {
  using C = SignalStrengthSettings;
  using namespace common::config;
  static const FieldTable<C> table{
      "sensor_model",
      {
          real<C>("alpha", &C::alpha, openClosed(0.0, 100.0), "", "α, decay exponent (§VII)"),
          derivedDefault(withNotes(real<C>("beta", &C::beta, openClosed(0.0, 1e12), "signal",
                                           "β, signal at distance 0. When it is left out, the loader computes it "
                                           "from the other values of the file as in §VII"),
                                   "", "3 (1 + γ Rs^α) = 9.75"),
                         "3 (1 + gamma Rs^alpha)",
                         // Oh §VII: a signal three times the one at the edge of the range.
                         [](const C& m, const common::Scenario& s) {
                           return 3.0 * (1.0 + m.gamma * std::pow(s.sensor_model.sensing_range, m.alpha));
                         }),
          real<C>("gamma", &C::gamma, kNonNegative, "1/separation^α", "γ (§VII)"),
          real<C>("eta", &C::eta, openClosed(0.0, 1e9), "signal", "η, detection threshold (§VII)"),
          real<C>("noise_sigma", &C::noise_sigma, kNonNegative, "signal",
                  "standard deviation of w. 0 means no false alarms"),
      }};
  return table;
}

SensorModelSettingsSpec settingsSpec() {
  SensorModelSettingsSpec spec;
  spec.keys = settingsTable().sortedKeys();
  spec.read = [](const common::config::Reader& r, const common::config::Section* given, common::Scenario& s) {
    auto settings = std::make_shared<SignalStrengthSettings>();
    if (given != nullptr) r.fields(*given, settingsTable(), *settings);
    common::config::deriveLeftOut(r, given, settingsTable(), *settings, s);
    return std::shared_ptr<const common::SensorModelSettings>(std::move(settings));
  };
  spec.write = [](std::ostream& out, const common::Scenario& s) {
    common::config::writeFields(out, "  ", settingsTable(), common::settingsOf<SignalStrengthSettings>(s.sensor_model),
                                s.derived);
  };
  spec.key_tables = [] {
    return std::vector<common::config::KeyTable>{
        common::config::keyTable("sensor_model signal_strength", "sensor_model", settingsTable())};
  };
  return spec;
}

}  // namespace wsn::node::signal_strength
