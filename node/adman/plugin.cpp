#include "node/adman/plugin.hpp"

#include "node/adman/adman_field.hpp"
#include "node/adman/config.hpp"

namespace wsn::node::adman {
namespace {

/// Readings, then attachments and MLMC with the readings of the other tiles near the shared sides.
class AdmanTile final : public TileSensors {
 public:
  explicit AdmanTile(const TileContext& context)
      : field_(common::settingsOf<AdmanSettings>(context.sensor_model), context.seed, context.layout, context.tile,
               context.truth) {}

  bool exchangesReadings() const override { return true; }

  std::vector<common::SensorReading> sense(std::int32_t tick) override {
    own_ = field_.read(tick);
    return field_.boundaryReadings(own_);
  }

  std::vector<common::Report> report(std::int32_t tick, std::span<const common::SensorReading> foreign) override {
    return field_.report(tick, own_, foreign);
  }

 private:
  AdmanField field_;
  std::vector<common::SensorReading> own_;  ///< this tick's readings, between sense() and report()
};

}  // namespace

SensorModelSpec sensorModelSpec() {
  return {"adman",
          "ADMAN: received signal strength in dB of every target (eq. 1); a two-stage GLRT per sensor tells a "
          "target within r0 from one in between (eqs. 2-13), attach rules resolve neighbours, and Maximum "
          "Likelihood Monte Carlo places each detected target (eq. 15, factorised or joint)",
          {"position"},
          settingsSpec(),
          [](const TileContext& context) -> std::unique_ptr<TileSensors> { return std::make_unique<AdmanTile>(context); }};
}

}  // namespace wsn::node::adman
