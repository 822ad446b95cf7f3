// The network between sensors and supernodes (Oh et al. §V): decides for every report whether
// it is lost and how many ticks it is delayed, and holds it until its delivery tick.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "common/faults.hpp"
#include "common/messages.hpp"
#include "network_model/topology.hpp"

namespace wsn::network_model {

/// What the router reads of a run: the link model of Oh §V and the run's limits. Built from a
/// scenario by routerConfig() (network_model/role_config.hpp); defaults are the scenario's.
struct RouterConfig {
  double pte = 0.3;               ///< transmission failure rate per edge
  double pde = 0.3;               ///< per-hop delay rate
  std::int32_t run_ticks = 100;   ///< T: a report due after tick T is counted after_end, never delivered
  std::int32_t window_size = 10;  ///< ws, in ticks: delays d >= ws are counted beyond_window
  std::uint64_t seed = 1;         ///< keys the loss and delay streams
  /// The scenario's faults: burst losses replace pte for their ticks, and a report due at a
  /// supernode that is dead by then is lost with it.
  common::FaultPlan faults{};
  friend bool operator==(const RouterConfig&, const RouterConfig&) = default;
};

/// What became of one report (one row of the run directory's observations.csv).
struct ReportFate {
  common::Report report;
  std::uint32_t supernode = 0;  ///< g(i)
  std::int32_t hops = -1;       ///< |sp(i)|; -1 when the sensor has no path (then lost is true)
  bool lost = false;            ///< transmission failure, or no path at all
  std::int32_t delay = -1;      ///< extra ticks d (saturated at INT32_MAX); -1 when lost
  std::int32_t tick_delivered = -1;  ///< tick + delay; -1 if lost or after the run's end
  bool to_dead_supernode = false;    ///< lost because g(i) is dead at the tick it was due (faults)
  friend bool operator==(const ReportFate&, const ReportFate&) = default;
};

/// Report counters. Every accepted report is in exactly one of lost, unreachable, delivered,
/// after_end and lost_dead_supernode; delayed counts delivered reports with d > 0 and beyond_window those
/// delivered with d >= window_size (a supernode's window cannot place them).
struct NetworkCounts {
  std::uint64_t sent = 0;           ///< accepted reports
  std::uint64_t lost = 0;           ///< transmission failed, probability 1 - pts
  std::uint64_t unreachable = 0;    ///< no path to the supernode
  std::uint64_t delivered = 0;      ///< handed to the supernode at tick + d <= run.ticks
  std::uint64_t delayed = 0;        ///< delivered with d > 0
  std::uint64_t beyond_window = 0;  ///< delivered with d >= window_size
  std::uint64_t after_end = 0;      ///< not lost, but tick + d > run.ticks
  std::uint64_t lost_dead_supernode = 0;  ///< due at a supernode that a fault killed or paused by then
  std::uint64_t rejected = 0;       ///< malformed (wrong tick, unknown sensor, non-finite position,
                                    ///< measurement not common::wellFormed); total only
  NetworkCounts& operator+=(const NetworkCounts& other);
  friend bool operator==(const NetworkCounts&, const NetworkCounts&) = default;
};

/// Routes reports to supernodes under the loss and delay model of Oh et al. §V. Each report's
/// fate is drawn from its own streams, Stream(seed, kNetworkLoss, sensor, tick) and
/// Stream(seed, kNetworkDelay, sensor, tick), so outcomes do not depend on arrival order,
/// batching or process layout. Call order per tick t: submit(t, ...), then deliveriesDue(t, j)
/// for every supernode j. The topology must outlive the router.
class Router {
 public:
  Router(const RouterConfig& config, const Topology& topology);

  /// The configuration it routes with (network.json records pte and pde from it).
  const RouterConfig& config() const { return config_; }

  /// A supernode lost outside the scenario (killed by hand), seen at `from_tick`: what is pending
  /// for it is lost with it (moved from delivered to lost_dead_supernode), and nothing due from
  /// then on is routed to it. Rows of observations.csv written before keep the fate they had.
  void loseSupernode(std::uint32_t supernode, std::int32_t from_tick);

  /// Routes the next ticks over `topology` (a fault changed the live supernodes): the same
  /// sensors and supernode indices, other groups and hop counts. It must outlive the router.
  void useTopology(const Topology& topology);
  const Topology& topology() const { return *topology_; }

  /// Routes all reports generated at `tick` (any order, possibly concatenated from several
  /// tiles; they are put in canonical order first) and returns their fates in that order.
  /// Malformed reports are counted as rejected and get no fate. Ticks must strictly increase
  /// from call to call (std::logic_error otherwise), so a tick cannot be routed twice.
  std::span<const ReportFate> submit(std::int32_t tick, std::span<const common::Report> reports);

  /// Removes and returns the observations supernode j receives at `tick`, ordered by
  /// (tick_generated, sensor). std::logic_error if `tick` was not submitted yet (its d = 0
  /// reports would be missed); std::out_of_range for an unknown supernode.
  std::vector<common::Observation> deliveriesDue(std::int32_t tick, std::uint32_t supernode);

  /// Fates of the reports of `tick` in canonical order (empty if none or forgotten).
  std::span<const ReportFate> fatesOf(std::int32_t tick) const;
  /// Frees the fates of ticks before `tick` once they were written out.
  void forgetFatesBefore(std::int32_t tick);

  /// Totals over all supernodes.
  const NetworkCounts& counts() const { return total_; }
  /// Counts of supernode j's tracking group (rejected stays 0 here).
  const NetworkCounts& counts(std::uint32_t supernode) const { return per_supernode_.at(supernode); }
  /// Delivered observations not yet taken by deliveriesDue().
  std::size_t pendingCount() const { return pending_count_; }
  /// The last tick passed to submit() (INT32_MIN before the first).
  std::int32_t lastSubmittedTick() const { return last_tick_; }

 private:
  const Topology* topology_;
  RouterConfig config_;
  /// pts(pte, k) for k = 0 .. maxHops of the current topology, at the pte of the tick routed.
  void prepareLinks(double pte);
  /// total_ as the sum of the groups' counts (rejected is counted in total_ alone).
  void recountTotal();
  std::vector<double> success_by_hops_;
  double links_pte_ = -1.0;  // the pte success_by_hops_ holds
  std::int32_t last_tick_;
  std::map<std::int32_t, std::vector<ReportFate>> fates_;
  std::vector<std::map<std::int32_t, std::vector<common::Observation>>> pending_;  // [supernode][tick]
  std::size_t pending_count_ = 0;
  NetworkCounts total_;
  std::vector<NetworkCounts> per_supernode_;
};

}  // namespace wsn::network_model
