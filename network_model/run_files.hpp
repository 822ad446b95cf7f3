// The network model's files in a run directory (observations.csv rows and network.json), as pure
// functions of what the router decided: no DDS, so that the formats are unit-tested on their own.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "network_model/live_topologies.hpp"
#include "network_model/router.hpp"
#include "network_model/topology.hpp"

namespace wsn::network_model {

/// The header of observations.csv: one row per report, in the order the router decided them;
/// `level` is the report's power_level (An eq. 4's ws, ADMAN's 3 inside or 1 in between, the
/// magnetometer's floor D; 0 for a fused report of eq. 6).
inline constexpr const char* kObservationsHeader =
    "tick_generated,tick_delivered,sensor,supernode,hops,delay,x,y,target,fate,level";

/// One observations.csv row; its fate reads delivered, lost, unreachable or after_end.
std::string observationRow(const ReportFate& fate);

/// What network.json records of a run: the model's settings and what became of the reports.
struct NetworkReport {
  double communication_range = 0;
  double pte = 0;
  double pde = 0;
  double mean_hops = 0;
  std::int32_t max_hops = 0;
  NetworkCounts total;
  std::vector<NetworkCounts> per_supernode;  ///< index = supernode id
  /// Written only for a run with faults, so that a run without them keeps its file as it was.
  bool with_faults = false;
  std::uint64_t silent_tile_ticks = 0;  ///< tile-ticks that sent nothing: a tile dead or paused
  std::vector<Rehome> rehomes;          ///< every supernode death, in tick order
};

/// The report of a run once the router has seen its last tick. The settings are read back from
/// the topology and the router, so the file records what was simulated.
NetworkReport networkReport(const Topology& topology, const Router& router);

/// The observations.csv fate of a report lost to a dead supernode.
inline constexpr const char* kDeadSupernodeFate = "dead_supernode";
/// Every fate an observations.csv row can have (observationRow), for the catalogue.
inline constexpr const char* kObservationFates[] = {"delivered", "lost", "unreachable", "after_end", kDeadSupernodeFate};

/// A number of network.json that sweeps tabulate and plot (`wsntrack components --json` lists them).
struct NetworkQuantity {
  const char* name;     ///< a sweep's metric name
  const char* title;    ///< its column title in a sweep's tables
  const char* label;    ///< a figure's axis label
  const char* key;      ///< its key in network.json
  const char* meaning;
};
/// The quantities of networkJson() worth a sweep's table or axis, in the catalogue's order.
const std::vector<NetworkQuantity>& networkQuantities();

/// network.json: the report, its loss and delay ratios as Oh §VII-E counts them, and the paper's
/// §VII-E counts as a reference named after the scenario they belong to (the paper's own example).
std::string networkJson(const NetworkReport& report);

}  // namespace wsn::network_model
