#include "aggregator/metric/metric.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "aggregator/run_scorer.hpp"
#include "tests/aggregator/test_support.hpp"

using wsn::aggregator::Column;
using wsn::aggregator::Json;
using wsn::aggregator::kLiveStream;
using wsn::aggregator::Metric;
using wsn::aggregator::MetricRegistry;
using wsn::aggregator::metricRegistry;
using wsn::aggregator::MetricReport;
using wsn::aggregator::MetricSpec;
using wsn::aggregator::MetricTick;
using wsn::aggregator::MetricTickValues;
using wsn::aggregator::metricsJson;
using wsn::aggregator::RunInfo;
using wsn::aggregator::RunScorer;
using wsn::aggregator::RunScores;
using wsn::aggregator::TickScores;
using wsn::common::MetricsConfig;
using wsn::common::Vec2;

using wsn::aggregator::test::target;
using wsn::aggregator::test::track;

namespace {

const std::vector<Vec2> kCentre = {{50, 50}};
const RunInfo kInfo{"toy", 7, 2, "gnn", 1, 0, "gated", "{\"version\":\"0.1.0\"}"};

/// A metric written the way a new one would be: it counts tracks, with a column, a live-only
/// running total and a summary of its own.
class ToyMetric final : public Metric {
 public:
  std::vector<Column> columns() const override { return {{"toy_tracks", true}}; }
  MetricTickValues add(const MetricTick& tick) override {
    total_ += static_cast<double>(tick.tracks.size());
    ++ticks_;
    return {{static_cast<double>(tick.tracks.size())}, {{"toy_total", total_}}};
  }
  MetricReport finish() const override { return {Json{{"ticks", ticks_}, {"total", total_}}}; }

 private:
  double total_ = 0.0;
  std::int64_t ticks_ = 0;
};

MetricSpec toySpec(std::string name = "toy") {
  return {std::move(name), "counts tracks", {},
          [](const MetricsConfig&, const std::vector<Vec2>&) -> std::unique_ptr<Metric> {
            return std::make_unique<ToyMetric>();
          },
          {}};
}

/// Only the registered metric called `name`.
MetricRegistry only(const std::string& name) { return MetricRegistry("metric", {metricRegistry().at(name)}); }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// The keys of a JSON object, in file order.
std::vector<std::string> keys(const Json& object) {
  std::vector<std::string> out;
  for (const auto& [key, value] : object.items()) out.push_back(key);
  return out;
}

}  // namespace

TEST_CASE("the registry lists every metric once, in the order of metrics.json", "[metric][registry]") {
  const auto& registry = metricRegistry();
  CHECK(registry.names() == "metrics, gospa, clear_mot, track_quality, boundary, classification, stop_mode");
  std::set<std::string> names;
  for (const MetricSpec& spec : registry) {
    INFO(spec.name);
    CHECK(names.insert(spec.name).second);
    CHECK_FALSE(spec.description.empty());
    CHECK_FALSE(spec.settings.empty());
    REQUIRE(spec.create);
    CHECK(spec.create(MetricsConfig{}, kCentre) != nullptr);
  }
  MetricRegistry copy = registry;
  CHECK_THROWS_AS(copy.add(registry.at("gospa")), std::logic_error);
  CHECK_THROWS_WITH(registry.at("mota"), Catch::Contains("unknown metric 'mota'; expected one of: metrics, gospa"));
}

TEST_CASE("a toy metric needs no other edit to appear in metrics.json, the per-tick CSV and the live values",
          "[metric][registry]") {
  MetricRegistry registry = metricRegistry();
  registry.add(toySpec());
  RunScorer scorer(kLiveStream, MetricsConfig{}, kCentre, registry);
  CHECK(scorer.csvHeader() == "tick,truth_targets,tracks,ospa,gospa,gospa_localisation,gospa_missed,gospa_false,toy_tracks");

  scorer.add(1, {target(1, 0, 0)}, {track(1, 0, 0), track(2, 9, 9)});
  const TickScores t2 = scorer.add(2, {target(1, 0, 0)}, {track(1, 0, 0)});
  // Tick 2: one track; the running total is 2 + 1 = 3.
  CHECK(scorer.csvRow(t2) == "2,1,1,0.000000,0.000000,0.000000,0.000000,0.000000,1");
  std::vector<std::string> live;
  for (const auto& v : t2.live()) live.push_back(v.name);
  CHECK(live == std::vector<std::string>{"truth_targets", "tracks", "ospa", "gospa", "gospa_localisation",
                                         "gospa_missed", "gospa_false", "toy_tracks", "eps_k_running",
                                         "ospa_mean_running", "toy_total"});
  CHECK(t2.find("toy_total") == 3.0);

  const Json json = Json::parse(metricsJson(kInfo, scorer.finish(), 1.0, 2.0));
  CHECK(json.at("toy") == Json{{"ticks", 2}, {"total", 3.0}});
  const auto top = keys(json);
  REQUIRE(top.size() >= 3);
  CHECK(top[top.size() - 3] == "toy");  // after the built-in blocks, before provenance and timing
}

TEST_CASE("two metrics cannot write the same per-tick column", "[metric][registry]") {
  MetricRegistry registry("metric", {toySpec("toy"), toySpec("toy_again")});
  CHECK_THROWS_AS(RunScorer(kLiveStream, MetricsConfig{}, kCentre, registry), std::logic_error);
}

TEST_CASE("two streams of one run are scored independently by the same metrics", "[metric][stream]") {
  // One target at (0, 0) for two ticks. The live stream has a false track at tick 1, the settled
  // one does not: live εK = (1 + 0) / 2 = 0.5, settled εK = 0; live OSPA at tick 1 with m = 1,
  // n = 2: sqrt(25 / 2), settled 0.
  RunScorer live(kLiveStream, MetricsConfig{}, kCentre);
  RunScorer settled("settled", MetricsConfig{}, kCentre);
  live.add(1, {target(1, 0, 0)}, {track(1, 0, 0), track(2, 20, 20)});
  settled.add(1, {target(1, 0, 0)}, {track(1, 0, 0)});
  for (auto* scorer : {&live, &settled}) scorer->add(2, {target(1, 0, 0)}, {track(1, 0, 0)});
  const RunScores live_scores = live.finish();
  const RunScores settled_scores = settled.finish();
  CHECK(live_scores.stream == "live");
  CHECK(settled_scores.stream == "settled");

  const std::string text = metricsJson(kInfo, {live_scores, settled_scores}, 1.0, 2.0);
  const Json json = Json::parse(text);
  // The live stream stays where metrics.json always had it.
  CHECK(json.at("eps_k").get<double>() == Approx(0.5).margin(1e-12));
  CHECK(json.at("metrics").at("ospa_per_tick").at(0).get<double>() == Approx(std::sqrt(12.5)).margin(1e-12));
  CHECK(json.at("clear_mot").at("false_positives") == 1);
  // The other under streams, with the same keys.
  const Json& other = json.at("streams").at("settled");
  CHECK(keys(other) == std::vector<std::string>{"eps_k", "eps_x", "eps_x_gated", "ospa", "metrics", "gospa",
                                                 "clear_mot", "track_quality", "boundary", "classification", "stop_mode"});
  CHECK(other.at("eps_k").get<double>() == 0.0);
  CHECK(other.at("metrics").at("ospa_mean").get<double>() == 0.0);
  CHECK(other.at("clear_mot").at("false_positives") == 0);

  // Adding a stream changes nothing of the live one's.
  Json alone = Json::parse(metricsJson(kInfo, live_scores, 1.0, 2.0));
  Json without = json;
  without.erase("streams");
  CHECK(without == alone);
  const auto top = keys(json);
  CHECK(top[top.size() - 3] == "streams");
  CHECK_THROWS_AS(metricsJson(kInfo, {live_scores, settled_scores, settled_scores}, 1.0, 2.0), std::logic_error);
}

TEST_CASE("metrics.json parses and has provenance and timing as its last lines, one each", "[metric][json]") {
  RunScorer scorer(kLiveStream, MetricsConfig{}, kCentre);
  scorer.add(1, {target(1, 0, 0)}, {track(1, 0.5, 0)});
  const RunScores scores = scorer.finish();
  const std::string text = metricsJson(kInfo, scores, 1.25, 0.5);
  const Json json = Json::parse(text);
  const auto top = keys(json);
  REQUIRE(top.size() >= 2);
  CHECK(top[top.size() - 2] == "provenance");
  CHECK(top.back() == "timing");
  CHECK(json.at("provenance") == Json{{"version", "0.1.0"}});
  CHECK(json.at("timing") == Json{{"wall_s", 1.25}, {"ticks_per_s", 0.5}});
  const auto all = lines(text);
  REQUIRE(all.size() >= 4);
  CHECK(all[all.size() - 3] == "  \"provenance\": {\"version\":\"0.1.0\"},");
  CHECK(all[all.size() - 2] == "  \"timing\": {\"wall_s\": 1.25, \"ticks_per_s\": 0.5}");
  CHECK(all.back() == "}");
  CHECK(text.back() == '\n');
  // No other line names them, so dropping those two lines drops exactly them.
  for (std::size_t i = 0; i + 3 < all.size(); ++i) {
    CHECK(all[i].find("\"provenance\"") == std::string::npos);
    CHECK(all[i].find("\"timing\"") == std::string::npos);
  }

  // Without provenance (a role started by hand) timing is still last, and the rest unchanged.
  const auto bare = lines(metricsJson(RunInfo{"toy", 7, 2, "gnn", 1, 0, "gated", ""}, scores, 1.25, 0.5));
  CHECK(bare.size() == all.size() - 1);
  CHECK(bare[bare.size() - 2] == all[all.size() - 2]);
}

TEST_CASE("the metrics block gives eps_K, eps_X and OSPA as numbers, and null for what is not finite",
          "[metric][json]") {
  // eps_K = |1 - 2| / 2 = 0.5; eps_X: one match, error 1 -> 1; OSPA, m = 1, n = 2, c = 5:
  // sqrt((1 + 25) / 2) = sqrt(13).
  RunScorer scorer(kLiveStream, MetricsConfig{}, kCentre, only("metrics"));
  scorer.add(1, {target(1, 0, 0), target(2, 10, 0)}, {track(3, 0, 1)});
  const Json json = Json::parse(metricsJson(kInfo, scorer.finish(), 1.0, 1.0));
  const Json& m = json.at("metrics");
  CHECK(m.at("eps_k").get<double>() == Approx(0.5));
  CHECK(m.at("eps_x").get<double>() == Approx(1.0));
  CHECK(m.at("ospa_mean").get<double>() == Approx(std::sqrt(13.0)).margin(1e-12));
  CHECK(m.at("ospa_per_tick") == Json::array({m.at("ospa_mean")}));
  CHECK(m.at("track_ids") == 1);
  CHECK(m.at("ticks_scored") == 1);
  CHECK(json.at("ospa") == m.at("ospa_mean"));

  // An empty run is valid and all zero.
  RunScorer empty(kLiveStream, MetricsConfig{}, kCentre, only("metrics"));
  const Json zero = Json::parse(metricsJson(kInfo, empty.finish(), 0.0, 0.0));
  CHECK(zero.at("eps_k").get<double>() == 0.0);
  CHECK(zero.at("metrics").at("ospa_per_tick").empty());

  // A non-finite number cannot come from valid inputs, but would still leave the file valid.
  RunScores odd{kLiveStream, {{"odd", MetricReport{Json{{"x", std::numeric_limits<double>::quiet_NaN()}}}}}};
  CHECK(Json::parse(metricsJson(kInfo, odd, 1.0, 1.0)).at("odd").at("x").is_null());
}
