// Faults a scenario injects into its own cluster (the `faults:` section) and what they mean tick by
// tick: which node tiles and supernodes are live, which supernodes own a tracking group, which
// handoffs a partition cuts, what the per-hop loss rate is. Every role reads the same plan, so a
// fault takes effect at the same tick everywhere and outputs stay a function of (scenario, seed).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace wsn::common {

/// What a fault does. The order is the scenario's choice list (common/scenario_schema.cpp).
enum class FaultAction {
  kKill,       ///< the process dies at `tick` for good
  kPause,      ///< the process stops for `ticks` ticks, then comes back
  kPartition,  ///< handoffs between two supernodes are lost for `ticks` ticks
  kBurstLoss,  ///< every hop fails with probability `pte` for `ticks` ticks
  kRestart,    ///< a new process takes a killed supernode's place from `tick` on, afresh
};

/// Which processes a kill or a pause can hit: the ones a deployment loses. The network model
/// and the aggregator are the simulation's own machinery; losing them ends the run.
enum class FaultRole { kNode, kSupernode };

/// One item of `faults:`.
struct FaultSpec {
  std::int32_t tick = 1;  ///< the first tick the fault holds
  FaultAction action = FaultAction::kKill;
  FaultRole role = FaultRole::kSupernode;  ///< kill, pause, restart
  std::int32_t index = 0;                  ///< kill, pause, restart: the tile or supernode index
  std::int32_t ticks = 0;                  ///< pause, partition, burst_loss: how long it holds
  double pte = 0.0;                        ///< burst_loss: the per-hop failure rate meanwhile
  std::vector<std::int32_t> between;       ///< partition: the two supernodes
  /// kill: 0 when the scenario names `index`; else the item killed `count` processes drawn from
  /// the run's seed, and this is one of them (the loader expands the item into `count` kills).
  std::int32_t count = 0;
  friend bool operator==(const FaultSpec&, const FaultSpec&) = default;

  static FaultSpec kill(FaultRole role, std::int32_t index, std::int32_t tick);
  static FaultSpec pause(FaultRole role, std::int32_t index, std::int32_t tick, std::int32_t ticks);
  static FaultSpec partition(std::int32_t a, std::int32_t b, std::int32_t tick, std::int32_t ticks);
  static FaultSpec burstLoss(double pte, std::int32_t tick, std::int32_t ticks);
  static FaultSpec restart(FaultRole role, std::int32_t index, std::int32_t tick);

  /// True for the faults that stop a process: kill and pause.
  bool stopsProcess() const { return action == FaultAction::kKill || action == FaultAction::kPause; }
  /// The last tick the fault holds (a kill holds to the end of any run, unless a restart ends it:
  /// see FaultPlan::killEnds; a restart holds at its tick).
  std::int32_t lastTick() const;
  /// "kill of supernode 2 at tick 40": how messages and metrics.json name it.
  std::string describe() const;
};

/// `count` of the indices `eligible`, drawn without replacement from the run's seed (the stream of
/// the `item`-th fault of the list), ascending: the processes a `kill` with `count` takes.
std::vector<std::int32_t> drawProcesses(std::uint64_t seed, std::size_t item, std::vector<std::int32_t> eligible,
                                        std::int32_t count);

/// "kill", "pause", ... and "node", "supernode": the scenario's names.
const char* faultActionName(FaultAction action);
const char* faultRoleName(FaultRole role);

/// The faults of a run as the roles see them: who is live at a tick, who owns a tracking group.
/// A supernode that comes back after a pause or a restart starts afresh (its group is handed back to it by
/// the supernodes that adopted it, through ordinary handoffs).
class FaultPlan {
 public:
  FaultPlan() = default;
  FaultPlan(std::vector<FaultSpec> faults, std::int32_t tiles, std::int32_t supernodes);

  /// True without scheduled faults and without processes lost by hand.
  bool empty() const { return faults_.empty() && lost_.empty(); }
  const std::vector<FaultSpec>& faults() const { return faults_; }

  /// A tile or supernode lost outside the scenario (killed by hand): dead from `from_tick` on, as
  /// the role holding this plan saw it go. Its death is not scheduled, so supernodeDies and
  /// dyingAt leave it out (nobody waits for its orphans); every liveness query counts it.
  void loseUnscheduled(FaultRole role, std::int32_t index, std::int32_t from_tick);
  /// The processes lost by hand, as kills at the tick each was lost from.
  const std::vector<FaultSpec>& lostUnscheduled() const { return lost_; }

  bool tileLive(std::int32_t tile, std::int32_t tick) const;
  bool supernodeLive(std::int32_t supernode, std::int32_t tick) const;
  /// The supernodes live at `tick`, as a mask over every supernode: the tracking groups of that
  /// tick are the Voronoi cells of these (Oh §V's g(i) over the live supernodes).
  std::vector<bool> liveSupernodes(std::int32_t tick) const;
  /// True when the supernode is live at `tick` but was not at tick - 1: it starts afresh there.
  bool supernodeReturns(std::int32_t supernode, std::int32_t tick) const;
  /// True when the supernode was live at tick - 1 and is not at `tick`: its group is re-homed and
  /// its last tracks are adopted at `tick`.
  bool supernodeDies(std::int32_t supernode, std::int32_t tick) const;
  /// The supernodes whose group is re-homed at `tick` (supernodeDies), in index order.
  std::vector<std::int32_t> dyingAt(std::int32_t tick) const;
  /// True when handoffs written at `tick` from one of the two supernodes to the other are lost.
  bool partitioned(std::int32_t a, std::int32_t b, std::int32_t tick) const;
  /// The per-hop failure rate a burst loss imposes on reports made at `tick`; none outside bursts
  /// (the highest of overlapping bursts).
  std::optional<double> burstPte(std::int32_t tick) const;
  /// Whether the supernode settles `tick` (reports its estimate of the tick once it left its
  /// window, or at the run's end): only when it is live from `tick` until then, since a tracker
  /// that dies or restarts in between takes its window with it.
  bool settles(std::int32_t supernode, std::int32_t tick, std::int32_t window_size, std::int32_t run_ticks) const;
  /// The live tiles at `tick`.
  std::int32_t liveTileCount(std::int32_t tick) const;
  /// The indices of the tiles and of the supernodes live at `tick`, ascending.
  std::vector<std::uint32_t> liveTiles(std::int32_t tick) const;
  std::vector<std::uint32_t> liveSupernodeIndices(std::int32_t tick) const;
  /// The ticks a process stops at: the ticks at which a kill or pause of it begins.
  std::optional<FaultSpec> processFaultAt(FaultRole role, std::int32_t index, std::int32_t tick) const;
  /// The supernodes a restart brings back at `tick` (new processes, which producers wait for
  /// before they write what the newcomer reads), in index order.
  std::vector<std::uint32_t> restartsAt(std::int32_t tick) const;
  /// The first tick of the process that is `role` `index` at `tick`: 1, or the tick of the last
  /// restart of it up to `tick`. Names a process incarnation (dds::roleIdentity).
  std::int32_t incarnation(FaultRole role, std::int32_t index, std::int32_t tick) const;
  /// The first tick a kill no longer holds: its process's next restart, if any.
  std::optional<std::int32_t> killEnds(const FaultSpec& kill) const;
  /// The tick of the first restart of `role` `index` after `tick`, if any.
  std::optional<std::int32_t> restartAfter(FaultRole role, std::int32_t index, std::int32_t tick) const;
  /// Whether the scenario restarts any process.
  bool hasRestarts() const { return has_restarts_; }

  friend bool operator==(const FaultPlan&, const FaultPlan&) = default;

 private:
  bool live(FaultRole role, std::int32_t index, std::int32_t tick) const;
  bool scheduledLive(FaultRole role, std::int32_t index, std::int32_t tick) const;
  std::vector<FaultSpec> faults_;
  std::vector<std::int32_t> last_tick_;  ///< per fault: the last tick a kill or pause holds
  bool has_restarts_ = false;
  std::vector<FaultSpec> lost_;
  std::int32_t tiles_ = 0;
  std::int32_t supernodes_ = 0;
};

}  // namespace wsn::common
