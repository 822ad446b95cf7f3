#include "aggregator/run_scorer.hpp"

#include <set>
#include <stdexcept>
#include <utility>

#include "common/output.hpp"

namespace wsn::aggregator {
namespace {

/// Free-text names (the scenario's) may hold invalid UTF-8: replace it rather than fail the run.
std::string dump(const Json& json, int indent = -1) {
  return json.dump(indent, ' ', false, Json::error_handler_t::replace);
}

/// A stream's block starts with its metrics' headline keys...
void addHeadlines(Json& out, const RunScores& scores) {
  for (const auto& [name, report] : scores.reports)
    for (const auto& [key, value] : report.headline.items()) out[key] = value;
}

/// ...and goes on with one summary per metric, under the metric's name.
void addSummaries(Json& out, const RunScores& scores) {
  for (const auto& [name, report] : scores.reports) out[name] = report.summary;
}

}  // namespace

std::vector<NamedValue> TickScores::live() const {
  std::vector<NamedValue> out = columns;
  out.insert(out.end(), live_only.begin(), live_only.end());
  return out;
}

std::optional<double> TickScores::find(std::string_view name) const {
  for (const auto* values : {&columns, &live_only})
    for (const auto& v : *values)
      if (v.name == name) return v.value;
  return std::nullopt;
}

const Json& RunScores::at(const std::string& name) const {
  for (const auto& [metric, report] : reports)
    if (metric == name) return report.summary;
  throw std::out_of_range("stream '" + stream + "' has no metric '" + name + "'");
}

RunScorer::RunScorer(std::string stream, const common::MetricsConfig& config,
                     const std::vector<common::Vec2>& supernodes, const MetricRegistry& metrics)
    : stream_(std::move(stream)) {
  std::set<std::string> names{"tick"};
  for (const MetricSpec& spec : metrics) {
    Entry entry{spec.name, spec.create(config, supernodes), 0};
    for (auto& column : entry.metric->columns()) {
      if (!names.insert(column.name).second)
        throw std::logic_error("metric '" + spec.name + "': column '" + column.name + "' is already taken");
      columns_.push_back(std::move(column));
      ++entry.columns;
    }
    metrics_.push_back(std::move(entry));
  }
}

TickScores RunScorer::add(std::int32_t tick, const std::vector<common::TargetState>& truth,
                          const std::vector<common::TrackEstimate>& tracks) {
  if (any_tick_ && tick <= last_tick_)
    throw std::invalid_argument("run_scorer: tick " + std::to_string(tick) + " added after tick " +
                                std::to_string(last_tick_));
  any_tick_ = true;
  last_tick_ = tick;

  std::vector<common::TrackEstimate> finite;
  finite.reserve(tracks.size());
  for (const auto& track : tracks)
    if (common::isFinite(track)) finite.push_back(track);
  const MetricTick input{tick, truth, finite, static_cast<std::int64_t>(tracks.size() - finite.size())};

  TickScores out;
  out.tick = tick;
  out.columns.reserve(columns_.size());
  for (auto& entry : metrics_) {
    MetricTickValues values = entry.metric->add(input);
    if (values.columns.size() != entry.columns)
      throw std::logic_error("metric '" + entry.name + "' gave " + std::to_string(values.columns.size()) +
                             " values for its " + std::to_string(entry.columns) + " columns");
    for (const double value : values.columns) out.columns.push_back({columns_[out.columns.size()].name, value});
    for (auto& value : values.live) out.live_only.push_back(std::move(value));
  }
  return out;
}

RunScores RunScorer::finish() const {
  RunScores out{stream_, {}};
  for (const auto& entry : metrics_) out.reports.emplace_back(entry.name, entry.metric->finish());
  return out;
}

std::string RunScorer::csvHeader() const {
  std::string header = "tick";
  for (const auto& column : columns_) header += "," + column.name;
  return header;
}

std::string RunScorer::csvRow(const TickScores& scores) const {
  if (scores.columns.size() != columns_.size())
    throw std::logic_error("run_scorer: a row of " + std::to_string(scores.columns.size()) + " cells under " +
                           std::to_string(columns_.size()) + " columns");
  std::string row = std::to_string(scores.tick);
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    const double value = scores.columns[i].value;
    row += "," + (columns_[i].whole ? std::to_string(static_cast<std::int64_t>(value)) : common::fixed6(value));
  }
  return row;
}

std::string metricsJson(const RunInfo& info, const std::vector<RunScores>& streams, double wall_s,
                        double ticks_per_s) {
  const RunScores* live = nullptr;
  Json others = Json::object();
  for (const auto& scores : streams) {
    if (scores.stream == kLiveStream) {
      live = &scores;
    } else {
      if (others.contains(scores.stream)) throw std::logic_error("metrics.json: stream '" + scores.stream + "' twice");
      addHeadlines(others[scores.stream], scores);
      addSummaries(others[scores.stream], scores);
    }
  }

  // The headline eps_k, eps_x and ospa come before the blocks: tools/sweep.py and the launcher's
  // summary read them (the launcher takes the first occurrence of a key).
  Json out{{"scenario", info.scenario}, {"seed", info.seed},         {"ticks", info.ticks},
           {"engine", info.engine},     {"association", info.association}, {"truth_targets", info.truth_targets}};
  if (live != nullptr) addHeadlines(out, *live);
  out["observations_dropped_stale"] = info.observations_dropped_stale;
  if (live != nullptr) addSummaries(out, *live);
  if (!others.empty()) out["streams"] = std::move(others);
  if (!info.faults.is_null()) out["faults"] = info.faults;

  // Provenance and timing are appended by hand, one line each, for the tests that drop them.
  std::string text = dump(out, 2);
  text.erase(text.size() - 2);  // the closing "\n}"
  if (!info.provenance_json.empty()) text += ",\n  \"provenance\": " + info.provenance_json;
  text += ",\n  \"timing\": {\"wall_s\": " + dump(Json(wall_s)) + ", \"ticks_per_s\": " + dump(Json(ticks_per_s)) +
          "}\n}\n";
  return text;
}

}  // namespace wsn::aggregator
