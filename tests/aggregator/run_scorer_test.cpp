#include "aggregator/run_scorer.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/truth.hpp"
#include "scenario/loader.hpp"
#include "tests/aggregator/test_support.hpp"

using wsn::aggregator::Json;
using wsn::aggregator::kLiveStream;
using wsn::aggregator::metricsJson;
using wsn::aggregator::RunInfo;
using wsn::aggregator::RunScorer;
using wsn::aggregator::RunScores;
using wsn::aggregator::TickScores;
using wsn::common::MetricsConfig;
using wsn::common::TargetState;
using wsn::common::TrackEstimate;
using wsn::common::Vec2;

using wsn::aggregator::test::target;
using wsn::aggregator::test::track;

namespace {

/// c = 5, p = 2 for OSPA and GOSPA, T = 3, gate 3, band 5: the scenario defaults.
MetricsConfig defaults() { return MetricsConfig{}; }

const std::vector<Vec2> kCentre = {{50, 50}};

/// Random births and deaths (pz = 0.05, and fast targets leaving the region) over four
/// tracking groups, so the perfect tracker meets every kind of tick.
constexpr const char* kBirthsAndDeaths = R"(name: births_and_deaths
region: {x_min: 0, y_min: 0, x_max: 100, y_max: 100}
targets:
  birth_rate: 5.0e-5
  death_probability: 0.05
  speed_class: fast
supernodes:
  - {x: 25, y: 25}
  - {x: 75, y: 25}
  - {x: 25, y: 75}
  - {x: 75, y: 75}
run:
  ticks: 60
  seed: 3
)";

/// The value `name` of a tick; fails the test when no metric gave it.
double value(const TickScores& tick, const std::string& name) {
  const auto found = tick.find(name);
  INFO(name);
  REQUIRE(found.has_value());
  return *found;
}

/// A real or count of a metric's metrics.json block, e.g. get(s, "clear_mot", "mota").
double get(const RunScores& s, const std::string& metric, const std::string& key) {
  return s.at(metric).at(key).get<double>();
}

bool flag(const RunScores& s, const std::string& metric, const std::string& key) {
  return s.at(metric).at(key).get<bool>();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

}  // namespace

TEST_CASE("a perfect tracker over a real truth with births and deaths scores no error anywhere",
          "[run_scorer][property]") {
  const auto scenario = wsn::scenario::parseScenario(kBirthsAndDeaths, "births_and_deaths.yaml");
  const wsn::common::Truth truth(truthConfig(scenario));
  RunScorer scorer(kLiveStream, scenario.metrics, scenario.supernodes);

  // The run must really have births after the start and deaths before the end.
  std::set<wsn::common::TargetId> at_start, at_end, ever;
  for (const auto& s : truth.at(1)) at_start.insert(s.id);
  for (const auto& s : truth.at(scenario.run.ticks)) at_end.insert(s.id);
  for (std::int32_t t = 1; t <= scenario.run.ticks; ++t) {
    std::vector<TrackEstimate> tracks;
    for (const auto& s : truth.at(t)) {
      ever.insert(s.id);
      tracks.push_back(track(static_cast<std::uint64_t>(s.id), s.x, s.y, s.vx, s.vy));
    }
    const TickScores tick = scorer.add(t, truth.at(t), tracks);
    CHECK(value(tick, "truth_targets") == value(tick, "tracks"));
    CHECK(value(tick, "ospa") == 0.0);
    CHECK(value(tick, "gospa") == 0.0);
    CHECK(value(tick, "eps_k_running") == 0.0);
  }
  REQUIRE(ever.size() > at_start.size());  // births
  REQUIRE(ever.size() > at_end.size());  // deaths
  REQUIRE(ever.size() >= 10);

  const RunScores s = scorer.finish();
  CHECK(flag(s, "metrics", "eps_k_defined"));
  CHECK(get(s, "metrics", "eps_k") == 0.0);
  CHECK(flag(s, "metrics", "eps_x_defined"));
  CHECK(get(s, "metrics", "eps_x") == 0.0);
  CHECK(get(s, "metrics", "ospa_mean") == 0.0);
  CHECK(get(s, "gospa", "mean") == 0.0);
  CHECK(get(s, "gospa", "localisation") == 0.0);
  CHECK(get(s, "gospa", "missed") == 0.0);
  CHECK(get(s, "gospa", "false") == 0.0);
  CHECK(flag(s, "clear_mot", "mota_defined"));
  CHECK(get(s, "clear_mot", "mota") == 1.0);
  CHECK(flag(s, "clear_mot", "motp_defined"));
  CHECK(get(s, "clear_mot", "motp") == 0.0);
  CHECK(get(s, "clear_mot", "id_switches") == 0);
  CHECK(get(s, "clear_mot", "fragmentations") == 0);
  CHECK(get(s, "clear_mot", "misses") == 0);
  CHECK(get(s, "clear_mot", "false_positives") == 0);
  const Json& targets = s.at("track_quality").at("targets");
  REQUIRE(targets.size() == ever.size());
  for (const auto& q : targets) {
    CHECK(q.at("tlr").get<double>() == 1.0);
    CHECK(q.at("tlr_length").get<double>() == 1.0);
    CHECK(q.at("rse_position").get<double>() == 0.0);
    CHECK(q.at("rse_velocity").get<double>() == 0.0);
    CHECK(q.at("mean_position_error").get<double>() == 0.0);
  }
  CHECK(get(s, "track_quality", "false_track_ticks") == 0);
  const Json& boundary = s.at("boundary");
  CHECK(boundary.at("supernodes") == 4);
  const auto target_ticks = [&](const char* side) { return boundary.at(side).at("target_ticks").get<double>(); };
  CHECK(target_ticks("boundary") > 0);  // some targets do cross the groups' boundaries
  CHECK(target_ticks("boundary") + target_ticks("interior") == get(s, "clear_mot", "ground_truth"));
  for (const char* side : {"boundary", "interior"}) {
    CHECK(boundary.at(side).at("duplicate_track_ticks") == 0);
    CHECK(boundary.at(side).at("id_switches") == 0);
    CHECK(boundary.at(side).at("fragmentations") == 0);
  }
}

TEST_CASE("an empty tick scores zero and leaves the run's ratios undefined", "[run_scorer]") {
  RunScorer scorer(kLiveStream, defaults(), kCentre);
  const TickScores t = scorer.add(1, {}, {});
  CHECK(value(t, "truth_targets") == 0);
  CHECK(value(t, "tracks") == 0);
  CHECK(value(t, "ospa") == 0.0);
  CHECK(value(t, "gospa") == 0.0);
  CHECK(value(t, "eps_k_running") == 0.0);
  CHECK(value(t, "ospa_mean_running") == 0.0);
  const RunScores s = scorer.finish();
  CHECK_FALSE(flag(s, "metrics", "eps_k_defined"));
  CHECK_FALSE(flag(s, "metrics", "eps_x_defined"));
  CHECK_FALSE(flag(s, "clear_mot", "mota_defined"));
  CHECK_FALSE(flag(s, "clear_mot", "motp_defined"));
  CHECK(s.at("track_quality").at("targets").empty());
  CHECK_FALSE(flag(s, "track_quality", "means_defined"));
  CHECK(get(s, "gospa", "ticks") == 1);
}

TEST_CASE("empty truth: every track is false", "[run_scorer]") {
  // Two tracks, no target, c = 5, p = 2: OSPA = c = 5; GOSPA² = 2 · 25 / 2 = 25, all false.
  RunScorer scorer(kLiveStream, defaults(), kCentre);
  const TickScores t = scorer.add(1, {}, {track(1, 0, 0), track(2, 10, 10)});
  CHECK(value(t, "truth_targets") == 0);
  CHECK(value(t, "tracks") == 2);
  CHECK(value(t, "ospa") == Approx(5.0).margin(1e-12));
  CHECK(value(t, "gospa") == Approx(5.0).margin(1e-12));
  CHECK(value(t, "gospa_false") == Approx(25.0).margin(1e-12));
  CHECK(value(t, "gospa_missed") == 0.0);
  CHECK(value(t, "eps_k_running") == 0.0);  // Σ K* = 0: undefined, reported as 0
  const RunScores s = scorer.finish();
  CHECK(get(s, "clear_mot", "false_positives") == 2);
  CHECK(get(s, "track_quality", "false_track_ticks") == 2);
  CHECK(s.at("boundary").at("interior").at("duplicate_track_ticks") == 0);
}

TEST_CASE("empty tracks: every target is missed", "[run_scorer]") {
  // Two targets, no track: OSPA = 5; GOSPA² = 2 · 25 / 2 = 25, all missed; εK = 2 / 2 = 1;
  // MOTA = 1 − 2 / 2 = 0; TLR 0 for both.
  RunScorer scorer(kLiveStream, defaults(), kCentre);
  const TickScores t = scorer.add(1, {target(1, 0, 0), target(2, 10, 10)}, {});
  CHECK(value(t, "truth_targets") == 2);
  CHECK(value(t, "tracks") == 0);
  CHECK(value(t, "ospa") == Approx(5.0).margin(1e-12));
  CHECK(value(t, "gospa") == Approx(5.0).margin(1e-12));
  CHECK(value(t, "gospa_missed") == Approx(25.0).margin(1e-12));
  CHECK(value(t, "gospa_false") == 0.0);
  CHECK(value(t, "eps_k_running") == Approx(1.0).margin(1e-12));
  const RunScores s = scorer.finish();
  CHECK(get(s, "clear_mot", "mota") == Approx(0.0).margin(1e-12));
  CHECK(get(s, "clear_mot", "misses") == 2);
  REQUIRE(s.at("track_quality").at("targets").size() == 2);
  CHECK(s.at("track_quality").at("targets")[0].at("tlr").get<double>() == 0.0);
  CHECK(get(s, "track_quality", "mean_tlr") == 0.0);
}

TEST_CASE("more tracks than targets: every metric sees the same tick", "[run_scorer]") {
  // Target 1 at (0, 0); tracks 10 at (1, 0), 11 at (10, 0), 12 at (0, 2). c = 5, p = 2, T = 3.
  //   OSPA: m = 1, n = 3, best pair d = 1: sqrt((1 + 25 + 25) / 3) = sqrt(17) = 4.123106.
  //   GOSPA: 1-10 (1²), two false at 25 / 2: 1 + 25 = 26, distance sqrt(26) = 5.099020.
  //   εK running: |3 − 1| / 1 = 2.
  //   CLEAR-MOT: 1-10 (d = 1), two false positives: MOTA = 1 − 2 / 1 = −1, MOTP = 1.
  //   Boundary (one supernode): track 12 is 2 < T from the tracked target 1: one interior
  //   duplicate; track 11 (10 away) is only false.
  //   Quality (gate 3): target 1 associated with 10: RSE_pos 1, TLR 1; 2 false track-ticks.
  // Tick 2: target 1 at (0, 0), track 10 on it: OSPA 0, running εK = (2 + 0) / 2 = 1,
  // running mean OSPA = sqrt(17) / 2.
  RunScorer scorer(kLiveStream, defaults(), kCentre);
  const TickScores t1 = scorer.add(1, {target(1, 0, 0)}, {track(10, 1, 0), track(11, 10, 0), track(12, 0, 2)});
  CHECK(t1.tick == 1);
  CHECK(value(t1, "truth_targets") == 1);
  CHECK(value(t1, "tracks") == 3);
  CHECK(value(t1, "ospa") == Approx(std::sqrt(17.0)).margin(1e-12));
  CHECK(value(t1, "gospa") == Approx(std::sqrt(26.0)).margin(1e-12));
  CHECK(value(t1, "gospa_localisation") == Approx(1.0).margin(1e-12));
  CHECK(value(t1, "gospa_missed") == 0.0);
  CHECK(value(t1, "gospa_false") == Approx(25.0).margin(1e-12));
  CHECK(value(t1, "eps_k_running") == Approx(2.0).margin(1e-12));
  CHECK(scorer.csvRow(t1) == "1,1,3,4.123106,5.099020,1.000000,0.000000,25.000000");

  const TickScores t2 = scorer.add(2, {target(1, 0, 0)}, {track(10, 0, 0)});
  CHECK(value(t2, "ospa") == 0.0);
  CHECK(value(t2, "eps_k_running") == Approx(1.0).margin(1e-12));
  CHECK(value(t2, "ospa_mean_running") == Approx(std::sqrt(17.0) / 2.0).margin(1e-12));

  const RunScores s = scorer.finish();
  CHECK(get(s, "metrics", "eps_k") == Approx(1.0).margin(1e-12));
  CHECK(get(s, "gospa", "mean") == Approx(std::sqrt(26.0) / 2.0).margin(1e-12));
  CHECK(get(s, "clear_mot", "matches") == 2);
  CHECK(get(s, "clear_mot", "false_positives") == 2);
  CHECK(get(s, "clear_mot", "mota") == Approx(1.0 - 2.0 / 2.0).margin(1e-12));
  CHECK(get(s, "clear_mot", "motp") == Approx(0.5).margin(1e-12));
  CHECK(s.at("boundary").at("interior").at("duplicate_track_ticks") == 1);
  CHECK(s.at("boundary").at("boundary").at("duplicate_track_ticks") == 0);
  const Json& targets = s.at("track_quality").at("targets");
  REQUIRE(targets.size() == 1);
  CHECK(targets[0].at("tlr").get<double>() == 1.0);
  CHECK(targets[0].at("rse_position").get<double>() == Approx(std::sqrt(0.5)).margin(1e-12));
  CHECK(get(s, "track_quality", "false_track_ticks") == 2);
}

TEST_CASE("non-finite tracks are dropped once, so every metric counts the same tracks", "[run_scorer]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  RunScorer scorer(kLiveStream, defaults(), kCentre);
  const TickScores t = scorer.add(1, {target(1, 0, 0)}, {track(1, 0, 0), track(2, 0, 0, nan, 0)});
  CHECK(value(t, "tracks") == 1);
  CHECK(value(t, "ospa") == 0.0);
  CHECK(value(t, "gospa") == 0.0);
  const RunScores s = scorer.finish();
  CHECK(get(s, "metrics", "tracks_ignored_nonfinite") == 1);
  CHECK(get(s, "clear_mot", "false_positives") == 0);
  CHECK(get(s, "track_quality", "false_track_ticks") == 0);
}

TEST_CASE("the run scorer wants increasing ticks and valid settings", "[run_scorer]") {
  RunScorer scorer(kLiveStream, defaults(), kCentre);
  scorer.add(2, {target(1, 0, 0)}, {});
  CHECK_THROWS_AS(scorer.add(2, {}, {}), std::invalid_argument);
  CHECK_THROWS_AS(scorer.add(1, {}, {}), std::invalid_argument);
  const RunScores s = scorer.finish();  // the refused ticks left no trace
  CHECK(get(s, "metrics", "ticks_scored") == 1);
  CHECK(get(s, "clear_mot", "ground_truth") == 1);  // the one target of tick 2
  CHECK(get(s, "gospa", "ticks") == 1);

  auto bad = defaults();
  bad.gospa_c = 0.0;
  CHECK_THROWS_AS(RunScorer(kLiveStream, bad, kCentre), std::invalid_argument);
  bad = defaults();
  bad.boundary_band = -1.0;
  CHECK_THROWS_AS(RunScorer(kLiveStream, bad, kCentre), std::invalid_argument);
  bad = defaults();
  bad.mot_threshold = 0.0;
  CHECK_THROWS_AS(RunScorer(kLiveStream, bad, kCentre), std::invalid_argument);
}

TEST_CASE("metrics_per_tick.csv has the header the plotting script reads", "[run_scorer][csv]") {
  // The columns come from the metrics in registration order: tools/plot_run.py and
  // tools/sweep.py read them by position.
  RunScorer scorer(kLiveStream, defaults(), kCentre);
  CHECK(scorer.csvHeader() == "tick,truth_targets,tracks,ospa,gospa,gospa_localisation,gospa_missed,gospa_false");
  CHECK(scorer.csvRow(scorer.add(7, {}, {})) == "7,0,0,0.000000,0.000000,0.000000,0.000000,0.000000");
}

TEST_CASE("metrics.json keeps the sweep's keys on top, every block in order, provenance and timing last",
          "[run_scorer][json]") {
  RunScorer scorer(kLiveStream, defaults(), {{25, 25}, {75, 25}});
  scorer.add(1, {target(1, 47, 25), target(2, 10, 10)}, {track(10, 47, 25), track(11, 48, 25)});
  scorer.add(2, {target(1, 48, 25), target(2, 10, 10)}, {track(10, 48, 25), track(20, 10, 11)});
  const RunScores scores = scorer.finish();
  const RunInfo info{"a \"quoted\" name", 7, 2, "gnn", 2, 3, "gated", "{\"version\":\"0.1.0\"}"};
  const std::string json = metricsJson(info, scores, 1.5, 2.0);
  // Without provenance (a role started by hand) the line is left out.
  const RunInfo bare{"n", 7, 2, "gnn", 2, 3, "gated", ""};
  CHECK(metricsJson(bare, scores, 1.5, 2.0).find("provenance") == std::string::npos);
  CHECK(json.find("\n  \"provenance\": {\"version\":\"0.1.0\"},\n  \"timing\": ") != std::string::npos);

  // Top-level keys in this order; the launcher and tools/sweep.py take eps_k, eps_x, ospa,
  // ospa_mean, track_ids, wall_s, ticks_per_s from their first occurrence.
  const std::vector<std::string> top = {"scenario",     "seed",  "ticks",     "engine",        "association", "truth_targets",
                                        "eps_k",        "eps_x", "ospa",      "observations_dropped_stale",
                                        "metrics",      "gospa", "clear_mot", "track_quality", "boundary",
                                        "provenance",   "timing"};
  std::size_t at = 0;
  for (const auto& key : top) {
    const auto found = json.find("\n  \"" + key + "\": ", at);
    INFO(key);
    REQUIRE(found != std::string::npos);
    at = found + 1;
  }
  CHECK(json.find("\"scenario\": \"a \\\"quoted\\\" name\"") != std::string::npos);
  CHECK(json.find("\"association\": \"gated\"") != std::string::npos);
  CHECK(json.find("\"eps_k\": ") == json.find("\n  \"eps_k\": ") + 3);
  CHECK(json.find("\"ospa\": ") == json.find("\n  \"ospa\": ") + 3);
  CHECK(json.find("\"ospa_mean\": ") < json.find("\"gospa\": "));
  CHECK(json.find("\"track_ids\": ") < json.find("\"gospa\": "));

  // Blocks carry their settings and counts.
  const Json parsed = Json::parse(json);
  CHECK(parsed.at("gospa").at("c") == 5.0);
  CHECK(parsed.at("clear_mot").at("threshold") == 3.0);
  CHECK(parsed.at("track_quality").at("gate") == 3.0);
  CHECK(parsed.at("boundary").at("band") == 5.0);
  const Json& first = parsed.at("track_quality").at("targets").at(0);
  CHECK(first.at("id") == 1);
  CHECK(first.at("ticks_alive") == 2);
  CHECK(first.at("ticks_associated") == 2);
  // Track 11 at (48, 25) duplicates target 1 at (47, 25), s = 3 <= 5: a boundary duplicate.
  CHECK(parsed.at("boundary").at("boundary").at("target_ticks") == 2);
  CHECK(parsed.at("boundary").at("boundary").at("duplicate_track_ticks") == 1);

  // The timing block is one line, the last before the closing brace, and the only thing that
  // changes with the wall time.
  const auto all = lines(json);
  REQUIRE(all.size() >= 3);
  CHECK(all.back() == "}");
  CHECK(all[all.size() - 2] == "  \"timing\": {\"wall_s\": 1.5, \"ticks_per_s\": 2.0}");
  auto other = lines(metricsJson(info, scores, 99.0, 0.5));
  CHECK(other[other.size() - 2] != all[all.size() - 2]);
  other.erase(other.end() - 2);
  auto same = all;
  same.erase(same.end() - 2);
  CHECK(other == same);
}
