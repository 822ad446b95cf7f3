#include "node/acoustic/config.hpp"

#include <cmath>

#include "common/config/yaml_reader.hpp"
#include "common/config/yaml_writer.hpp"

namespace wsn::node::acoustic {
namespace {

using common::Scenario;
using common::config::compactNumber;
using common::config::Reader;
using common::config::Section;

/// sensor_model.acoustic: a tick is a whole number (at most 100000) of detection steps.
void tickIsWholeDetectionSteps(const Reader& r, const DetectionConfig& ac, int line) {
  const double steps = ac.tick_s / ac.detection_step_s;
  if (std::abs(steps - std::round(steps)) > 1e-6 * steps || std::round(steps) > 100000.0)
    r.fail(line, "'sensor_model.acoustic.tick_s' " + compactNumber(ac.tick_s) +
                     " must be a whole number (at most 100000) of detection steps of " +
                     compactNumber(ac.detection_step_s) + " s");
}

/// sensor_model.environmental_noise: a preset, or components whose fractions add up to at most 1.
EnvironmentalNoiseConfig readNoise(const Reader& r, const common::config::Entry& entry) {
  const Section nsec = r.section(entry, environmentalNoiseTable());
  EnvironmentalNoiseConfig noise;
  const common::config::Entry* components = nsec.find("components");
  if (nsec.find("preset") != nullptr && components != nullptr)
    r.fail(nsec.line, "'sensor_model.environmental_noise' takes either 'preset' or 'components', not both");
  r.fields(nsec, environmentalNoiseTable(), noise);
  noise.components = *noisePreset(noise.preset);
  if (components == nullptr || components->value.IsNull()) return noise;
  const std::string path = "sensor_model.environmental_noise.components";
  if (!components->value.IsSequence())
    r.fail(Reader::lineOf(*components), "'" + path + "' must be a list of {fraction, duration_s}, got " +
                                            common::config::describe(components->value));
  noise.preset = "custom";
  double total = 0.0;
  common::config::forEachItem(
      r, *components, path, "{fraction, duration_s}", [&](const YAML::Node& item, int line, const std::string& p) {
        const Section c = r.item(item, line, p, noiseComponentTable());
        r.require(c, {"fraction", "duration_s"}, "share of the sensors and seconds each hears the noise");
        NoiseComponent component;
        r.fields(c, noiseComponentTable(), component);
        total += component.fraction;
        noise.components.push_back(component);
      });
  if (total > 1.0)
    r.fail(Reader::lineOf(*components),
           "the fractions of '" + path + "' add up to " + compactNumber(total) + "; expected at most 1");
  return noise;
}

/// The retarded emission time is unique only while a target is slower than its sound: a scripted
/// target's speed.
void scriptedTargetSlowerThanSound(const Reader& r, const Scenario& s, const common::TargetSpec& spec,
                                   const Section& item) {
  const auto& ac = common::settingsOf<AcousticSettings>(s.sensor_model).acoustic;
  const double target_speed = spec.topSpeed() / ac.tick_s;
  if (!(target_speed < ac.sound_speed))
    r.fail(item.line, "'" + item.path + "' moves at " + compactNumber(target_speed) +
                          " per second, not slower than the sound speed " + compactNumber(ac.sound_speed) +
                          " of 'sensor_model.acoustic'");
}

/// Born targets move at up to the speed class's bound on each axis (common/truth.cpp), and must
/// stay slower than their sound too.
void bornTargetsSlowerThanSound(const Reader& r, const Scenario& s, int line) {
  if (!(s.targets.birth_rate > 0.0)) return;
  const auto& ac = common::settingsOf<AcousticSettings>(s.sensor_model).acoustic;
  const double per_axis = s.targets.speed_class == common::SpeedClass::kSlow     ? 1.0
                          : s.targets.speed_class == common::SpeedClass::kMedium ? 2.0
                                                                                 : 5.0;
  const double fastest = per_axis * std::sqrt(2.0) / ac.tick_s;
  if (!(fastest < ac.sound_speed))
    r.fail(line, "'targets.speed_class' lets born targets move at up to " + compactNumber(fastest) +
                     " per second, not slower than the sound speed " + compactNumber(ac.sound_speed) +
                     " of 'sensor_model.acoustic'");
}

}  // namespace

std::optional<std::vector<NoiseComponent>> noisePreset(const std::string& name) {
  // An et al. 2013 §3.3.1.
  if (name == "none") return std::vector<NoiseComponent>{};
  if (name == "noise1") return std::vector<NoiseComponent>{{0.06, 0.1}};
  if (name == "noise2") return std::vector<NoiseComponent>{{0.05, 0.1}, {0.01, 0.5}};
  if (name == "noise3") return std::vector<NoiseComponent>{{0.05, 0.1}, {0.01, 1.0}};
  return std::nullopt;
}

const common::config::FieldTable<AcousticSettings>& settingsTable() {
  using C = AcousticSettings;
  using namespace common::config;
  static const FieldTable<C> table{
      "sensor_model",
      {
          real<C>("alpha", &C::alpha, openClosed(0.0, 100.0), "",
                  "α, decay exponent (An et al. 2014 eq. 3: Ps = Pt / d^α)"),
          nested<C>("acoustic", "mapping", "see below", "see below", "the acoustic detection model"),
          nested<C>("environmental_noise", "mapping", "no noise", "see below", "sporadic noise, An et al. 2013 §3.1"),
      }};
  return table;
}

const common::config::FieldTable<DetectionConfig>& detectionTable() {
  using C = DetectionConfig;
  using namespace common::config;
  static const FieldTable<C> table{
      "sensor_model.acoustic",
      {
          real<C>("threshold", &C::threshold, openClosed(0.0, 1e12), "power", "cs (γs), the sensor threshold"),
          real<C>("sound_speed", &C::sound_speed, kPositive, "length/s",
                  "Vs. Every target must be slower (the loader checks scripted ones)"),
          real<C>("detection_step_s", &C::detection_step_s, openClosed(0.0, 10.0), "s", "Δt of the detection model"),
          withNotes(real<C>("tick_s", &C::tick_s, openClosed(0.0, 1e3), "s",
                            "the duration of one tick: the fusion centre runs once per tick. Velocities stay per "
                            "tick"),
                    "(0, 1000], a whole number of detection steps"),
          real<C>("power_fluctuation", &C::power_fluctuation, closedOpen(0.0, 1.0), "",
                  "f: every emission's power is Pt (1 + f U(−1, 1)) (§5.2 studies 0, 0.2, 0.4)"),
      }};
  return table;
}

const common::config::FieldTable<EnvironmentalNoiseConfig>& environmentalNoiseTable() {
  using C = EnvironmentalNoiseConfig;
  using namespace common::config;
  static const FieldTable<C> table{
      "sensor_model.environmental_noise",
      {
          choice<C>("preset", &C::preset, {"none", "noise1", "noise2", "noise3"},
                    "the paper's noises: Noise 1 = 0.1 s on 6 % of the sensors; Noise 2 = 0.1 s on 5 % + 0.5 s on "
                    "1 %; Noise 3 = 0.1 s on 5 % + 1 s on 1 %"),
          nested<C>("components", "list of `{fraction, duration_s}`", "—",
                    "fractions in [0, 1] adding up to at most 1, durations in (0, 1e6] s",
                    "at any time `fraction` of the sensors, chosen at random, hear noise of power cs (1 + U(0, 1)) for "
                    "`duration_s` (rounded to whole ticks, at least one)"),
      }};
  return table;
}

const common::config::FieldTable<NoiseComponent>& noiseComponentTable() {
  using C = NoiseComponent;
  using namespace common::config;
  static const FieldTable<C> table{
      "sensor_model.environmental_noise.components[]",
      {
          real<C>("fraction", &C::fraction, kProbability, "", "share of the sensors that hear the noise at any time"),
          real<C>("duration_s", &C::duration_s, openClosed(0.0, 1e6), "s", "how long each of them hears it"),
      }};
  return table;
}

SensorModelSettingsSpec settingsSpec() {
  SensorModelSettingsSpec spec;
  spec.keys = settingsTable().sortedKeys();
  spec.target_keys = {"sensing_range"};
  spec.read = [](const Reader& r, const Section* given, Scenario&) {
    auto settings = std::make_shared<AcousticSettings>();
    if (given == nullptr) return std::shared_ptr<const common::SensorModelSettings>(std::move(settings));
    r.fields(*given, settingsTable(), *settings);
    if (const common::config::Entry* a = given->find("acoustic")) {
      const Section asec = r.section(*a, detectionTable());
      r.fields(asec, detectionTable(), settings->acoustic);
      tickIsWholeDetectionSteps(r, settings->acoustic, asec.line);
    }
    if (const common::config::Entry* n = given->find("environmental_noise"))
      settings->environmental_noise = readNoise(r, *n);
    return std::shared_ptr<const common::SensorModelSettings>(std::move(settings));
  };
  spec.write = [](std::ostream& out, const Scenario& s) {
    using namespace common::config;
    const auto& settings = common::settingsOf<AcousticSettings>(s.sensor_model);
    writeFields(out, "  ", settingsTable(), settings, s.derived);
    out << "  acoustic:\n";
    writeFields(out, "    ", detectionTable(), settings.acoustic);
    out << "  environmental_noise:\n";
    if (settings.environmental_noise.preset != "custom")
      writeFields(out, "    ", environmentalNoiseTable(), settings.environmental_noise);
    else
      writeList(out, "    ", "components", noiseComponentTable(), settings.environmental_noise.components);
  };
  spec.check_target = scriptedTargetSlowerThanSound;
  spec.check_targets = bornTargetsSlowerThanSound;
  spec.key_tables = [] {
    using common::config::keyTable;
    return std::vector<common::config::KeyTable>{
        keyTable("sensor_model acoustic_doppler", "sensor_model", settingsTable()),
        keyTable("sensor_model.acoustic", "sensor_model.acoustic", detectionTable()),
        keyTable("sensor_model.environmental_noise", "sensor_model.environmental_noise", environmentalNoiseTable()),
    };
  };
  return spec;
}

}  // namespace wsn::node::acoustic
