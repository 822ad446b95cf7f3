#include "network_model/link_model.hpp"

#include <catch2/catch.hpp>

#include "common/rng.hpp"

namespace nm = wsn::network_model;

TEST_CASE("success probability matches hand values of Oh's pts(pte, k)", "[network][link]") {
  // k = 1: one path of one hop, pts = 1 - (1 - 0.7)^1 = 0.7.
  CHECK(nm::successProbability(0.3, 1) == Approx(0.7).margin(1e-12));
  // k = 2: 1 - (1 - 0.7^2)^2 = 1 - 0.51^2 = 1 - 0.2601 = 0.7399.
  CHECK(nm::successProbability(0.3, 2) == Approx(0.7399).margin(1e-12));
  // k = 3: 1 - (1 - 0.343)^3 = 1 - 0.657^3 = 1 - 0.283593393 = 0.716406607.
  CHECK(nm::successProbability(0.3, 3) == Approx(0.716406607).margin(1e-9));
}

TEST_CASE("success probability is 0 without a path and at certain failure, 1 without failures", "[network][link]") {
  CHECK(nm::successProbability(0.3, 0) == 0.0);
  CHECK(nm::successProbability(0.3, -1) == 0.0);
  CHECK(nm::successProbability(1.0, 4) == Approx(0.0).margin(1e-15));
  CHECK(nm::successProbability(0.0, 7) == Approx(1.0).margin(1e-15));
}

TEST_CASE("success probability reproduces Oh's kmax = 38 at pte = 0.1", "[network][link]") {
  // Oh §VII-C: for pte = .1 the largest k with pts >= .5 is 38.
  // 0.9^38 = 0.018248, (1 - 0.018248)^38 = 0.4966 -> pts = 0.5034;
  // 0.9^39 = 0.016423, (1 - 0.016423)^39 = 0.5242 -> pts = 0.4758.
  CHECK(nm::successProbability(0.1, 38) >= 0.5);
  CHECK(nm::successProbability(0.1, 39) < 0.5);
  CHECK(nm::successProbability(0.1, 38) == Approx(0.5034).margin(1e-3));
}

TEST_CASE("delay distribution follows eq. (7) by hand", "[network][link]") {
  // k = 2, pde = 0.3: P(0) = 0.7^2 = 0.49; P(1) = C(2,1) 0.49 0.3 = 0.294;
  // P(2) = C(3,2) 0.49 0.09 = 0.1323.
  CHECK(nm::delayProbability(0.3, 2, 0) == Approx(0.49).margin(1e-12));
  CHECK(nm::delayProbability(0.3, 2, 1) == Approx(0.294).margin(1e-12));
  CHECK(nm::delayProbability(0.3, 2, 2) == Approx(0.1323).margin(1e-12));
  CHECK(nm::delayProbability(0.3, 2, -1) == 0.0);
  // P(d < 2) = 0.49 + 0.294 = 0.784; P(d < 0) = 0.
  CHECK(nm::delayProbabilityBelow(0.3, 2, 2) == Approx(0.784).margin(1e-12));
  CHECK(nm::delayProbabilityBelow(0.3, 2, 0) == 0.0);
  // The pmf sums to 1 (tail beyond 400 is below 1e-40 at pde = 0.6, k = 5).
  CHECK(nm::delayProbabilityBelow(0.6, 5, 400) == Approx(1.0).margin(1e-12));
  // Mean k pde / (1 - pde) = 2 * 0.3 / 0.7 = 0.857142857.
  CHECK(nm::meanDelay(0.3, 2) == Approx(0.857142857).margin(1e-9));
}

TEST_CASE("delay draws are zero without delay rate and endless at pde = 1", "[network][link]") {
  wsn::common::Stream stream(1, wsn::common::Purpose::kNetworkDelay, 0, 0);
  CHECK(nm::drawDelay(stream, 0.0, 5) == 0);
  CHECK(nm::drawDelay(stream, 1.0, 1) == nm::kInfiniteDelay);
  CHECK(nm::drawDelay(stream, 0.5, 0) == 0);
}
