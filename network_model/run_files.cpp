#include "network_model/run_files.hpp"

#include <nlohmann/json.hpp>

#include "common/output.hpp"
#include "network_model/calibration.hpp"

namespace wsn::network_model {
namespace {

// Insertion order is the file's order: settings, counts, ratios, then the breakdowns.
using Json = nlohmann::ordered_json;

void putCounts(Json& json, const NetworkCounts& c, bool with_faults) {
  json["sent"] = c.sent;
  json["lost"] = c.lost;
  json["unreachable"] = c.unreachable;
  json["delivered"] = c.delivered;
  json["delayed"] = c.delayed;
  json["beyond_window"] = c.beyond_window;
  json["after_end"] = c.after_end;
  if (with_faults) json["lost_dead_supernode"] = c.lost_dead_supernode;
}

Json rehomeJson(const Rehome& r) {
  Json json;
  json["supernode"] = r.supernode;
  json["tick"] = r.tick;
  json["sensors"] = r.sensors;
  json["reachable_before"] = r.reachable_before;
  json["reachable_after"] = r.reachable_after;
  json["mean_hops_before"] = r.mean_hops_before;
  json["mean_hops_after"] = r.mean_hops_after;
  json["adopters"] = Json::array();
  for (const auto& [supernode, sensors] : r.adopters) json["adopters"].push_back({{"supernode", supernode}, {"sensors", sensors}});
  return json;
}

double ratio(std::uint64_t part, std::uint64_t whole) {
  return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
}

}  // namespace

std::string observationRow(const ReportFate& fate) {
  const auto& r = fate.report;
  const char* what = fate.hops < 0               ? "unreachable"
                     : fate.to_dead_supernode   ? kDeadSupernodeFate
                     : fate.lost                ? "lost"
                     : fate.tick_delivered < 0  ? "after_end"
                                                : "delivered";
  return std::to_string(r.tick) + "," + (fate.tick_delivered < 0 ? std::string() : std::to_string(fate.tick_delivered)) +
         "," + std::to_string(r.sensor) + "," + std::to_string(fate.supernode) + "," + std::to_string(fate.hops) + "," +
         (fate.delay < 0 ? std::string() : std::to_string(fate.delay)) + "," + common::fixed6(r.x) + "," +
         common::fixed6(r.y) + "," + std::to_string(r.target) + "," + what + "," + std::to_string(r.power_level);
}

NetworkReport networkReport(const Topology& topology, const Router& router) {
  NetworkReport report;
  report.communication_range = topology.communicationRange();
  report.pte = router.config().pte;
  report.pde = router.config().pde;
  report.mean_hops = topology.meanHops();
  report.max_hops = topology.maxHops();
  report.total = router.counts();
  for (std::uint32_t j = 0; j < topology.supernodeCount(); ++j) report.per_supernode.push_back(router.counts(j));
  return report;
}

const std::vector<NetworkQuantity>& networkQuantities() {
  static const std::vector<NetworkQuantity> quantities{
      {"reports", "reports", "reports sent", "sent", "reports the sensors sent towards a supernode"},
      {"reports_lost", "reports lost", "reports lost", "lost", "reports lost on a hop (pte)"},
      {"reports_unreachable", "unreachable", "reports unreachable", "unreachable",
       "reports with no route to their supernode"},
      {"reports_delayed", "received delayed", "reports received delayed", "delayed",
       "reports delivered one tick or more late (pde)"},
      {"delivery_ratio", "delivery ratio", "end-to-end delivery ratio", "delivered_to_total",
       "reports delivered to a supernode within the run over reports sent"},
      {"loss_ratio", "loss ratio", "end-to-end loss ratio", "lost_to_total",
       "reports lost or unreachable over reports sent"},
      {"mean_hops", "mean hops", "mean hops to the supernode", "mean_hops", "mean route length of the reports, in hops"},
  };
  return quantities;
}

std::string networkJson(const NetworkReport& report) {
  const auto& c = report.total;
  // A report is "received" when it is not lost, as in Oh §VII-E; one due after the last tick is
  // received late, so it counts as delayed too (its d > 0 by construction).
  const std::uint64_t received = c.delivered + c.after_end;
  Json json;
  json["communication_range"] = report.communication_range;
  json["pte"] = report.pte;
  json["pde"] = report.pde;
  json["mean_hops"] = report.mean_hops;
  json["max_hops"] = report.max_hops;
  putCounts(json, c, report.with_faults);
  json["rejected"] = c.rejected;
  json["lost_to_total"] = ratio(c.lost + c.unreachable + c.lost_dead_supernode, c.sent);
  // The end-to-end delivery ratio a reader understands, for sweeps' axes: delivered within the run.
  json["delivered_to_total"] = ratio(c.delivered, c.sent);
  json["delayed_to_received"] = ratio(c.delayed + c.after_end, received);
  json["supernodes"] = Json::array();
  for (std::size_t j = 0; j < report.per_supernode.size(); ++j) {
    Json group;
    group["supernode"] = j;
    putCounts(group, report.per_supernode[j], report.with_faults);
    json["supernodes"].push_back(std::move(group));
  }
  if (report.with_faults) {
    json["silent_tile_ticks"] = report.silent_tile_ticks;
    json["rehomes"] = Json::array();
    for (const auto& r : report.rehomes) json["rehomes"].push_back(rehomeJson(r));
  }
  // The paper's counts belong to one run of its own example, not to whatever this run simulated:
  // they travel as a reference that names the scenario they can be compared with.
  const auto count = [](double paper_count) { return static_cast<std::uint64_t>(paper_count); };
  json["reference_oh_vii_e"] = {
      {"applies_to", "scenarios/oh_quadrants.yaml (Oh et al. 2005, Sec. VII-E: 100 x 100 grid, 4 supernodes, "
                     "pte = pde = 0.3, T = 100); not a statement about other scenarios"},
      {"reports", count(kPaperReports)},
      {"lost_reports", count(kPaperLost)},
      {"received_reports", count(kPaperReceived)},
      {"delayed_reports", count(kPaperDelayed)}};
  return json.dump(2) + "\n";
}

}  // namespace wsn::network_model
