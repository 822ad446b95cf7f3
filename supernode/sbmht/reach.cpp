#include "supernode/sbmht/reach.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wsn::supernode::sbmht {

using common::kX;
using common::kY;

ReachUpdate constrainToReach(const common::GaussianState& estimate, common::Vec2 sensor, double range) {
  ReachUpdate out{estimate, 1.0};
  const double dx = estimate.x(kX) - sensor.x;
  const double dy = estimate.x(kY) - sensor.y;
  const double d = std::hypot(dx, dy);
  if (d < 1e-9) return out;
  common::StateVector c = common::StateVector::Zero();
  c(kX) = dx / d;
  c(kY) = dy / d;
  const common::StateVector Pc = estimate.P * c;
  const double s2 = c.dot(Pc);
  if (!(s2 > 0.0)) {
    out.probability = d <= range ? 1.0 : 0.0;
    return out;
  }
  const double s = std::sqrt(s2);
  const double b = (range - d) / s;
  const double Phi = 0.5 * std::erfc(-b / std::numbers::sqrt2);
  // Far inside reach the truncation changes nothing a double can hold; far beyond it, nothing is left.
  if (Phi >= 1.0) return out;
  if (!(Phi > 1e-300)) {
    out.probability = 0.0;
    return out;
  }
  const double phi = std::exp(-0.5 * b * b) / std::sqrt(2.0 * std::numbers::pi);
  const double lambda = phi / Phi;
  const double mean = d - s * lambda;
  const double variance = std::max(0.0, s2 * (1.0 - b * lambda - lambda * lambda));
  out.state.x = estimate.x + Pc * ((mean - d) / s2);
  out.state.P = estimate.P - Pc * Pc.transpose() * ((s2 - variance) / (s2 * s2));
  out.state.P = 0.5 * (out.state.P + out.state.P.transpose());
  out.probability = Phi;
  return out;
}

}  // namespace wsn::supernode::sbmht
