// The browser map of a watch (`wsntrack watch RUN_DIR --http [ADDR:]PORT`): the server, the tick
// events it streams, and the viewer's reader of the supernodes' deliveries that the terminal view
// does not need. The watch's DDS loop hands it each sample; it never slows the run down.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/dds/entity.hpp"
#include "launcher/map_server.hpp"
#include "launcher/watch_map.hpp"
#include "wsntrack.h"

namespace wsn::launcher {

/// The map of a live run: serves from construction (the URL is printed) until destruction.
class LiveMap {
 public:
  /// Starts serving the run in `run_dir` on `address`:`port` and reads the deliveries of every
  /// supernode on `participant` (best effort: a lost delivery costs a cross on the map, never a
  /// wait of the network model), its condition attached to `waitset` with `token`.
  LiveMap(const std::string& run_dir, const std::string& address, int port, const dds::Participant& participant,
          dds::WaitSet& waitset, dds_attach_t token);

  void onTracks(std::int32_t tick, std::vector<common::TrackEstimate> tracks) { assembler_.onTracks(tick, std::move(tracks)); }
  void onMetrics(std::int32_t tick, std::map<std::string, double> metrics) { assembler_.onMetrics(tick, std::move(metrics)); }
  /// Takes the deliveries of this run that arrived, and streams every tick completed so far.
  void poll(std::uint64_t run_id);
  /// The run ended: the ticks still held are streamed and, for a run that finished, those the
  /// watch joined too late for are read from its files; the page says `state` with `text`.
  void ended(const std::string& state, const std::string& text);
  /// The page's address, e.g. http://127.0.0.1:8080/.
  const std::string& url() const { return url_; }

 private:
  std::string run_dir_;
  std::map<std::int32_t, std::vector<MapTarget>> truth_;
  std::set<std::int32_t> streamed_;
  std::shared_ptr<MapFeed> feed_ = std::make_shared<MapFeed>();
  MapServer server_;
  std::string url_;
  MapTickAssembler assembler_;
  dds::Topic<wsn_msg_DeliveryBatch> delivery_topic_;
  dds::Reader<wsn_msg_DeliveryBatch> delivery_reader_;
  dds::ReadCondition deliveries_ready_;

  void stream(std::vector<MapTick> ticks);
};

/// The map of a finished run, from its files, served until `stop()` returns true (polled every
/// 0.2 s). Prints the URL; throws std::runtime_error for unreadable files or an address in use.
void serveFinishedRun(const std::string& run_dir, const std::string& address, int port, bool (*stop)());

/// {"state": STATE, "text": TEXT} as the page reads it.
std::string mapStatusJson(const std::string& state, const std::string& text);

}  // namespace wsn::launcher
