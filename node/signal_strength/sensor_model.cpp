#include "node/signal_strength/sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wsn::node {

double signalStrength(const signal_strength::SignalStrengthSettings& model, double distance) {
  return model.beta / (1.0 + model.gamma * std::pow(distance, model.alpha));
}

double noiseExceedanceProbability(const signal_strength::SignalStrengthSettings& model) {
  if (!(model.noise_sigma > 0.0)) return model.eta <= 0.0 ? 1.0 : 0.0;
  return 0.5 * std::erfc(model.eta / (model.noise_sigma * std::numbers::sqrt2));
}

double sampleNormalTail(common::Stream& stream, double a) {
  if (a < 0.0) {
    while (true) {
      const double w = stream.normal();
      if (w >= a) return w;
    }
  }
  const double lambda = 0.5 * (a + std::sqrt(a * a + 4.0));
  while (true) {
    const double w = a - std::log(stream.uniformPositive()) / lambda;
    const double excess = w - lambda;
    if (stream.uniform() < std::exp(-0.5 * excess * excess)) return w;
  }
}

GeometricSkips::GeometricSkips(double q) : q_(std::clamp(q, 0.0, 1.0)) {
  if (q_ > 0.0 && q_ < 1.0) {
    log_miss_ = std::log1p(-q_);
    constexpr int kTable = 64;
    all_miss_.reserve(kTable);
    for (int n = 0; n < kTable; ++n) all_miss_.push_back(std::exp(n * log_miss_) * (1.0 - 1e-12));
  }
}

std::uint64_t GeometricSkips::fromUniform(double u) const {
  if (q_ >= 1.0) return 0;
  if (q_ <= 0.0) return UINT64_MAX;
  const double g = std::floor(std::log(u) / log_miss_);
  return g >= 1.8e19 ? UINT64_MAX : static_cast<std::uint64_t>(g);
}

std::uint64_t GeometricSkips::draw(common::Stream& stream) const { return fromUniform(stream.uniformPositive()); }

std::uint64_t GeometricSkips::drawUpTo(common::Stream& stream, std::uint64_t limit) const {
  const double u = stream.uniformPositive();
  if (limit < all_miss_.size() && u < all_miss_[limit]) return limit;
  return std::min(fromUniform(u), limit);
}

}  // namespace wsn::node
