// The HTTP side of `wsntrack watch --http`: a read-only server (Debian's cpp-httplib) of the map
// page, the run's field and a Server-Sent Events stream of its ticks, fed by the watch's DDS loop.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace httplib {
class Server;
}

namespace wsn::launcher {

/// Every tick event so far and the run's state, shared by the DDS loop (which adds) and the
/// server's connections (each reads from its own position). Thread-safe.
class MapFeed {
 public:
  /// Where one connection has read up to.
  struct Cursor {
    std::size_t ticks = 0;
    std::size_t status_version = 0;
  };

  /// A tick's event (mapTickJson), after those added before it.
  void addTick(std::string json);
  /// The run's state as the page shows it: {"state": "waiting"|"live"|"finished"|"failed", "text": ...}.
  void setStatus(std::string json);
  /// Waits up to `wait` for what `cursor` has not seen; appends it as Server-Sent Events (every new
  /// tick, then the state if it changed) to `out` and moves the cursor. False once closed.
  bool next(Cursor& cursor, std::chrono::milliseconds wait, std::string& out);
  /// Ends every stream (the server stops).
  void close();

 private:
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<std::string> ticks_;
  std::string status_ = R"({"state":"waiting","text":"waiting for the run"})";
  std::size_t status_version_ = 1;
  bool closed_ = false;
};

/// "[ADDR:]PORT" as (address, port): 127.0.0.1 without an address, so that the map is seen from
/// this host only unless asked; port 0 takes any free port. std::invalid_argument saying what was
/// expected otherwise.
std::pair<std::string, int> parseHttpAddress(const std::string& text);

/// The server: GET / (the page), /api/run (the field), /events (the ticks as Server-Sent Events);
/// nothing else, and nothing that changes anything.
class MapServer {
 public:
  MapServer(std::string field_json, std::shared_ptr<MapFeed> feed);
  ~MapServer();
  MapServer(const MapServer&) = delete;
  MapServer& operator=(const MapServer&) = delete;

  /// Binds `address`:`port` (0: any free port) and serves on a thread of its own; returns the port.
  /// std::runtime_error when the address cannot be bound.
  int start(const std::string& address, int port);
  /// Ends the streams, stops serving and joins the thread (also on destruction).
  void stop();

 private:
  std::string field_json_;
  std::shared_ptr<MapFeed> feed_;
  std::unique_ptr<httplib::Server> server_;
  std::thread thread_;
};

/// The page itself: HTML, CSS and JavaScript in one document, with no outside resource.
const char* mapPageHtml();

}  // namespace wsn::launcher
