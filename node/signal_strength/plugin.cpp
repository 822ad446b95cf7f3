#include "node/signal_strength/plugin.hpp"

#include "node/signal_strength/config.hpp"
#include "node/signal_strength/sensor_field.hpp"

namespace wsn::node::signal_strength {
namespace {

/// Detection then the 2 Rs election with the readings of the other tiles near the shared edges.
class SignalStrengthTile final : public TileSensors {
 public:
  explicit SignalStrengthTile(const TileContext& context)
      : truth_(context.truth), field_(common::settingsOf<SignalStrengthSettings>(context.sensor_model), context.sensor_model.sensing_range,
               context.seed, context.layout, context.tile) {}

  bool exchangesReadings() const override { return true; }

  std::vector<common::SensorReading> sense(std::int32_t tick) override {
    own_ = field_.detect(tick, truth_.at(tick));
    return field_.boundaryReadings(own_);
  }

  std::vector<common::Report> report(std::int32_t tick, std::span<const common::SensorReading> foreign) override {
    return field_.fuse(tick, own_, foreign, truth_.at(tick));
  }

 private:
  const common::Truth& truth_;
  SensorField field_;
  std::vector<common::SensorReading> own_;  ///< this tick's readings, between sense() and report()
};

}  // namespace

SensorModelSpec sensorModelSpec() {
  return {"signal_strength",
          "Oh et al. eq. (5): z = beta / (1 + gamma d^alpha) + w within Rs, detection when z >= eta; each "
          "detecting sensor that beats its neighbours within 2 Rs reports their z-weighted centre of mass (eq. 6)",
          {"position"},
          settingsSpec(),
          [](const TileContext& context) -> std::unique_ptr<TileSensors> {
            return std::make_unique<SignalStrengthTile>(context);
          }};
}

}  // namespace wsn::node::signal_strength
