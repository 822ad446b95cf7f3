#include "network_model/router.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include <catch2/catch.hpp>

#include "network_model/link_model.hpp"

namespace nm = wsn::network_model;
using wsn::common::Observation;
using wsn::common::Report;
using wsn::common::Vec2;

namespace {

/// Supernode at the origin and sensors at x = 1..kLine on a line with range 1, so sensor id
/// k - 1 is exactly k hops away (see the topology tests).
constexpr int kLine = 6;

nm::Topology lineTopology() {
  std::vector<Vec2> sensors;
  for (int k = 1; k <= kLine; ++k) sensors.push_back({static_cast<double>(k), 0.0});
  return nm::Topology(nm::TopologyConfig{std::vector<Vec2>{{0, 0}}, 1.0}, sensors);
}

nm::RouterConfig linkConfig(double pte, double pde, std::int32_t ticks, std::uint64_t seed = 7) {
  return nm::RouterConfig{.pte = pte, .pde = pde, .run_ticks = ticks, .window_size = 10, .seed = seed};
}

Report reportOf(std::int32_t tick, wsn::common::SensorId sensor) {
  return Report{tick, sensor, static_cast<double>(sensor) + 0.25, 0.5, static_cast<wsn::common::TargetId>(sensor % 3)};
}

void checkBalanced(const nm::NetworkCounts& c) {
  CHECK(c.sent == c.lost + c.unreachable + c.delivered + c.after_end);
  CHECK(c.delayed <= c.delivered);
  CHECK(c.beyond_window <= c.delayed);
}

}  // namespace

TEST_CASE("measured loss and delay match pts, eq. (7) mean and P(d = 0) over 10^4 reports per hop count",
          "[network][router][statistics]") {
  const nm::Topology topology = lineTopology();
  // 10^4 ticks, one report per sensor per tick: 10^4 reports at each k = 1..6. The run is long
  // enough (10^6 ticks) that no delay reaches past its end.
  constexpr std::int32_t kTicks = 10000;
  struct Case {
    double pte;
    double pde;
  };
  for (const Case c : {Case{0.3, 0.3}, Case{0.1, 0.6}, Case{0.5, 0.1}}) {
    INFO("pte " << c.pte << ", pde " << c.pde);
    nm::Router router(linkConfig(c.pte, c.pde, 1000000), topology);
    std::vector<double> sent(kLine + 1, 0), lost(kLine + 1, 0), received(kLine + 1, 0), on_time(kLine + 1, 0),
        delay_sum(kLine + 1, 0);
    std::vector<Report> reports;
    for (std::int32_t t = 1; t <= kTicks; ++t) {
      reports.clear();
      for (wsn::common::SensorId s = 0; s < kLine; ++s) reports.push_back(reportOf(t, s));
      for (const nm::ReportFate& fate : router.submit(t, reports)) {
        const auto k = static_cast<std::size_t>(fate.hops);
        sent[k] += 1;
        if (fate.lost) {
          lost[k] += 1;
          continue;
        }
        received[k] += 1;
        delay_sum[k] += fate.delay;
        if (fate.delay == 0) on_time[k] += 1;
      }
      // Delivered observations are due exactly at tick_generated + d (checked against fates).
      for (const Observation& o : router.deliveriesDue(t, 0)) {
        REQUIRE(o.tick_delivered == t);
        const auto fates = router.fatesOf(o.tick_generated);
        const auto it = std::find_if(fates.begin(), fates.end(), [&](const nm::ReportFate& f) {
          return f.report.sensor == o.sensor;
        });
        REQUIRE(it != fates.end());
        REQUIRE(it->tick_delivered == t);
        REQUIRE(o.tick_generated + it->delay == t);
      }
    }
    for (int k = 1; k <= kLine; ++k) {
      INFO("k " << k);
      const auto i = static_cast<std::size_t>(k);
      REQUIRE(sent[i] == kTicks);
      // Loss ratio vs 1 - pts within 4 binomial sigma, sigma = sqrt(p (1 - p) / n).
      const double p_lost = 1.0 - nm::successProbability(c.pte, k);
      CHECK(lost[i] / sent[i] == Approx(p_lost).margin(4.0 * std::sqrt(p_lost * (1.0 - p_lost) / sent[i]) + 1e-12));
      // Mean delay vs k pde / (1 - pde) within 4 standard errors; NegBin variance k pde / (1 - pde)^2.
      const double mean = nm::meanDelay(c.pde, k);
      const double variance = k * c.pde / ((1.0 - c.pde) * (1.0 - c.pde));
      CHECK(delay_sum[i] / received[i] == Approx(mean).margin(4.0 * std::sqrt(variance / received[i])));
      // P(d = 0) = (1 - pde)^k within 4 binomial sigma.
      const double p0 = std::pow(1.0 - c.pde, k);
      CHECK(on_time[i] / received[i] == Approx(p0).margin(4.0 * std::sqrt(p0 * (1.0 - p0) / received[i]) + 1e-12));
    }
    checkBalanced(router.counts());
    // Everything delivered up to the last tick was collected; the rest is still pending.
    CHECK(router.counts().after_end == 0);
  }
}

TEST_CASE("reports in a different order or split differently get identical fates and deliveries",
          "[network][router][determinism]") {
  const nm::Topology topology = lineTopology();
  const auto config = linkConfig(0.3, 0.5, 60);
  nm::Router a(config, topology);
  nm::Router b(config, topology);
  for (std::int32_t t = 1; t <= 50; ++t) {
    std::vector<Report> forward;
    for (wsn::common::SensorId s = 0; s < kLine; ++s) forward.push_back(reportOf(t, s));
    // b sees the same reports as two tiles concatenated in reverse order, each reversed.
    std::vector<Report> backward(forward.rbegin(), forward.rend());
    std::rotate(backward.begin(), backward.begin() + 2, backward.end());
    const auto fa = a.submit(t, forward);
    const auto fb = b.submit(t, backward);
    REQUIRE(std::vector<nm::ReportFate>(fa.begin(), fa.end()) == std::vector<nm::ReportFate>(fb.begin(), fb.end()));
    // Canonical order: by sensor id.
    for (std::size_t i = 1; i < fa.size(); ++i) CHECK(fa[i - 1].report.sensor < fa[i].report.sensor);
    REQUIRE(a.deliveriesDue(t, 0) == b.deliveriesDue(t, 0));
  }
  CHECK(a.counts() == b.counts());
}

TEST_CASE("a different seed gives different fates", "[network][router][determinism]") {
  const nm::Topology topology = lineTopology();
  nm::Router a(linkConfig(0.3, 0.5, 100, 1), topology);
  nm::Router b(linkConfig(0.3, 0.5, 100, 2), topology);
  bool differs = false;
  for (std::int32_t t = 1; t <= 20; ++t) {
    std::vector<Report> reports;
    for (wsn::common::SensorId s = 0; s < kLine; ++s) reports.push_back(reportOf(t, s));
    const auto fa = a.submit(t, reports);
    const auto fb = b.submit(t, reports);
    differs = differs || !std::equal(fa.begin(), fa.end(), fb.begin(), fb.end());
  }
  CHECK(differs);
}

TEST_CASE("deliveries are due at t + d in (tick_generated, sensor) order and are handed out once",
          "[network][router]") {
  const nm::Topology topology = lineTopology();
  nm::Router router(linkConfig(0.0, 0.6, 200), topology);
  std::vector<nm::ReportFate> all;
  std::uint64_t collected = 0;
  for (std::int32_t t = 1; t <= 200; ++t) {
    std::vector<Report> reports;
    for (wsn::common::SensorId s = 0; s < kLine; ++s) reports.push_back(reportOf(t, s));
    const auto fates = router.submit(t, reports);
    all.insert(all.end(), fates.begin(), fates.end());
    const auto due = router.deliveriesDue(t, 0);
    collected += due.size();
    for (std::size_t i = 1; i < due.size(); ++i)
      CHECK(std::tie(due[i - 1].tick_generated, due[i - 1].sensor) < std::tie(due[i].tick_generated, due[i].sensor));
    // The same tick a second time is empty: nothing is handed out twice.
    CHECK(router.deliveriesDue(t, 0).empty());
    // Expected: exactly the fates with tick_delivered == t, carried over unchanged.
    std::vector<Observation> expected;
    for (const nm::ReportFate& f : all)
      if (f.tick_delivered == t)
        expected.push_back({f.report.tick, t, f.report.sensor, f.report.x, f.report.y, f.report.target});
    std::sort(expected.begin(), expected.end(), [](const Observation& x, const Observation& y) {
      return std::tie(x.tick_generated, x.sensor) < std::tie(y.tick_generated, y.sensor);
    });
    CHECK(due == expected);
  }
  // pte = 0: nothing lost; pde = 0.6 with k up to 6 delays many reports past tick 200.
  const auto& c = router.counts();
  CHECK(c.lost == 0);
  CHECK(c.after_end > 0);
  CHECK(c.delivered == collected);
  CHECK(router.pendingCount() == 0);
  checkBalanced(c);
  for (const nm::ReportFate& f : all) {
    if (f.tick_delivered < 0) {
      CHECK(f.report.tick + static_cast<std::int64_t>(f.delay) > 200);
    } else {
      CHECK(f.tick_delivered == f.report.tick + f.delay);
    }
  }
}

TEST_CASE("counters add up per supernode and in total, with unreachable and after-end reports",
          "[network][router]") {
  // Two supernodes: A = (0, 0) with a line of sensors 0..2 at x = 1, 2, 3; B = (10, 0) with
  // sensor 3 at (10.5, 0) (1 hop) and sensor 4 at (13, 0), out of range of everything.
  const std::vector<Vec2> sensors{{1, 0}, {2, 0}, {3, 0}, {10.5, 0}, {13, 0}};
  const nm::Topology topology(nm::TopologyConfig{std::vector<Vec2>{{0, 0}, {10, 0}}, 1.0}, sensors);
  REQUIRE(topology.hops(4) == -1);
  auto config = linkConfig(0.3, 0.5, 30);
  config.window_size = 2;
  nm::Router router(config, topology);
  for (std::int32_t t = 1; t <= 30; ++t) {
    std::vector<Report> reports;
    for (wsn::common::SensorId s = 0; s < 5; ++s) reports.push_back(reportOf(t, s));
    router.submit(t, reports);
    router.deliveriesDue(t, 0);
    router.deliveriesDue(t, 1);
  }
  const auto& total = router.counts();
  CHECK(total.sent == 150);  // 5 sensors x 30 ticks
  CHECK(total.unreachable == 30);  // sensor 4 every tick
  CHECK(router.counts(1).unreachable == 30);
  CHECK(router.counts(0).unreachable == 0);
  CHECK(router.counts(0).sent == 90);
  CHECK(router.counts(1).sent == 60);
  checkBalanced(total);
  checkBalanced(router.counts(0));
  checkBalanced(router.counts(1));
  CHECK(total.lost > 0);
  CHECK(total.delayed > 0);
  CHECK(total.beyond_window > 0);
  nm::NetworkCounts sum = router.counts(0);
  sum += router.counts(1);
  CHECK(sum == total);
  CHECK(router.pendingCount() == 0);
  // Unreachable reports are marked lost with hops -1 and no delay.
  for (const nm::ReportFate& f : router.fatesOf(5))
    if (f.report.sensor == 4) {
      CHECK(f.lost);
      CHECK(f.hops == -1);
      CHECK(f.delay == -1);
      CHECK(f.tick_delivered == -1);
      CHECK(f.supernode == 1);
    }
}

TEST_CASE("malformed reports are rejected and counted, not routed", "[network][router]") {
  const nm::Topology topology = lineTopology();
  nm::Router router(linkConfig(0.0, 0.0, 10), topology);
  const std::vector<Report> reports{
      reportOf(3, 1),                                                    // fine
      reportOf(2, 2),                                                    // wrong tick
      Report{3, 99, 1.0, 1.0, 0},                                        // unknown sensor
      Report{3, 3, std::numeric_limits<double>::quiet_NaN(), 1.0, 0},    // non-finite position
  };
  const auto fates = router.submit(3, reports);
  REQUIRE(fates.size() == 1);
  CHECK(fates[0].report == reportOf(3, 1));
  // pte = pde = 0: delivered on time.
  CHECK(fates[0].tick_delivered == 3);
  CHECK(router.counts().rejected == 3);
  CHECK(router.counts().sent == 1);
  CHECK(router.deliveriesDue(3, 0).size() == 1);
}

TEST_CASE("a report's measurement reaches the supernode as sent, and a malformed one is rejected", "[network][router]") {
  const nm::Topology topology = lineTopology();
  nm::Router router(linkConfig(0.0, 0.0, 10), topology);
  // Sensor 1 stands at (2, 0): a bearing report lies at the sensor.
  wsn::common::Measurement measured;
  measured.kind = wsn::common::MeasurementKind::bearing;
  measured.values = {0.3};
  measured.noise = {0.01};
  measured.sensor = wsn::common::SensorPose{2.0, 0.0, 0.5};
  measured.class_likelihoods = {0.9, 0.1};
  Report bearing{3, 1, 2.0, 0.0, 0, 0, wsn::common::MeasurementRef(measured)};
  Report no_pose = bearing;
  no_pose.sensor = 2;
  measured.sensor.reset();
  no_pose.measurement = wsn::common::MeasurementRef(measured);
  Report stale_position = reportOf(3, 3);
  stale_position.measurement =
      wsn::common::MeasurementRef(wsn::common::Measurement::position(stale_position.x, stale_position.y));
  stale_position.x += 1.0;  // the measurement still says the old x
  const std::vector<Report> reports{bearing, no_pose, stale_position, reportOf(3, 4)};

  const auto fates = router.submit(3, reports);
  REQUIRE(fates.size() == 2);
  CHECK(router.counts().rejected == 2);
  const auto delivered = router.deliveriesDue(3, 0);
  REQUIRE(delivered.size() == 2);
  CHECK(delivered[0].sensor == 1);
  CHECK(delivered[0].measurement == bearing.measurement);
  CHECK(delivered[1].measurement.get() == nullptr);  // a plain position stays plain
}

TEST_CASE("ticks must move forward and deliveries wait for their tick's submission", "[network][router]") {
  const nm::Topology topology = lineTopology();
  nm::Router router(linkConfig(0.3, 0.3, 10), topology);
  router.submit(4, {});
  CHECK_THROWS_AS(router.submit(4, {}), std::logic_error);
  CHECK_THROWS_AS(router.submit(3, {}), std::logic_error);
  CHECK_THROWS_AS(router.deliveriesDue(5, 0), std::logic_error);
  CHECK_THROWS_AS(router.deliveriesDue(4, 1), std::out_of_range);
  CHECK(router.deliveriesDue(4, 0).empty());
}

TEST_CASE("two reports from one sensor in one tick are both routed, reproducibly", "[network][router]") {
  const nm::Topology topology = lineTopology();
  const auto config = linkConfig(0.3, 0.3, 100);
  nm::Router a(config, topology);
  nm::Router b(config, topology);
  Report first = reportOf(1, 4);
  Report second = first;
  second.x += 0.5;
  const std::vector<Report> ab{first, second};
  const std::vector<Report> ba{second, first};
  const auto fa = a.submit(1, ab);
  const auto fb = b.submit(1, ba);
  REQUIRE(fa.size() == 2);
  CHECK(std::vector<nm::ReportFate>(fa.begin(), fa.end()) == std::vector<nm::ReportFate>(fb.begin(), fb.end()));
  CHECK(fa[0].report == first);
}

TEST_CASE("forgotten fates free their ticks only", "[network][router]") {
  const nm::Topology topology = lineTopology();
  nm::Router router(linkConfig(0.3, 0.3, 10), topology);
  for (std::int32_t t = 1; t <= 3; ++t) router.submit(t, std::vector<Report>{reportOf(t, 0)});
  router.forgetFatesBefore(3);
  CHECK(router.fatesOf(1).empty());
  CHECK(router.fatesOf(2).empty());
  CHECK(router.fatesOf(3).size() == 1);
}
