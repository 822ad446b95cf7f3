// Conversions between the wire types generated from idl/wsntrack.idl and the plain C++
// messages of common/messages.hpp. Encoding hands no ownership to Cyclone: flat items are returned
// by value, and nested sequences (a report's measurement) point into storage the result owns;
// decoding copies out of the loaned sample.
#pragma once

#include <cstdint>
#include <vector>

#include "common/messages.hpp"
#include "wsntrack.h"

namespace wsn::dds {

/// A decoded batch: who produced it, for which tick, and its items.
template <typename Item>
struct Batch {
  std::uint64_t run_id = 0;
  std::uint32_t producer = 0;
  std::int32_t tick = 0;
  std::vector<Item> items;
};

/// Builds a sequence view over a vector; valid while the vector lives and is not resized.
template <typename Seq, typename T>
Seq sequenceView(std::vector<T>& items) {
  Seq seq{};
  seq._maximum = static_cast<std::uint32_t>(items.size());
  seq._length = static_cast<std::uint32_t>(items.size());
  seq._buffer = items.data();
  seq._release = false;
  return seq;
}

std::vector<wsn_msg_SensorReading> encode(const std::vector<common::SensorReading>& readings);
std::vector<common::SensorReading> decode(const dds_sequence_wsn_msg_SensorReading& seq);

/// Wire items with the storage their nested sequences point into, so that the messages they were
/// encoded from may go before the write. Move-only: a moved vector keeps its buffer where it was,
/// a copied one would leave the items pointing into the original.
template <typename Wire>
struct Encoded {
  std::vector<Wire> items;
  std::vector<double> doubles;  ///< the items' class probabilities

  Encoded() = default;
  Encoded(Encoded&&) noexcept = default;
  Encoded& operator=(Encoded&&) noexcept = default;
  Encoded(const Encoded&) = delete;
  Encoded& operator=(const Encoded&) = delete;
};

/// Throws std::length_error for a class vector longer than kMaxClasses.
Encoded<wsn_msg_TrackEstimate> encode(const std::vector<common::TrackEstimate>& tracks);
std::vector<common::TrackEstimate> decode(const dds_sequence_wsn_msg_TrackEstimate& seq);

/// The settled estimate of ticks first .. first + by_tick.size() - 1 as flat (tick, track) items.
Encoded<wsn_msg_SettledTrack> encodeSettled(std::int32_t first,
                                            const std::vector<std::vector<common::TrackEstimate>>& by_tick);
/// Whether the settled ticks first .. last span at most max_ticks ticks (none when last < first): a
/// batch settles at most a window's worth, so a receiver refuses a batch for which this is false.
bool settledSpanFits(std::int32_t first, std::int32_t last, std::int32_t max_ticks);

/// The tracks of each tick first .. last (empty when last < first); items outside are ignored.
/// Throws std::length_error unless settledSpanFits (a receiver checks that first and refuses the
/// batch), so a malformed sample cannot make it allocate without bound.
std::vector<std::vector<common::TrackEstimate>> decodeSettled(const dds_sequence_wsn_msg_SettledTrack& seq,
                                                              std::int32_t first, std::int32_t last,
                                                              std::int32_t max_ticks);

Encoded<wsn_msg_TrackHandoff> encode(const std::vector<common::TrackHandoff>& handoffs);
std::vector<common::TrackHandoff> decode(const dds_sequence_wsn_msg_TrackHandoff& seq);

}  // namespace wsn::dds
