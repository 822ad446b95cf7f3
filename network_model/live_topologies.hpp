// The communication graph of every set of live supernodes a run's faults produce (Oh §V's g(i)
// and hop counts over the survivors), each built once, and what re-homing a dead supernode's
// tracking group did to its sensors.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "network_model/topology.hpp"

namespace wsn::network_model {

/// Topologies by live-supernode mask; the all-live one is built at once, the others on first use.
class LiveTopologies {
 public:
  LiveTopologies(TopologyConfig config, std::span<const common::Vec2> sensors);
  /// G over the supernodes `live` marks (one flag per supernode of the scenario).
  const Topology& at(const std::vector<bool>& live);
  /// G with every supernode live: the scenario's own topology.
  const Topology& full() const { return *full_; }

 private:
  TopologyConfig config_;
  std::vector<common::Vec2> sensors_;
  const Topology* full_ = nullptr;
  std::map<std::vector<bool>, std::unique_ptr<Topology>> built_;
};

/// What became of a dead supernode's tracking group when it was re-homed.
struct Rehome {
  std::uint32_t supernode = 0;
  std::int32_t tick = 0;             ///< the first tick routed over the survivors
  std::size_t sensors = 0;           ///< the group's size before
  std::size_t reachable_before = 0;  ///< of them, with a path to the dead supernode
  std::size_t reachable_after = 0;   ///< with a path to their new supernode
  std::map<std::uint32_t, std::size_t> adopters;  ///< new supernode -> sensors it took over
  double mean_hops_before = 0.0;     ///< over the group's reachable sensors
  double mean_hops_after = 0.0;
};

/// Compares supernode `dead`'s group in `before` with where its sensors belong in `after`.
Rehome rehomeOf(const Topology& before, const Topology& after, std::uint32_t dead, std::int32_t tick);

}  // namespace wsn::network_model
