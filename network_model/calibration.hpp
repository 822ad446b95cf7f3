// Expected loss and delay ratios of a topology under Oh et al. §V, used to calibrate the default
// communication range against the paper's Fig. 6 and the counts of its §VII-E example.
#pragma once

#include <cstdint>
#include <vector>

#include "network_model/topology.hpp"

namespace wsn::network_model {

/// Oh et al. §VII-E at pte = pde = 0.3: 1174 reports, 319 lost, 449 of the 855 received delayed.
inline constexpr double kPaperReports = 1174.0;
inline constexpr double kPaperLost = 319.0;
inline constexpr double kPaperReceived = 855.0;
inline constexpr double kPaperDelayed = 449.0;

/// Ratios expected when every sensor sends one report (uniform average over sensors;
/// unreachable sensors count as lost).
struct ExpectedRatios {
  double lost_to_total = 0.0;        ///< E[1 - pts]
  double delayed_to_total = 0.0;     ///< E[pts (1 - (1-pde)^k)]
  double delayed_to_received = 0.0;  ///< E[pts (1 - (1-pde)^k)] / E[pts]
  /// E[pts P(1 <= d < ws)]: delayed but still inside the window (Fig. 6 right, dotted).
  double delayed_in_window_to_total = 0.0;
  /// E[pts P(d <= j)] for j = 0 .. ws - 1: a report made at tick t is at its supernode by tick
  /// t + j. What an engine deciding at the newest tick sees of the last ticks' reports.
  std::vector<double> arrived_by_lag;
};

/// Oh et al. §V, eq. (7) averaged over the topology's hop histogram.
ExpectedRatios expectedRatios(const Topology& topology, double pte, double pde, std::int32_t window_size);

/// Chi-square distance of (lost_to_total, delayed_to_received) from the §VII-E counts, each
/// term scaled by its binomial variance at the paper's sample size (1174 resp. 855 reports).
double paperMismatch(const ExpectedRatios& ratios);

/// Where the supernodes of the calibration geometry sit.
enum class SupernodePlacement {
  kQuadrants,  ///< Oh §VII-E: one at the centre of each quadrant
  kCentre,     ///< Oh §VII-C, D: a single one at the centre
};

/// Oh §VII's supernodes, placed as given, with the given range.
TopologyConfig ohTopologyConfig(double communication_range, SupernodePlacement placement);

/// The communication graph of Oh §VII: ohTopologyConfig() over the 100 x 100 region with a grid
/// of spacing 1 (10^4 sensors at 0.5 .. 99.5, laid out as a scenario's grid is).
Topology ohCalibrationTopology(double communication_range, SupernodePlacement placement);

}  // namespace wsn::network_model
