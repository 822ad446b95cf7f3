#include "network_model/live_topologies.hpp"

namespace wsn::network_model {

LiveTopologies::LiveTopologies(TopologyConfig config, std::span<const common::Vec2> sensors)
    : config_(std::move(config)), sensors_(sensors.begin(), sensors.end()) {
  full_ = &at(std::vector<bool>(config_.supernodes.size(), true));
}

const Topology& LiveTopologies::at(const std::vector<bool>& live) {
  auto& slot = built_[live];
  if (!slot) {
    TopologyConfig config = config_;
    config.live_supernodes = live;
    slot = std::make_unique<Topology>(config, sensors_);
  }
  return *slot;
}

Rehome rehomeOf(const Topology& before, const Topology& after, std::uint32_t dead, std::int32_t tick) {
  Rehome r;
  r.supernode = dead;
  r.tick = tick;
  double hops_before = 0.0;
  double hops_after = 0.0;
  for (common::SensorId i = 0; i < before.sensorCount(); ++i) {
    if (before.supernodeOf(i) != dead) continue;
    ++r.sensors;
    ++r.adopters[after.supernodeOf(i)];
    if (before.hops(i) >= 0) {
      ++r.reachable_before;
      hops_before += before.hops(i);
    }
    if (after.hops(i) >= 0) {
      ++r.reachable_after;
      hops_after += after.hops(i);
    }
  }
  r.mean_hops_before = r.reachable_before == 0 ? 0.0 : hops_before / static_cast<double>(r.reachable_before);
  r.mean_hops_after = r.reachable_after == 0 ? 0.0 : hops_after / static_cast<double>(r.reachable_after);
  return r;
}

}  // namespace wsn::network_model
