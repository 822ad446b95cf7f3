#include "network_model/calibration.hpp"

#include <algorithm>
#include <cmath>

#include "common/scenario_config.hpp"
#include "common/sensor_layout.hpp"
#include "network_model/link_model.hpp"

namespace wsn::network_model {

ExpectedRatios expectedRatios(const Topology& topology, double pte, double pde, std::int32_t window_size) {
  ExpectedRatios ratios;
  const auto sensors = static_cast<double>(topology.sensorCount());
  if (sensors == 0.0) return ratios;
  const auto& histogram = topology.hopHistogram();
  double received = 0.0;
  double delayed = 0.0;
  double delayed_in_window = 0.0;
  ratios.arrived_by_lag.assign(static_cast<std::size_t>(std::max(window_size, 1)), 0.0);
  for (std::size_t k = 1; k < histogram.size(); ++k) {
    if (histogram[k] == 0) continue;
    const auto weight = static_cast<double>(histogram[k]) / sensors;
    const int hops = static_cast<int>(k);
    const double pts = successProbability(pte, hops);
    // Oh et al. eq. (7): P(d = 0) = (1 - pde)^k.
    const double on_time = delayProbability(pde, hops, 0);
    received += weight * pts;
    delayed += weight * pts * (1.0 - on_time);
    delayed_in_window += weight * pts * (delayProbabilityBelow(pde, hops, window_size) - on_time);
    for (std::size_t lag = 0; lag < ratios.arrived_by_lag.size(); ++lag)
      ratios.arrived_by_lag[lag] += weight * pts * delayProbabilityBelow(pde, hops, static_cast<std::int64_t>(lag) + 1);
  }
  for (double& arrived : ratios.arrived_by_lag) arrived = std::clamp(arrived, 0.0, 1.0);
  // The weights sum to 1 only up to rounding; keep the ratio inside [0, 1].
  ratios.lost_to_total = std::clamp(1.0 - received, 0.0, 1.0);
  ratios.delayed_to_total = delayed;
  ratios.delayed_to_received = received > 0.0 ? delayed / received : 0.0;
  ratios.delayed_in_window_to_total = delayed_in_window;
  return ratios;
}

double paperMismatch(const ExpectedRatios& ratios) {
  const double lost = kPaperLost / kPaperReports;
  const double delayed = kPaperDelayed / kPaperReceived;
  const double lost_variance = lost * (1.0 - lost) / kPaperReports;
  const double delayed_variance = delayed * (1.0 - delayed) / kPaperReceived;
  const double dl = ratios.lost_to_total - lost;
  const double dd = ratios.delayed_to_received - delayed;
  return dl * dl / lost_variance + dd * dd / delayed_variance;
}

TopologyConfig ohTopologyConfig(double communication_range, SupernodePlacement placement) {
  TopologyConfig config;
  if (placement == SupernodePlacement::kQuadrants)
    config.supernodes = {{25.0, 25.0}, {75.0, 25.0}, {25.0, 75.0}, {75.0, 75.0}};
  else
    config.supernodes = {{50.0, 50.0}};
  config.communication_range = communication_range;
  return config;
}

Topology ohCalibrationTopology(double communication_range, SupernodePlacement placement) {
  // The grid comes from SensorLayout so that it stays the one a run with these settings uses.
  common::SensorFieldConfig grid;
  grid.region = {0.0, 0.0, 100.0, 100.0};
  grid.sensors.kind = common::SensorLayoutConfig::Kind::kGrid;
  grid.sensors.spacing = 1.0;
  const common::SensorLayout layout(grid);
  return Topology(ohTopologyConfig(communication_range, placement), layout.truePositions());
}

}  // namespace wsn::network_model
