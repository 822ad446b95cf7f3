#include "network_model/router.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>

#include "common/rng.hpp"
#include "network_model/link_model.hpp"

namespace wsn::network_model {
namespace {

/// Canonical report order: by sensor, then by every other field, so duplicates also sort
/// reproducibly (the measurement last: it only differs where x, y agree for non-position kinds).
bool reportBefore(const common::Report& a, const common::Report& b) {
  return std::tie(a.sensor, a.x, a.y, a.target, a.power_level, a.measurement) <
         std::tie(b.sensor, b.x, b.y, b.target, b.power_level, b.measurement);
}

bool observationBefore(const common::Observation& a, const common::Observation& b) {
  return std::tie(a.tick_generated, a.sensor, a.x, a.y, a.target, a.power_level, a.measurement) <
         std::tie(b.tick_generated, b.sensor, b.x, b.y, b.target, b.power_level, b.measurement);
}

}  // namespace

NetworkCounts& NetworkCounts::operator+=(const NetworkCounts& other) {
  sent += other.sent;
  lost += other.lost;
  unreachable += other.unreachable;
  delivered += other.delivered;
  delayed += other.delayed;
  beyond_window += other.beyond_window;
  after_end += other.after_end;
  lost_dead_supernode += other.lost_dead_supernode;
  rejected += other.rejected;
  return *this;
}

Router::Router(const RouterConfig& config, const Topology& topology)
    : topology_(&topology),
      config_(config),
      last_tick_(std::numeric_limits<std::int32_t>::min()),
      pending_(topology.supernodeCount()),
      per_supernode_(topology.supernodeCount()) {
  prepareLinks(config_.pte);
}

void Router::prepareLinks(double pte) {
  const auto size = static_cast<std::size_t>(topology_->maxHops()) + 1;
  if (pte == links_pte_ && success_by_hops_.size() == size) return;
  success_by_hops_.resize(size);
  for (std::size_t k = 0; k < size; ++k) success_by_hops_[k] = successProbability(pte, static_cast<int>(k));
  links_pte_ = pte;
}

void Router::loseSupernode(std::uint32_t supernode, std::int32_t from_tick) {
  config_.faults.loseUnscheduled(common::FaultRole::kSupernode, static_cast<std::int32_t>(supernode), from_tick);
  auto& group = per_supernode_.at(supernode);
  auto& store = pending_.at(supernode);
  for (auto it = store.lower_bound(from_tick); it != store.end();) {
    const auto n = static_cast<std::uint64_t>(it->second.size());
    group.delivered -= n;
    group.lost_dead_supernode += n;
    pending_count_ -= it->second.size();
    it = store.erase(it);
  }
  recountTotal();
}

void Router::recountTotal() {
  const std::uint64_t rejected = total_.rejected;
  total_ = NetworkCounts{};
  for (const NetworkCounts& group : per_supernode_) total_ += group;
  total_.rejected = rejected;
}

void Router::useTopology(const Topology& topology) {
  if (topology.sensorCount() != topology_->sensorCount() || topology.supernodeCount() != topology_->supernodeCount())
    throw std::logic_error("network router: a topology of other sensors or supernodes");
  topology_ = &topology;
  links_pte_ = -1.0;  // the hop range may differ
}

std::span<const ReportFate> Router::submit(std::int32_t tick, std::span<const common::Report> reports) {
  if (tick <= last_tick_)
    throw std::logic_error("network router: tick " + std::to_string(tick) + " submitted after tick " +
                           std::to_string(last_tick_));
  last_tick_ = tick;
  prepareLinks(config_.faults.burstPte(tick).value_or(config_.pte));

  std::vector<common::Report> ordered;
  ordered.reserve(reports.size());
  for (const common::Report& report : reports) {
    const bool valid = report.tick == tick && report.sensor < topology_->sensorCount() &&
                       std::isfinite(report.x) && std::isfinite(report.y) && common::wellFormed(report);
    if (valid)
      ordered.push_back(report);
    else
      ++total_.rejected;
  }
  std::sort(ordered.begin(), ordered.end(), reportBefore);

  std::vector<ReportFate> fates;
  fates.reserve(ordered.size());
  // A sensor sends at most one report per tick, so each report normally owns fresh streams. A
  // duplicate continues the streams of the report before it, which stays deterministic because
  // duplicates are in canonical order.
  std::optional<common::Stream> loss_stream;
  std::optional<common::Stream> delay_stream;
  for (std::size_t n = 0; n < ordered.size(); ++n) {
    const common::Report& report = ordered[n];
    if (n == 0 || ordered[n - 1].sensor != report.sensor) {
      loss_stream.emplace(config_.seed, common::Purpose::kNetworkLoss, report.sensor, tick);
      delay_stream.emplace(config_.seed, common::Purpose::kNetworkDelay, report.sensor, tick);
    }
    ReportFate fate;
    fate.report = report;
    fate.supernode = topology_->supernodeOf(report.sensor);
    fate.hops = topology_->hops(report.sensor);
    NetworkCounts& group = per_supernode_[fate.supernode];
    ++group.sent;

    if (fate.hops < 0) {
      fate.lost = true;
      ++group.unreachable;
    } else if (!loss_stream->bernoulli(success_by_hops_[static_cast<std::size_t>(fate.hops)])) {
      // Oh et al. §V: delivered with probability pts(pte, |sp(i)|).
      fate.lost = true;
      ++group.lost;
    } else {
      // Oh et al. eq. (7): d ~ NegBin(|sp(i)|, pde) extra ticks.
      const std::int64_t d = drawDelay(*delay_stream, config_.pde, fate.hops);
      fate.delay = static_cast<std::int32_t>(std::min<std::int64_t>(d, std::numeric_limits<std::int32_t>::max()));
      if (d > static_cast<std::int64_t>(config_.run_ticks) - tick) {
        ++group.after_end;
      } else if (!config_.faults.supernodeLive(static_cast<std::int32_t>(fate.supernode), static_cast<std::int32_t>(tick + d))) {
        fate.lost = true;
        fate.to_dead_supernode = true;
        fate.delay = -1;
        ++group.lost_dead_supernode;
      } else {
        fate.tick_delivered = static_cast<std::int32_t>(tick + d);
        ++group.delivered;
        if (d > 0) ++group.delayed;
        if (d >= config_.window_size) ++group.beyond_window;
        pending_[fate.supernode][fate.tick_delivered].push_back(common::observationOf(report, fate.tick_delivered));
        ++pending_count_;
      }
    }
    fates.push_back(fate);
  }

  recountTotal();

  auto& stored = fates_[tick];
  stored = std::move(fates);
  return stored;
}

std::vector<common::Observation> Router::deliveriesDue(std::int32_t tick, std::uint32_t supernode) {
  if (supernode >= pending_.size())
    throw std::out_of_range("network router: no supernode " + std::to_string(supernode));
  if (tick > last_tick_)
    throw std::logic_error("network router: deliveries of tick " + std::to_string(tick) +
                           " requested before that tick was submitted");
  auto& store = pending_[supernode];
  auto it = store.find(tick);
  if (it == store.end()) return {};
  std::vector<common::Observation> due = std::move(it->second);
  store.erase(it);
  pending_count_ -= due.size();
  std::sort(due.begin(), due.end(), observationBefore);
  return due;
}

std::span<const ReportFate> Router::fatesOf(std::int32_t tick) const {
  const auto it = fates_.find(tick);
  if (it == fates_.end()) return {};
  return it->second;
}

void Router::forgetFatesBefore(std::int32_t tick) { fates_.erase(fates_.begin(), fates_.lower_bound(tick)); }

}  // namespace wsn::network_model
