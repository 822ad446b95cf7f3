#include "launcher/watch_map.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "common/output.hpp"
#include "common/sensor_layout.hpp"
#include "common/track_id.hpp"
#include "scenario/loader.hpp"

namespace wsn::launcher {
namespace {

using Json = nlohmann::ordered_json;

/// A finite number for JSON (NaN and infinities have no JSON form): null otherwise.
Json number(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

/// A CSV file of the run directory read row by row, its columns found by name.
class CsvRows {
 public:
  explicit CsvRows(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw std::runtime_error(path + ": cannot read it");
    std::string header;
    if (!std::getline(in_, header)) throw std::runtime_error(path + ":1: expected a header, got an empty file");
    header_ = common::splitCsvLine(header);
  }

  /// The position of column `name`; throws naming the file when the header lacks it.
  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < header_.size(); ++i)
      if (header_[i] == name) return i;
    throw std::runtime_error(path_ + ":1: expected a column '" + name + "' in the header");
  }

  /// The next row, or false at the end; throws on a row of another width.
  bool next(std::vector<std::string>& cells) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_;
      if (line.empty()) continue;
      cells = common::splitCsvLine(line);
      if (cells.size() != header_.size())
        throw std::runtime_error(where() + ": expected " + std::to_string(header_.size()) + " fields, got " +
                                 std::to_string(cells.size()));
      return true;
    }
    return false;
  }

  /// Cell `i` of the current row as a number; throws "FILE:LINE: column 'NAME' ..." otherwise.
  double number(const std::vector<std::string>& cells, std::size_t i) const {
    try {
      std::size_t used = 0;
      const double value = std::stod(cells[i], &used);
      if (used == cells[i].size()) return value;
    } catch (const std::logic_error&) {
    }
    throw std::runtime_error(where() + ": column '" + header_[i] + "' must be a number, got '" + cells[i] + "'");
  }

  /// Cell `i` as an unsigned 64-bit number (a track id); throws as number() does.
  std::uint64_t whole(const std::vector<std::string>& cells, std::size_t i) const {
    try {
      std::size_t used = 0;
      const auto value = std::stoull(cells[i], &used);
      if (used == cells[i].size() && cells[i].front() != '-') return value;
    } catch (const std::logic_error&) {
    }
    throw std::runtime_error(where() + ": column '" + header_[i] + "' must be a whole number, got '" + cells[i] + "'");
  }

  const std::vector<std::string>& header() const { return header_; }
  std::string where() const { return path_ + ":" + std::to_string(line_ + 1); }

 private:
  std::string path_;
  std::ifstream in_;
  std::vector<std::string> header_;
  int line_ = 0;
};

void readTracks(const std::string& path, std::map<std::int32_t, MapTick>& ticks) {
  CsvRows csv(path);
  const auto tick = csv.column("tick"), track = csv.column("track"), x = csv.column("x"), y = csv.column("y"),
             vx = csv.column("vx"), vy = csv.column("vy"), pxx = csv.column("p_xx"), pxy = csv.column("p_xy"),
             pyy = csv.column("p_yy");
  std::vector<std::string> cells;
  while (csv.next(cells)) {
    common::TrackEstimate t;
    t.track = csv.whole(cells, track);
    t.x = csv.number(cells, x);
    t.y = csv.number(cells, y);
    t.vx = csv.number(cells, vx);
    t.vy = csv.number(cells, vy);
    t.covariance[0] = csv.number(cells, pxx);
    t.covariance[1] = t.covariance[4] = csv.number(cells, pxy);
    t.covariance[5] = csv.number(cells, pyy);
    const auto at = static_cast<std::int32_t>(csv.number(cells, tick));
    ticks[at].tick = at;
    ticks[at].tracks.push_back(t);
  }
}

void readDelivered(const std::string& path, std::map<std::int32_t, MapTick>& ticks) {
  CsvRows csv(path);
  const auto delivered = csv.column("tick_delivered"), fate = csv.column("fate"), x = csv.column("x"),
             y = csv.column("y"), target = csv.column("target");
  std::vector<std::string> cells;
  while (csv.next(cells)) {
    if (cells[fate] != "delivered") continue;
    common::Observation o;
    o.tick_delivered = static_cast<std::int32_t>(csv.number(cells, delivered));
    o.x = csv.number(cells, x);
    o.y = csv.number(cells, y);
    o.target = static_cast<common::TargetId>(csv.number(cells, target));
    ticks[o.tick_delivered].tick = o.tick_delivered;
    ticks[o.tick_delivered].reports.push_back(o);
  }
}

void readMetrics(const std::string& path, std::map<std::int32_t, MapTick>& ticks) {
  CsvRows csv(path);
  const auto tick = csv.column("tick");
  const auto& header = csv.header();
  std::vector<std::string> cells;
  while (csv.next(cells)) {
    const auto at = static_cast<std::int32_t>(csv.number(cells, tick));
    ticks[at].tick = at;
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (i != tick) ticks[at].metrics[header[i]] = csv.number(cells, i);
  }
}

}  // namespace

std::map<std::int32_t, std::vector<MapTarget>> readMapTruth(const std::string& path) {
  CsvRows csv(path);
  const auto tick = csv.column("tick"), target = csv.column("target"), x = csv.column("x"), y = csv.column("y");
  std::map<std::int32_t, std::vector<MapTarget>> truth;
  std::vector<std::string> cells;
  while (csv.next(cells))
    truth[static_cast<std::int32_t>(csv.number(cells, tick))].push_back(
        {static_cast<std::int64_t>(csv.number(cells, target)), csv.number(cells, x), csv.number(cells, y)});
  return truth;
}

std::string mapFieldJson(const std::string& run_dir, bool live) {
  const common::Scenario scenario = scenario::loadScenario(run_dir + "/scenario.yaml");
  Json field;
  field["scenario"] = scenario.name;
  field["ticks"] = scenario.run.ticks;
  field["live"] = live;
  field["region"] = {scenario.region.x_min, scenario.region.y_min, scenario.region.x_max, scenario.region.y_max};
  field["supernodes"] = Json::array();
  for (const auto& s : scenario.supernodes) field["supernodes"].push_back({s.x, s.y});
  const common::SensorLayout layout(common::sensorFieldConfig(scenario));
  field["sensor_count"] = layout.size();
  field["sensors"] = Json::array();
  if (layout.size() <= kMapMaxSensors)
    for (const auto& p : layout.truePositions()) field["sensors"].push_back({p.x, p.y});
  return field.dump();
}

std::string mapTickJson(const MapTick& tick, const std::vector<MapTarget>& truth) {
  Json event;
  event["tick"] = tick.tick;
  event["truth"] = Json::array();
  for (const auto& t : truth) event["truth"].push_back({t.id, number(t.x), number(t.y)});
  event["reports"] = Json::array();
  for (const auto& r : tick.reports)
    event["reports"].push_back({number(r.x), number(r.y), r.target == common::kFalseAlarm ? -1 : static_cast<std::int64_t>(r.target)});
  event["tracks"] = Json::array();
  for (const auto& t : tick.tracks)
    event["tracks"].push_back(Json{{"label", common::track_id::label(t.track)},
                                   {"x", number(t.x)},
                                   {"y", number(t.y)},
                                   {"vx", number(t.vx)},
                                   {"vy", number(t.vy)},
                                   {"pxx", number(t.covariance[0])},
                                   {"pxy", number(t.covariance[1])},
                                   {"pyy", number(t.covariance[5])}});
  event["metrics"] = Json::object();
  for (const auto& [name, value] : tick.metrics) event["metrics"][name] = number(value);
  return event.dump();
}

std::vector<MapTick> readFinishedTicks(const std::string& run_dir) {
  std::map<std::int32_t, MapTick> ticks;
  readTracks(run_dir + "/tracks.csv", ticks);
  readDelivered(run_dir + "/observations.csv", ticks);
  readMetrics(run_dir + "/metrics_per_tick.csv", ticks);
  std::vector<MapTick> out;
  for (auto& [tick, value] : ticks) out.push_back(std::move(value));
  return out;
}

void MapTickAssembler::received(std::int32_t tick, const std::function<void(Held&)>& add) {
  if (tick < forgotten_below_) return;
  auto& held = held_[tick];
  held.tick.tick = tick;
  add(held);
  if (held.given) complete_.push_back(held.tick);
  settle();
}

void MapTickAssembler::onDeliveries(std::int32_t tick, std::vector<common::Observation> reports) {
  received(tick, [&](Held& held) { held.tick.reports.insert(held.tick.reports.end(), reports.begin(), reports.end()); });
}

void MapTickAssembler::onTracks(std::int32_t tick, std::vector<common::TrackEstimate> tracks) {
  last_tracks_ = std::max(last_tracks_, tick);
  received(tick, [&](Held& held) {
    held.tick.tracks = std::move(tracks);
    held.tracks = true;
  });
}

void MapTickAssembler::onMetrics(std::int32_t tick, std::map<std::string, double> metrics) {
  last_metrics_ = std::max(last_metrics_, tick);
  received(tick, [&](Held& held) {
    held.tick.metrics = std::move(metrics);
    held.metrics = true;
  });
}

void MapTickAssembler::settle() {
  for (auto& [tick, held] : held_) {
    if (held.given) continue;
    const bool both = held.tracks && held.metrics;
    const bool late = (held.tracks && last_tracks_ - tick >= kLateTicks) || (held.metrics && last_metrics_ - tick >= kLateTicks);
    if (!both && !late) continue;
    complete_.push_back(held.tick);
    held.given = true;
  }
  // What is given out and far behind both topics is forgotten, and anything later for it ignored:
  // the page keeps what it was given (a sample that late is one the terminal view drops too).
  const std::int32_t settled = std::min(last_tracks_, last_metrics_) - 4 * kLateTicks;
  while (!held_.empty() && held_.begin()->first < settled && held_.begin()->second.given) {
    forgotten_below_ = held_.begin()->first + 1;
    held_.erase(held_.begin());
  }
}

std::vector<MapTick> MapTickAssembler::takeComplete() { return std::exchange(complete_, {}); }

std::vector<MapTick> MapTickAssembler::flush() {
  for (auto& [tick, held] : held_)
    if (!held.given) {
      complete_.push_back(held.tick);
      held.given = true;
    }
  return takeComplete();
}

}  // namespace wsn::launcher
