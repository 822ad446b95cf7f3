// What the browser map of `wsntrack watch --http` shows, as JSON: the run's field (region, sensors,
// supernodes) and one event per tick (truth, delivered reports, global tracks with covariance,
// per-tick metrics), from the live DDS samples or from a finished run's files. Pure: no DDS, no HTTP.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/messages.hpp"

namespace wsn::launcher {

/// Above this many sensors the field is sent without them (their count only): a browser draws
/// 10^4 dots at once well, not 10^6.
inline constexpr std::size_t kMapMaxSensors = 20000;

/// One target of truth.csv at one tick.
struct MapTarget {
  std::int64_t id = 0;
  double x = 0.0;
  double y = 0.0;
};

/// truth.csv by tick; throws std::runtime_error "FILE:LINE: what was expected" on a malformed row.
std::map<std::int32_t, std::vector<MapTarget>> readMapTruth(const std::string& path);

/// The field of the run in `run_dir` (its scenario.yaml): name, ticks, region, supernodes and, up
/// to kMapMaxSensors, the sensors' positions, as the JSON object /api/run serves; `live` says
/// whether the run is being watched live or read from its files.
std::string mapFieldJson(const std::string& run_dir, bool live);

/// What the page draws for one tick.
struct MapTick {
  std::int32_t tick = 0;
  std::vector<common::TrackEstimate> tracks;
  std::vector<common::Observation> reports;  ///< delivered at this tick (x, y, target)
  std::map<std::string, double> metrics;     ///< the TickMetrics values (columns and running scores)
};

/// One tick as the JSON of a "tick" event: tick, truth [[id, x, y]], reports [[x, y, target]],
/// tracks [{label, x, y, vx, vy, pxx, pxy, pyy}], metrics {name: value}.
std::string mapTickJson(const MapTick& tick, const std::vector<MapTarget>& truth);

/// The ticks of a finished run, from tracks.csv, observations.csv (its delivered reports) and
/// metrics_per_tick.csv, in tick order; throws std::runtime_error "FILE:LINE: ..." on a malformed file.
std::vector<MapTick> readFinishedTicks(const std::string& run_dir);

/// Assembles the live samples of each tick into a MapTick. No order holds across topics: a tick's
/// metrics may come before its tracks. A tick is complete when both came; when only one of them did
/// and the same topic is kLateTicks ticks further on (an aggregator without TickMetrics), it is
/// complete with what it has. Whatever comes for a tick already given out gives that tick out again,
/// whole, so that the last event of every tick has all of it.
class MapTickAssembler {
 public:
  /// How many ticks one topic may run ahead of the other before a tick is given out without it.
  static constexpr std::int32_t kLateTicks = 3;

  void onDeliveries(std::int32_t tick, std::vector<common::Observation> reports);
  void onTracks(std::int32_t tick, std::vector<common::TrackEstimate> tracks);
  void onMetrics(std::int32_t tick, std::map<std::string, double> metrics);
  /// The ticks completed (or completed again) since the last call, in the order they were.
  std::vector<MapTick> takeComplete();
  /// Every tick still held (the run ended), in tick order.
  std::vector<MapTick> flush();

 private:
  struct Held {
    MapTick tick;
    bool tracks = false;
    bool metrics = false;
    bool given = false;  ///< given out already: anything more for it gives it out again
  };
  std::map<std::int32_t, Held> held_;
  std::int32_t last_tracks_ = 0;
  std::int32_t last_metrics_ = 0;
  std::int32_t forgotten_below_ = 0;  ///< ticks below this were given out and are no longer held
  std::vector<MapTick> complete_;
  /// Applies `add` to the tick's held data (nothing for a forgotten tick), gives the tick out again
  /// when it was already, and gives out what is complete now.
  void received(std::int32_t tick, const std::function<void(Held&)>& add);
  void settle();
};

}  // namespace wsn::launcher
