// The per-report link model of Oh et al. §V: loss over k hops relayed on k independent paths,
// and the negative-binomial extra delay of eq. (7). Pure functions of (pte, pde, k).
#pragma once

#include <cstdint>
#include <limits>

#include "common/rng.hpp"

namespace wsn::network_model {

/// A delay that never ends (pde = 1): the report is never delivered.
inline constexpr std::int64_t kInfiniteDelay = std::numeric_limits<std::int64_t>::max();

/// Oh et al. §V: probability that a report k hops from its supernode arrives when it is relayed
/// over k independent k-hop paths whose edges each fail with probability pte,
/// pts(pte, k) = 1 - (1 - (1 - pte)^k)^k. Returns 0 for k <= 0 (no path).
double successProbability(double pte, int k);

/// Oh et al. eq. (7): P(d) = C(k+d-1, d) (1-pde)^k pde^d, the number of delayed sampling
/// intervals before k delay-less hops. 0 for d < 0; for k <= 0, all mass sits at d = 0.
double delayProbability(double pde, int k, std::int64_t d);

/// P(d < limit) under eq. (7), e.g. limit = ws: the delayed report still fits the window.
double delayProbabilityBelow(double pde, int k, std::int64_t limit);

/// E[d] = k pde / (1 - pde) under eq. (7) (infinite for pde = 1).
double meanDelay(double pde, int k);

/// Draws d from eq. (7) as the sum of k geometric failure counts with success probability
/// 1 - pde (at most one number of `stream` per hop). Saturates at kInfiniteDelay.
std::int64_t drawDelay(common::Stream& stream, double pde, int k);

}  // namespace wsn::network_model
