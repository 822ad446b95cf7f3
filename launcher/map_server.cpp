#include "launcher/map_server.hpp"

#include <httplib.h>

#include <stdexcept>

namespace wsn::launcher {
namespace {

void appendEvent(std::string& out, const char* name, const std::string& json) {
  out += "event: ";
  out += name;
  out += "\ndata: ";
  out += json;
  out += "\n\n";
}

}  // namespace

void MapFeed::addTick(std::string json) {
  {
    const std::lock_guard lock(mutex_);
    ticks_.push_back(std::move(json));
  }
  changed_.notify_all();
}

void MapFeed::setStatus(std::string json) {
  {
    const std::lock_guard lock(mutex_);
    if (json == status_) return;
    status_ = std::move(json);
    ++status_version_;
  }
  changed_.notify_all();
}

bool MapFeed::next(Cursor& cursor, std::chrono::milliseconds wait, std::string& out) {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, wait, [&] {
    return closed_ || cursor.ticks < ticks_.size() || cursor.status_version != status_version_;
  });
  if (closed_) return false;
  for (; cursor.ticks < ticks_.size(); ++cursor.ticks) appendEvent(out, "tick", ticks_[cursor.ticks]);
  if (cursor.status_version != status_version_) {
    appendEvent(out, "status", status_);
    cursor.status_version = status_version_;
  }
  return true;
}

void MapFeed::close() {
  {
    const std::lock_guard lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
}

std::pair<std::string, int> parseHttpAddress(const std::string& text) {
  const auto colon = text.rfind(':');
  std::string address = colon == std::string::npos ? "127.0.0.1" : text.substr(0, colon);
  if (address.size() > 2 && address.front() == '[' && address.back() == ']')  // an IPv6 address: [::1]:8080
    address = address.substr(1, address.size() - 2);
  const std::string port_text = colon == std::string::npos ? text : text.substr(colon + 1);
  std::size_t used = 0;
  int port = -1;
  try {
    port = std::stoi(port_text, &used);
  } catch (const std::logic_error&) {
  }
  if (port_text.empty() || used != port_text.size() || port < 0 || port > 65535 || address.empty())
    throw std::invalid_argument("--http: expected [ADDR:]PORT with PORT in [0, 65535] (0: any free port), got '" +
                                text + "'");
  return {address, port};
}

MapServer::MapServer(std::string field_json, std::shared_ptr<MapFeed> feed)
    : field_json_(std::move(field_json)), feed_(std::move(feed)), server_(std::make_unique<httplib::Server>()) {
  server_->Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(mapPageHtml(), "text/html; charset=utf-8");
  });
  server_->Get("/api/run", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(field_json_, "application/json");
  });
  server_->Get("/events", [feed = feed_](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    auto cursor = std::make_shared<MapFeed::Cursor>();
    res.set_chunked_content_provider("text/event-stream", [feed, cursor](std::size_t, httplib::DataSink& sink) {
      std::string out;
      if (!feed->next(*cursor, std::chrono::seconds(1), out)) {
        sink.done();
        return false;
      }
      // A comment line when nothing happened: a closed browser tab shows up as a failed write.
      if (out.empty()) out = ":\n\n";
      return sink.write(out.data(), out.size());
    });
  });
}

MapServer::~MapServer() { stop(); }

int MapServer::start(const std::string& address, int port) {
  const int bound = port == 0 ? server_->bind_to_any_port(address) : (server_->bind_to_port(address, port) ? port : -1);
  if (bound < 0)
    throw std::runtime_error("--http: cannot listen on " + address + ":" + std::to_string(port) +
                             " (in use, or not an address of this host)");
  thread_ = std::thread([this] { server_->listen_after_bind(); });
  return bound;
}

void MapServer::stop() {
  if (feed_) feed_->close();
  if (server_) server_->stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace wsn::launcher
