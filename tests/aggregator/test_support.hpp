// Truth states and track estimates built by value for the aggregator's metric tests.
#pragma once

#include <cstdint>

#include "common/messages.hpp"
#include "common/truth.hpp"

namespace wsn::aggregator::test {

inline common::TargetState target(int id, double x, double y, double vx = 0.0, double vy = 0.0) {
  return {id, x, y, vx, vy};
}

inline common::TrackEstimate track(std::uint64_t id, double x, double y, double vx = 0.0, double vy = 0.0) {
  return {id, x, y, vx, vy, {}, 0, {}, {}};
}

}  // namespace wsn::aggregator::test
