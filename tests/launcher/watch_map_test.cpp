// The browser map's data (launcher/watch_map.cpp) and its server's pieces (launcher/map_server.cpp):
// ticks assembled from the live samples, their JSON, a finished run read from its files, the
// Server-Sent Events of the feed, and the --http address.
#include "launcher/watch_map.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/track_id.hpp"
#include "launcher/map_server.hpp"

namespace wsn::launcher {
namespace {

namespace fs = std::filesystem;

common::TrackEstimate track(std::uint64_t serial, double x) {
  common::TrackEstimate t;
  t.track = common::track_id::supernodeSerial(0, serial);
  t.x = x;
  t.covariance[0] = 0.25;
  t.covariance[1] = t.covariance[4] = 0.05;
  t.covariance[5] = 0.5;
  return t;
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST_CASE("a tick is given out once it has its tracks and its metrics, in either order", "[launcher][map]") {
  MapTickAssembler assembler;
  common::Observation report;
  report.x = 3.0;
  assembler.onDeliveries(1, {report});
  assembler.onTracks(1, {track(1, 2.0)});
  CHECK(assembler.takeComplete().empty());  // the metrics of tick 1 are still to come
  assembler.onMetrics(1, {{"ospa", 0.5}});
  auto done = assembler.takeComplete();
  REQUIRE(done.size() == 1);
  CHECK(done[0].tick == 1);
  CHECK(done[0].reports.size() == 1);
  CHECK(done[0].tracks.size() == 1);
  CHECK(done[0].metrics.at("ospa") == 0.5);
  // No order holds across topics: tick 2's metrics before its tracks.
  assembler.onMetrics(2, {{"ospa", 0.25}});
  CHECK(assembler.takeComplete().empty());
  assembler.onTracks(2, {track(1, 2.5), track(2, 7.0)});
  done = assembler.takeComplete();
  REQUIRE(done.size() == 1);
  CHECK(done[0].tracks.size() == 2);
  CHECK(done[0].metrics.at("ospa") == 0.25);
}

TEST_CASE("a tick still missing a topic goes out late, and again whole when the rest comes", "[launcher][map]") {
  MapTickAssembler assembler;
  // The tracks of ticks 1 to 4 come, and the metrics lag: tick 1 goes out with its tracks alone
  // when the tracks are kLateTicks ahead.
  for (std::int32_t t = 1; t <= 1 + MapTickAssembler::kLateTicks; ++t) assembler.onTracks(t, {track(1, t)});
  auto done = assembler.takeComplete();
  REQUIRE(done.size() == 1);
  CHECK(done[0].tick == 1);
  CHECK(done[0].metrics.empty());
  // Its metrics after all: tick 1 again, whole (the page keeps the last event of a tick).
  assembler.onMetrics(1, {{"ospa", 1.0}});
  done = assembler.takeComplete();
  REQUIRE(done.size() == 1);
  CHECK(done[0].tick == 1);
  CHECK(done[0].tracks.size() == 1);
  CHECK(done[0].metrics.at("ospa") == 1.0);
  // The end of the run gives out what is held, in tick order.
  done = assembler.flush();
  REQUIRE(done.size() == 3);
  CHECK(done.front().tick == 2);
  CHECK(done.back().tick == 4);
}

TEST_CASE("a tick's JSON has its truth, reports, labelled tracks and metrics", "[launcher][map]") {
  MapTick tick;
  tick.tick = 7;
  tick.tracks = {track(4, 1.5)};
  tick.tracks[0].y = std::nan("");
  common::Observation report;
  report.x = 1.0;
  report.y = 2.0;
  tick.reports = {report};
  tick.metrics = {{"ospa", 0.25}, {"tracks", 1}};
  const auto json = nlohmann::json::parse(mapTickJson(tick, {{5, 1.25, 2.5}}));
  CHECK(json.at("tick") == 7);
  CHECK(json.at("truth") == nlohmann::json::parse("[[5, 1.25, 2.5]]"));
  CHECK(json.at("reports") == nlohmann::json::parse("[[1.0, 2.0, -1]]"));  // a false alarm: target -1
  const auto& t = json.at("tracks").at(0);
  CHECK(t.at("label") == "0:4");
  CHECK(t.at("x") == 1.5);
  CHECK(t.at("y").is_null());  // NaN has no JSON form
  CHECK(t.at("pxx") == 0.25);
  CHECK(t.at("pxy") == 0.05);
  CHECK(t.at("pyy") == 0.5);
  CHECK(json.at("metrics").at("ospa") == 0.25);
}

TEST_CASE("a finished run's ticks come from its files, and a malformed row is named", "[launcher][map]") {
  const fs::path dir = fs::temp_directory_path() / ("wsn-map-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  write(dir / "tracks.csv", "tick,track,label,x,y,vx,vy,p_xx,p_xy,p_xvx,p_xvy,p_yy\n"
                            "1,281474976710657,0:1,1,2,0,0,0.1,0.02,0,0,0.3\n2,281474976710657,0:1,2,2,0,0,0.1,0,0,0,0.3\n");
  write(dir / "observations.csv", "tick_generated,tick_delivered,sensor,supernode,hops,delay,x,y,target,fate,level\n"
                                  "1,2,5,0,1,1,1.5,2.5,0,delivered,0\n1,,6,0,1,,9,9,-1,lost,0\n");
  write(dir / "metrics_per_tick.csv", "tick,truth_targets,tracks,ospa\n1,1,1,0.5\n2,1,1,0.25\n");
  write(dir / "truth.csv", "tick,target,x,y,vx,vy,class\n1,0,1,2,1,0,unknown\n");
  const auto ticks = readFinishedTicks(dir.string());
  REQUIRE(ticks.size() == 2);
  CHECK(ticks[0].tracks.size() == 1);
  CHECK(ticks[0].tracks[0].covariance[1] == 0.02);
  CHECK(ticks[0].tracks[0].covariance[4] == 0.02);
  CHECK(ticks[0].reports.empty());  // delivered at tick 2; the lost one never
  REQUIRE(ticks[1].reports.size() == 1);
  CHECK(ticks[1].reports[0].x == 1.5);
  CHECK(ticks[1].metrics.at("ospa") == 0.25);
  CHECK(readMapTruth((dir / "truth.csv").string()).at(1).size() == 1);

  write(dir / "metrics_per_tick.csv", "tick,truth_targets,tracks,ospa\n1,1,1,0.5\n2,1,1,x\n");
  CHECK_THROWS_WITH(readFinishedTicks(dir.string()),
                    (dir / "metrics_per_tick.csv").string() + ":3: column 'ospa' must be a number, got 'x'");
  write(dir / "tracks.csv", "tick,track,x\n");
  CHECK_THROWS_WITH(readFinishedTicks(dir.string()),
                    (dir / "tracks.csv").string() + ":1: expected a column 'y' in the header");
  fs::remove_all(dir);
}

TEST_CASE("the feed streams every tick, then the state when it changes, from each cursor", "[launcher][map]") {
  MapFeed feed;
  MapFeed::Cursor early;
  std::string out;
  REQUIRE(feed.next(early, std::chrono::milliseconds(0), out));
  CHECK(out == "event: status\ndata: {\"state\":\"waiting\",\"text\":\"waiting for the run\"}\n\n");
  feed.addTick("{\"tick\":1}");
  feed.addTick("{\"tick\":2}");
  feed.setStatus("{\"state\":\"finished\"}");
  out.clear();
  REQUIRE(feed.next(early, std::chrono::milliseconds(0), out));
  CHECK(out == "event: tick\ndata: {\"tick\":1}\n\nevent: tick\ndata: {\"tick\":2}\n\n"
               "event: status\ndata: {\"state\":\"finished\"}\n\n");
  MapFeed::Cursor late;  // a browser that connects now gets the whole history
  std::string history;
  REQUIRE(feed.next(late, std::chrono::milliseconds(0), history));
  CHECK(history == out);
  out.clear();
  REQUIRE(feed.next(early, std::chrono::milliseconds(10), out));  // nothing new: an empty wait
  CHECK(out.empty());
  feed.close();
  CHECK_FALSE(feed.next(early, std::chrono::milliseconds(0), out));
}

TEST_CASE("the map address is a port, or an address and a port, and nothing else", "[launcher][map]") {
  CHECK(parseHttpAddress("8080") == std::pair<std::string, int>{"127.0.0.1", 8080});
  CHECK(parseHttpAddress("0") == std::pair<std::string, int>{"127.0.0.1", 0});
  CHECK(parseHttpAddress("0.0.0.0:9000") == std::pair<std::string, int>{"0.0.0.0", 9000});
  CHECK(parseHttpAddress("[::1]:8080") == std::pair<std::string, int>{"::1", 8080});
  for (const char* bad : {"", "x", "70000", "-1", ":80", "127.0.0.1:", "80x"})
    CHECK_THROWS_WITH(parseHttpAddress(bad), Catch::Contains("expected [ADDR:]PORT"));
}

}  // namespace
}  // namespace wsn::launcher
