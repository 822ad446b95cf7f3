#include "launcher/resource_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

namespace wsn::launcher {
namespace {

// Measured on the 2-core development machine (RelWithDebInfo), default scenario otherwise:
// measuring the observation statistics took 2.0 s for 10^5 sensors and 44 s for 10^6, i.e.
// 44 s (N / 10^6)^1.35; a resident sensor costs about 150 bytes in each process that holds the
// whole layout (the launcher while it resolves, the network model, the node tiles together); a
// target-tick about 64 bytes in each process holding the truth (launcher, node tiles, aggregator)
// and 0.5 ms of tick loop (detection, routing, MCMCDA, scoring: 0.3 s for the default 600); a
// breadth-first visit of a neighbour about 2 ns, once for the components and once per supernode.
constexpr double kStatisticsSecondsAtMillion = 44.0;
constexpr double kStatisticsExponent = 1.35;
constexpr double kBytesPerSensor = 150.0;
constexpr double kBytesPerTargetTick = 64.0;
constexpr double kSecondsPerTargetTick = 5e-4;
constexpr double kSecondsPerNeighbourVisit = 2e-9;
// Far beyond: the default scenario takes about a second, a 10^6-sensor grid under a minute.
constexpr double kFarTooLongSeconds = 600;

std::string human(double value, const char* unit) {
  const char* prefixes[] = {"", "k", "M", "G", "T", "P"};
  int p = 0;
  while (value >= 1000.0 && p < 5) {
    value /= 1000.0;
    ++p;
  }
  char text[64];
  std::snprintf(text, sizeof text, *unit != '\0' ? "%.3g %s%s" : "%.3g%s%s", value, prefixes[p], unit);
  return text;
}

std::string duration(double seconds) {
  char text[64];
  if (seconds < 120) std::snprintf(text, sizeof text, "%.0f s", seconds);
  else if (seconds < 7200) std::snprintf(text, sizeof text, "%.0f min", seconds / 60);
  else std::snprintf(text, sizeof text, "%.1f h", seconds / 3600);
  return text;
}

}  // namespace

ResourceEstimate estimateResources(const common::Scenario& scenario) {
  ResourceEstimate e;
  const double area = std::max(scenario.region.width() * scenario.region.height(), 0.0);
  const double spacing = scenario.sensors.spacing;
  if (scenario.sensors.kind == common::SensorLayoutConfig::Kind::kGrid)
    e.sensors = std::floor(scenario.region.width() / spacing) * std::floor(scenario.region.height() / spacing);
  else if (scenario.sensors.kind == common::SensorLayoutConfig::Kind::kList)
    e.sensors = static_cast<double>(scenario.sensors.list.size());
  else
    e.sensors = static_cast<double>(scenario.sensors.count);
  // communication_range is in separations (the grid's spacing, or the random layout's mean
  // distance), so (range / spacing)^2 is range^2 here; no more neighbours than sensors.
  e.neighbours = std::min(std::numbers::pi * scenario.network.communication_range * scenario.network.communication_range,
                          e.sensors);

  const double ticks = scenario.run.ticks;
  for (const auto& target : scenario.targets.scripted) {
    const double end = target.disappear_tick > 0 ? std::min<double>(target.disappear_tick, ticks + 1) : ticks + 1;
    e.target_ticks += std::max(end - target.appear_tick, 0.0);
  }
  e.targets = static_cast<double>(scenario.targets.scripted.size()) + scenario.targets.count;
  e.target_ticks += scenario.targets.count * std::min<double>(scenario.targets.lifetime_max, ticks);
  // Born targets: a Poisson number per tick; each lives at most to the end (half the run on average).
  const double births = scenario.targets.birth_rate * area * ticks;
  e.targets += births;
  e.target_ticks += births * ticks / 2.0;

  const double tiles = std::max(scenario.run.node_processes, 1);
  const double supernodes = static_cast<double>(scenario.supernodes.size());
  e.memory_bytes = 3.0 * e.sensors * kBytesPerSensor + (tiles + 2.0) * e.target_ticks * kBytesPerTargetTick;
  e.seconds = kStatisticsSecondsAtMillion * std::pow(e.sensors / 1e6, kStatisticsExponent) +
              e.sensors * e.neighbours * (1.0 + supernodes) * kSecondsPerNeighbourVisit +
              e.target_ticks * kSecondsPerTargetTick;
  return e;
}

std::vector<std::string> resourceWarnings(const ResourceEstimate& e, double ram_bytes) {
  std::vector<std::string> warnings;
  const std::string what = human(e.sensors, "") + " sensors (" + human(e.neighbours, "") + " neighbours each), " +
                           human(e.targets, "") + " targets, " + human(e.target_ticks, "") + " target-ticks";
  if (ram_bytes > 0 && e.memory_bytes > ram_bytes / 2)
    warnings.push_back("warning: estimated memory " + human(e.memory_bytes, "B") + " is more than half of this "
                       "machine's " + human(ram_bytes, "B") + " (" + what + ")");
  if (e.seconds > kFarTooLongSeconds)
    warnings.push_back("warning: estimated run time " + duration(e.seconds) + ", set-up included, is over 10 minutes on "
                       "this machine (" + what + "); --timeout and Ctrl-C stop it at any stage");
  return warnings;
}

double totalRamBytes() {
  std::ifstream in("/proc/meminfo");
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string key;
    double kb = 0;
    if (fields >> key >> kb && key == "MemTotal:") return kb * 1024.0;
  }
  return 0;
}

}  // namespace wsn::launcher
