#include "network_model/link_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wsn::network_model {

double successProbability(double pte, int k) {
  if (k <= 0) return 0.0;
  // Oh et al. §V: one k-hop path survives with (1 - pte)^k; all k independent paths fail with
  // (1 - (1 - pte)^k)^k.
  const double path_success = std::pow(1.0 - pte, k);
  return 1.0 - std::pow(1.0 - path_success, k);
}

double delayProbability(double pde, int k, std::int64_t d) {
  if (d < 0) return 0.0;
  if (k <= 0) return d == 0 ? 1.0 : 0.0;
  // Oh et al. eq. (7) by the ratio P(d) / P(d-1) = (k + d - 1) / d * pde, which stays finite
  // where the binomial coefficient alone would overflow.
  double p = std::pow(1.0 - pde, k);
  for (std::int64_t i = 1; i <= d && p > 0.0; ++i)
    p *= static_cast<double>(k + i - 1) / static_cast<double>(i) * pde;
  return p;
}

double delayProbabilityBelow(double pde, int k, std::int64_t limit) {
  if (limit <= 0) return 0.0;
  if (k <= 0) return 1.0;
  double p = std::pow(1.0 - pde, k);
  double cumulative = p;
  for (std::int64_t d = 1; d < limit && p > 0.0; ++d) {
    p *= static_cast<double>(k + d - 1) / static_cast<double>(d) * pde;
    cumulative += p;
  }
  return std::min(cumulative, 1.0);
}

double meanDelay(double pde, int k) {
  if (k <= 0 || pde <= 0.0) return 0.0;
  if (pde >= 1.0) return std::numeric_limits<double>::infinity();
  return static_cast<double>(k) * pde / (1.0 - pde);
}

std::int64_t drawDelay(common::Stream& stream, double pde, int k) {
  // Oh et al. eq. (7): a negative binomial is a sum of k independent geometric failure counts.
  std::int64_t total = 0;
  for (int hop = 0; hop < k; ++hop) {
    const std::uint64_t g = stream.geometric(1.0 - pde);
    if (g >= static_cast<std::uint64_t>(kInfiniteDelay - total)) {
      total = kInfiniteDelay;
      continue;
    }
    total += static_cast<std::int64_t>(g);
  }
  return total;
}

}  // namespace wsn::network_model
