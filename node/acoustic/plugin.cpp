#include "node/acoustic/plugin.hpp"

#include "node/acoustic/acoustic_field.hpp"
#include "node/acoustic/config.hpp"

namespace wsn::node::acoustic {
namespace {

/// Acoustic sensors report straight to the fusion centre (An et al. 2014 §2): no readings are
/// exchanged between tiles, each tile publishes its sensors' raw detections.
class AcousticTile final : public TileSensors {
 public:
  explicit AcousticTile(const TileContext& context)
      : field_(fieldConfigOf(context.sensor_model, context.seed, context.scripted_targets), context.layout, context.tile, context.truth) {}

  bool exchangesReadings() const override { return false; }
  std::vector<common::SensorReading> sense(std::int32_t) override { return {}; }
  std::vector<common::Report> report(std::int32_t tick, std::span<const common::SensorReading>) override {
    return field_.detect(tick);
  }

 private:
  AcousticField field_;
};

}  // namespace

SensorModelSpec sensorModelSpec() {
  return {"acoustic_doppler",
          "An et al. 2014 eq. (1)-(4): sensors hear the targets' sound with the Doppler effect and report "
          "(id, floor(Ps / cs)) when Ps >= cs, under the sporadic environmental noise of An et al. 2013",
          {"position"},
          settingsSpec(),
          [](const TileContext& context) -> std::unique_ptr<TileSensors> {
            return std::make_unique<AcousticTile>(context);
          }};
}

}  // namespace wsn::node::acoustic
