#include "node/signal_strength/sensor_model.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "common/rng.hpp"

using wsn::common::Purpose;
using wsn::node::signal_strength::SignalStrengthSettings;
using wsn::common::Stream;

TEST_CASE("signalStrength follows Oh eq. 5", "[node][sensor_model]") {
  const SignalStrengthSettings model;  // alpha 2, beta 9.75, gamma 1
  // beta / (1 + gamma d^alpha): d = 0 -> 9.75; d = 1 -> 9.75 / 2; d = 1.2 -> 9.75 / 2.44; d = Rs = 1.5
  // -> 9.75 / 3.25 = 3, which is why Oh §VII picks beta = 3 (1 + gamma Rs^alpha).
  CHECK(wsn::node::signalStrength(model, 0.0) == Approx(9.75).margin(1e-12));
  CHECK(wsn::node::signalStrength(model, 1.0) == Approx(4.875).margin(1e-12));
  CHECK(wsn::node::signalStrength(model, 1.2) == Approx(3.9959016393).margin(1e-9));
  CHECK(wsn::node::signalStrength(model, 1.5) == Approx(3.0).margin(1e-12));
}

TEST_CASE("noiseExceedanceProbability is the Gaussian tail beyond eta / sigma", "[node][sensor_model]") {
  SignalStrengthSettings model;
  // Q(2) = 0.5 erfc(2 / sqrt 2) = 0.0227501319.
  CHECK(wsn::node::noiseExceedanceProbability(model) == Approx(0.0227501319).margin(1e-9));
  model.noise_sigma = 2.0;  // Q(1) = 0.1586552539
  CHECK(wsn::node::noiseExceedanceProbability(model) == Approx(0.1586552539).margin(1e-9));
  model.noise_sigma = 0.0;  // noise off: z = 0 never reaches eta = 2 ...
  CHECK(wsn::node::noiseExceedanceProbability(model) == 0.0);
  model.eta = 0.0;  // ... but always reaches eta = 0.
  CHECK(wsn::node::noiseExceedanceProbability(model) == 1.0);
}

TEST_CASE("sampleNormalTail draws from the normal conditioned on the tail", "[node][sensor_model]") {
  // E[w | w >= a] = phi(a) / Q(a) and sd = sqrt(1 + a m - m^2) with m that mean:
  //   a = -1: 0.28760 (sd 0.794), a = 0: 0.79788 (0.603), a = 2: 2.37322 (0.338), a = 5: 5.18650 (0.181).
  // With n = 20000 draws the standard error is below 0.006; margins are about 4 of them.
  struct Case {
    double a, mean, margin;
  };
  for (const Case c : {Case{-1.0, 0.28760, 0.023}, Case{0.0, 0.79788, 0.018}, Case{2.0, 2.37322, 0.010},
                       Case{5.0, 5.18650, 0.006}}) {
    Stream stream(42, Purpose::kNoiseExceedance, 0, static_cast<std::int64_t>(c.a * 10));
    const int n = 20000;
    double sum = 0.0;
    double lowest = INFINITY;
    for (int i = 0; i < n; ++i) {
      const double w = wsn::node::sampleNormalTail(stream, c.a);
      sum += w;
      lowest = std::min(lowest, w);
    }
    INFO("a = " << c.a);
    CHECK(lowest >= c.a);
    CHECK(sum / n == Approx(c.mean).margin(c.margin));
  }
}

TEST_CASE("GeometricSkips counts Bernoulli(q) failures before a success", "[node][sensor_model]") {
  // Mean (1 - q) / q: q = 0.0227501 -> 42.956, sd sqrt(1 - q) / q = 43.45; 20000 draws give a
  // standard error of 0.31 (margin 1.3).
  const double q = 0.0227501319;
  const wsn::node::GeometricSkips skips(q);
  Stream stream(3, Purpose::kNoiseExceedance, 1, 1);
  double sum = 0.0;
  for (int i = 0; i < 20000; ++i) sum += static_cast<double>(skips.draw(stream));
  CHECK(sum / 20000 == Approx((1 - q) / q).margin(1.3));
  // Edge cases: q = 1 always succeeds at once, q = 0 never does.
  Stream other(3, Purpose::kNoiseExceedance, 2, 1);
  CHECK(wsn::node::GeometricSkips(1.0).draw(other) == 0);
  CHECK(wsn::node::GeometricSkips(0.0).draw(other) == UINT64_MAX);
}

TEST_CASE("GeometricSkips::drawUpTo equals the capped full draw", "[node][sensor_model]") {
  // The shortcut U <= (1 - q)^limit must never change a result: compare against the full
  // inversion on an identical stream, for limits inside and beyond the cached table.
  for (double q : {0.0227501319, 0.3, 0.97}) {
    const wsn::node::GeometricSkips skips(q);
    Stream fast(8, Purpose::kNoiseExceedance, 0, 0);
    Stream full(8, Purpose::kNoiseExceedance, 0, 0);
    int capped = 0;
    for (int i = 0; i < 50000; ++i) {
      const std::uint64_t limit = static_cast<std::uint64_t>(i % 80);
      const std::uint64_t expected = std::min(skips.draw(full), limit);
      REQUIRE(skips.drawUpTo(fast, limit) == expected);
      capped += expected == limit ? 1 : 0;
    }
    CHECK(capped > 0);
  }
}
