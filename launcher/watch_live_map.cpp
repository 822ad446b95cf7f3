#include "launcher/watch_live_map.hpp"

#include <unistd.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "common/dds/packing.hpp"
#include "common/dds/role_runtime.hpp"

namespace wsn::launcher {
namespace {

std::string urlOf(const std::string& address, int port) {
  const bool v6 = address.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + address + "]" : address) + ":" + std::to_string(port) + "/";
}

/// A map on an address other hosts can reach has no password: said once, beside its URL.
void warnIfReachable(const std::string& address, const std::string& url) {
  if (address.rfind("127.", 0) == 0 || address == "::1" || address == "localhost") return;
  std::cerr << "wsntrack watch: warning: anyone who reaches " << url
            << " can read the run's map (it has no password, whatever the run's DDS Security)\n";
}

/// A reader of the deliveries to every supernode: they go out in one partition per supernode
/// (topic_names::supernodePartition), which the pattern matches.
dds::Qos deliveriesOfEverySupernode() { return dds::Qos::bestEffort(dds::Endpoint::kViewer).inPartition("supernode-*"); }

}  // namespace

std::string mapStatusJson(const std::string& state, const std::string& text) {
  return nlohmann::json{{"state", state}, {"text", text}}.dump();
}

LiveMap::LiveMap(const std::string& run_dir, const std::string& address, int port, const dds::Participant& participant,
                 dds::WaitSet& waitset, dds_attach_t token)
    : run_dir_(run_dir),
      truth_(readMapTruth(run_dir + "/truth.csv")),
      server_(mapFieldJson(run_dir, true), feed_),
      delivery_topic_(participant, dds::topic_names::kDeliveryBatch),
      delivery_reader_(participant, delivery_topic_, deliveriesOfEverySupernode()),
      deliveries_ready_(delivery_reader_) {
  url_ = urlOf(address, server_.start(address, port));
  waitset.attach(deliveries_ready_.handle(), token);
  feed_->setStatus(mapStatusJson("live", "live: the run is going on"));
  std::cerr << "wsntrack watch: the map is at " << url_ << "\n" << std::flush;
  warnIfReachable(address, url_);
}

void LiveMap::poll(std::uint64_t run_id) {
  delivery_reader_.take([&](const wsn_msg_DeliveryBatch& batch) {
    if (batch.run_id != run_id) return;
    try {
      assembler_.onDeliveries(batch.tick, dds::unpackObservations(batch.observations, batch.tick));
    } catch (const dds::PackingError&) {
      // Not the run's own (the roles count such batches as malformed): nothing to draw.
    }
  });
  stream(assembler_.takeComplete());
}

void LiveMap::ended(const std::string& state, const std::string& text) {
  stream(assembler_.flush());
  if (state == "finished") {
    // The aggregator closes its CSV files and writes metrics.json before it reports DONE, so they
    // hold every tick by now: those the watch joined too late for come from them.
    try {
      std::vector<MapTick> missed;
      for (auto& tick : readFinishedTicks(run_dir_))
        if (!streamed_.count(tick.tick)) missed.push_back(std::move(tick));
      stream(std::move(missed));
    } catch (const std::exception& error) {
      std::cerr << "wsntrack watch: the map shows the live ticks only: " << error.what() << "\n";
    }
  }
  feed_->setStatus(mapStatusJson(state, text));
}

void LiveMap::stream(std::vector<MapTick> ticks) {
  static const std::vector<MapTarget> none;
  for (const auto& tick : ticks) {
    const auto truth = truth_.find(tick.tick);
    feed_->addTick(mapTickJson(tick, truth == truth_.end() ? none : truth->second));
    streamed_.insert(tick.tick);
  }
}

void serveFinishedRun(const std::string& run_dir, const std::string& address, int port, bool (*stop)()) {
  const auto truth = readMapTruth(run_dir + "/truth.csv");
  auto feed = std::make_shared<MapFeed>();
  static const std::vector<MapTarget> none;
  const auto ticks = readFinishedTicks(run_dir);
  for (const auto& tick : ticks) {
    const auto at = truth.find(tick.tick);
    feed->addTick(mapTickJson(tick, at == truth.end() ? none : at->second));
  }
  feed->setStatus(mapStatusJson("finished", "finished: " + std::to_string(ticks.size()) + " ticks from its files"));
  MapServer server(mapFieldJson(run_dir, false), feed);
  const std::string url = urlOf(address, server.start(address, port));
  std::cerr << "wsntrack watch: the run in " << run_dir << " has finished; its map (" << ticks.size()
            << " ticks, from its files) is at " << url << " until Ctrl-C\n"
            << std::flush;
  warnIfReachable(address, url);
  while (!stop()) ::usleep(200000);
}

}  // namespace wsn::launcher
