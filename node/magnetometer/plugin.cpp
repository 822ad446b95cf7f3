#include "node/magnetometer/plugin.hpp"

#include "node/magnetometer/config.hpp"
#include "node/magnetometer/magnetometer_field.hpp"

namespace wsn::node::magnetometer {
namespace {

/// Oh §VIII does not fuse the testbed's readings by eq. (6) ("to retain enough distinct data
/// points to form meaningful tracks"): each detecting sensor reports its own position, so no
/// readings cross tile edges.
class MagnetometerTile final : public TileSensors {
 public:
  explicit MagnetometerTile(const TileContext& context)
      : field_(fieldConfigOf(context.sensor_model, context.seed), context.layout, context.tile, context.truth) {}

  bool exchangesReadings() const override { return false; }
  std::vector<common::SensorReading> sense(std::int32_t) override { return {}; }
  std::vector<common::Report> report(std::int32_t tick, std::span<const common::SensorReading>) override {
    return field_.detect(tick);
  }

 private:
  MagnetometerField field_;
};

}  // namespace

SensorModelSpec sensorModelSpec() {
  return {"magnetometer",
          "Oh et al. 2005 §VIII: two-axis magnetometers sampled within each tick report their own position when "
          "eq. (11), the mean size of the field's sample-to-sample change over W samples, exceeds eta; a magnet is "
          "a vertical dipole, the bias drifts and jumps (false alarms)",
          {"position"},
          settingsSpec(),
          [](const TileContext& context) -> std::unique_ptr<TileSensors> {
            return std::make_unique<MagnetometerTile>(context);
          }};
}

}  // namespace wsn::node::magnetometer
