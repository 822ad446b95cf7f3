// The communication graph of Oh et al. §V: which supernode each sensor reports to (nearest,
// g(i)) and over how many hops (shortest path |sp(i)|), computed once per run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"

namespace wsn::network_model {

/// What the communication graph is built from besides the sensors: where the supernodes sit
/// and the radio range. Built from a scenario by topologyConfig() (network_model/role_config.hpp).
struct TopologyConfig {
  std::vector<common::Vec2> supernodes;
  double communication_range = 11.6;  ///< the scenario's calibrated default (docs/NETWORK.md)
  /// Which supernodes are live (a fault killed or paused the others); empty: all of them. A dead
  /// supernode is no node of G: it neither owns a group nor relays.
  std::vector<bool> live_supernodes{};
  friend bool operator==(const TopologyConfig&, const TopologyConfig&) = default;
};

/// Oh et al. §V: G has a node per sensor (true position) and per supernode, and an edge iff
/// two nodes are at most communication_range apart (compared on squared distances). Each
/// sensor i belongs to its nearest supernode g(i) (ties go to the lower supernode index) and
/// reports over a shortest path in G to g(i), which may pass through any node, including
/// sensors of other groups and other supernodes. A sensor with no such path is unreachable.
/// Supernodes that TopologyConfig::live_supernodes marks dead are left out of G and of g(i);
/// indices stay those of the scenario, and a dead supernode's group is empty.
class Topology {
 public:
  /// Builds G over the given true sensor positions (sensor i at sensors[i]; a run passes
  /// SensorLayout::truePositions()). Throws std::invalid_argument without a live supernode.
  Topology(const TopologyConfig& config, std::span<const common::Vec2> sensors);

  /// Number of sensors (ids 0 .. sensorCount() - 1).
  std::size_t sensorCount() const { return supernode_of_.size(); }
  /// Number of supernodes.
  std::uint32_t supernodeCount() const { return static_cast<std::uint32_t>(supernodes_.size()); }
  /// Position of supernode j.
  common::Vec2 supernodePosition(std::uint32_t j) const { return supernodes_[j]; }
  /// The radio range that defines the edges of G.
  double communicationRange() const { return range_; }

  /// g(i): index of the nearest supernode (lowest index among equally near ones).
  std::uint32_t supernodeOf(common::SensorId sensor) const { return supernode_of_[sensor]; }
  /// |sp(i)|: hops on a shortest path from sensor i to g(i); -1 when there is none.
  std::int32_t hops(common::SensorId sensor) const { return hops_[sensor]; }
  /// hops() of every sensor, indexed by id.
  std::span<const std::int32_t> allHops() const { return hops_; }
  /// Number of sensors with g(i) = j (reachable or not): the size of j's tracking group.
  std::size_t groupSize(std::uint32_t j) const { return group_size_[j]; }

  /// Sensors with a path to their supernode.
  std::size_t reachableCount() const { return sensorCount() - unreachable_; }
  /// Sensors without a path to their supernode; their reports are always lost.
  std::size_t unreachableCount() const { return unreachable_; }
  /// histogram[k] = number of sensors at k hops (k >= 1; index 0 stays 0).
  const std::vector<std::size_t>& hopHistogram() const { return histogram_; }
  /// Mean hop count over reachable sensors (0 when none is reachable).
  double meanHops() const;
  /// Largest hop count of a reachable sensor (0 when none is reachable).
  std::int32_t maxHops() const { return static_cast<std::int32_t>(histogram_.size()) - 1; }

 private:
  void build(std::span<const common::Vec2> sensors);

  std::vector<common::Vec2> supernodes_;
  std::vector<std::uint32_t> live_;  ///< indices of the live supernodes, ascending
  double range_ = 0.0;
  std::vector<std::uint32_t> supernode_of_;
  std::vector<std::int32_t> hops_;
  std::vector<std::size_t> group_size_;
  std::vector<std::size_t> histogram_;
  std::size_t unreachable_ = 0;
};

}  // namespace wsn::network_model
