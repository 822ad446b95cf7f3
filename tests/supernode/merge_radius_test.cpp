// merge_radius in the position engines (MCMCDA, GNN): a target that gives two reports a tick (a
// sensor model that reports every detecting sensor, Oh §VIII) is one track when its reports are
// merged, and more than one when they are not; merging also never joins two targets farther apart
// than the radius.
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

#include "supernode/supernode_tracker.hpp"
#include "tests/supernode/test_support.hpp"

namespace wsn::supernode {
namespace {

using test::observation;

common::Scenario scenarioOf(const std::string& engine, double merge_radius) {
  common::Scenario s;
  s.source_path = "test.yaml";
  s.supernodes = {{50.0, 50.0}};
  s.tracker.engine = engine;
  s.tracker.params["measurement_sigma"] = {0.3, 0};
  if (engine == "mcmcda") s.tracker.params["false_alarm_density"] = {1e-3, 0};
  s.tracker.params["merge_radius"] = {merge_radius, 0};
  return s;
}

/// Ticks 1..20; each target at (x0 + t, y) gives two reports a tick, 0.5 above and below it.
/// Returns the confirmed tracks of every tick from 6 on.
std::vector<std::size_t> trackCounts(const std::string& engine, double merge_radius, std::vector<double> rows) {
  auto tracker = test::trackerFor(scenarioOf(engine, merge_radius), 0);
  std::vector<std::size_t> counts;
  for (std::int32_t t = 1; t <= 20; ++t) {
    std::vector<common::Observation> delivered;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const auto target = static_cast<common::TargetId>(k);
      delivered.push_back(observation(t, t, 20.0 + t, rows[k] - 0.5, target));
      delivered.push_back(observation(t, t, 20.0 + t, rows[k] + 0.5, target));
    }
    const auto out = tracker.step(t, delivered, {});
    if (t >= 6) counts.push_back(out.tracks.size());
  }
  return counts;
}

TEST_CASE("a target's two reports a tick make one track when merged", "[merge_radius]") {
  for (const std::string engine : {"mcmcda", "gnn"}) {
    INFO(engine);
    // The reports are 1 apart: a radius of 1.5 joins them, at their mean, the target's position.
    for (const std::size_t count : trackCounts(engine, 1.5, {50.0})) CHECK(count == 1);
    // Without merging the engine sees two targets 1 apart (or clutter): never just one track.
    const auto unmerged = trackCounts(engine, 0.0, {50.0});
    CHECK(std::set<std::size_t>(unmerged.begin(), unmerged.end()) != std::set<std::size_t>{1});
  }
}

TEST_CASE("merging never joins two targets farther apart than the radius", "[merge_radius]") {
  for (const std::string engine : {"mcmcda", "gnn"}) {
    INFO(engine);
    // Targets 5 apart (rows 45 and 50), each with two reports 1 apart: radius 1.5 gives two
    // clusters, two tracks.
    for (const std::size_t count : trackCounts(engine, 1.5, {45.0, 50.0})) CHECK(count == 2);
  }
}

}  // namespace
}  // namespace wsn::supernode
