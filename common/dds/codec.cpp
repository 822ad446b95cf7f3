#include "common/dds/codec.hpp"

#include <algorithm>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace wsn::dds {
namespace {

/// Converts each element of a vector with `convert`.
template <typename Out, typename In, typename F>
std::vector<Out> mapVector(const std::vector<In>& in, F convert) {
  std::vector<Out> out;
  out.reserve(in.size());
  for (const auto& element : in) out.push_back(convert(element));
  return out;
}

/// Converts each element of a received IDL sequence with `convert`.
template <typename Out, typename Seq, typename F>
std::vector<Out> mapSequence(const Seq& seq, F convert) {
  std::vector<Out> out;
  out.reserve(seq._length);
  for (std::uint32_t i = 0; i < seq._length; ++i) out.push_back(convert(seq._buffer[i]));
  return out;
}

/// Appends `values` to `pool` (whose capacity was reserved up front, so earlier views stay valid)
/// and returns a sequence over the appended part.
dds_sequence_double appendDoubles(std::vector<double>& pool, const std::vector<double>& values, std::size_t bound,
                                  const char* what) {
  if (values.size() > bound)
    throw std::length_error(std::string(what) + ": " + std::to_string(values.size()) +
                            " values, the wire holds at most " + std::to_string(bound));
  dds_sequence_double seq{};
  if (values.empty()) return seq;
  const std::size_t at = pool.size();
  pool.insert(pool.end(), values.begin(), values.end());
  seq._maximum = seq._length = static_cast<std::uint32_t>(values.size());
  seq._buffer = pool.data() + at;
  seq._release = false;
  return seq;
}

std::vector<double> copyOut(const dds_sequence_double& seq) {
  return seq._length == 0 ? std::vector<double>{} : std::vector<double>(seq._buffer, seq._buffer + seq._length);
}

}  // namespace

std::vector<wsn_msg_SensorReading> encode(const std::vector<common::SensorReading>& readings) {
  return mapVector<wsn_msg_SensorReading>(readings, [](const common::SensorReading& r) {
    return wsn_msg_SensorReading{r.sensor, r.z};
  });
}

std::vector<common::SensorReading> decode(const dds_sequence_wsn_msg_SensorReading& seq) {
  return mapSequence<common::SensorReading>(seq, [](const wsn_msg_SensorReading& r) {
    return common::SensorReading{r.sensor, r.z};
  });
}

namespace {

/// The class probabilities of `items`, counted for the reservation below.
template <typename Message>
std::size_t classDoubles(const std::vector<Message>& items) {
  std::size_t n = 0;
  for (const auto& item : items) n += item.class_probabilities.size();
  return n;
}

/// Room for `items` wire items and `doubles` class probabilities, reserved up front so that the
/// views into it stay valid.
template <typename Wire>
Encoded<Wire> withRoom(std::size_t items, std::size_t doubles) {
  Encoded<Wire> encoded;
  encoded.doubles.reserve(doubles);
  encoded.items.reserve(items);
  return encoded;
}

template <typename Wire>
wsn_msg_TrackEstimate wireTrack(const common::TrackEstimate& t, Encoded<Wire>& storage) {
  wsn_msg_TrackEstimate w{t.track, t.x, t.y, t.vx, t.vy, {}, t.last_seen_tick, {},
                          t.stop_probability.value_or(std::numeric_limits<double>::quiet_NaN())};
  std::copy(t.covariance.begin(), t.covariance.end(), w.covariance);
  w.class_probabilities = appendDoubles(storage.doubles, t.class_probabilities, common::kMaxClasses,
                                        "track class probabilities");
  return w;
}

/// NaN, what the wire sends for none, and any other value that is no probability read as none: the
/// same policy as a malformed class vector (common::receivedClassVector).
std::optional<double> stopProbabilityOf(double wire) {
  if (!(wire >= 0.0 && wire <= 1.0)) return std::nullopt;
  return wire;
}

common::TrackEstimate trackOf(const wsn_msg_TrackEstimate& t) {
  common::TrackEstimate e{t.track, t.x, t.y, t.vx, t.vy, {}, t.last_seen_tick, copyOut(t.class_probabilities),
                          stopProbabilityOf(t.stop_probability)};
  std::copy(std::begin(t.covariance), std::end(t.covariance), e.covariance.begin());
  return e;
}

}  // namespace

Encoded<wsn_msg_TrackEstimate> encode(const std::vector<common::TrackEstimate>& tracks) {
  auto encoded = withRoom<wsn_msg_TrackEstimate>(tracks.size(), classDoubles(tracks));
  for (const auto& track : tracks) encoded.items.push_back(wireTrack(track, encoded));
  return encoded;
}

std::vector<common::TrackEstimate> decode(const dds_sequence_wsn_msg_TrackEstimate& seq) {
  return mapSequence<common::TrackEstimate>(seq, [](const wsn_msg_TrackEstimate& t) { return trackOf(t); });
}

Encoded<wsn_msg_SettledTrack> encodeSettled(std::int32_t first,
                                            const std::vector<std::vector<common::TrackEstimate>>& by_tick) {
  std::size_t items = 0;
  std::size_t doubles = 0;
  for (const auto& tracks : by_tick) {
    items += tracks.size();
    doubles += classDoubles(tracks);
  }
  auto encoded = withRoom<wsn_msg_SettledTrack>(items, doubles);
  for (std::size_t k = 0; k < by_tick.size(); ++k)
    for (const auto& track : by_tick[k])
      encoded.items.push_back({first + static_cast<std::int32_t>(k), wireTrack(track, encoded)});
  return encoded;
}

namespace {

std::int64_t settledSpan(std::int32_t first, std::int32_t last) {
  return last >= first ? static_cast<std::int64_t>(last) - first + 1 : 0;
}

}  // namespace

bool settledSpanFits(std::int32_t first, std::int32_t last, std::int32_t max_ticks) {
  return settledSpan(first, last) <= max_ticks;
}

std::vector<std::vector<common::TrackEstimate>> decodeSettled(const dds_sequence_wsn_msg_SettledTrack& seq,
                                                              std::int32_t first, std::int32_t last,
                                                              std::int32_t max_ticks) {
  const std::int64_t span = settledSpan(first, last);
  if (!settledSpanFits(first, last, max_ticks))
    throw std::length_error("settled ticks " + std::to_string(first) + " .. " + std::to_string(last) + " span " +
                            std::to_string(span) + " ticks, more than the window's " + std::to_string(max_ticks));
  std::vector<std::vector<common::TrackEstimate>> by_tick(static_cast<std::size_t>(span));
  for (std::uint32_t i = 0; i < seq._length; ++i) {
    const auto& item = seq._buffer[i];
    if (item.tick < first || item.tick > last) continue;
    by_tick[static_cast<std::size_t>(item.tick - first)].push_back(trackOf(item.track));
  }
  return by_tick;
}

Encoded<wsn_msg_TrackHandoff> encode(const std::vector<common::TrackHandoff>& handoffs) {
  auto encoded = withRoom<wsn_msg_TrackHandoff>(handoffs.size(), classDoubles(handoffs));
  for (const auto& h : handoffs) {
    wsn_msg_TrackHandoff w{};
    w.track = h.track;
    w.to_supernode = h.to_supernode;
    w.last_tick = h.last_tick;
    std::copy(h.state.begin(), h.state.end(), w.state);
    std::copy(h.covariance.begin(), h.covariance.end(), w.covariance);
    w.hits = h.hits;
    w.misses = h.misses;
    w.confirmed = h.confirmed;
    w.class_probabilities = appendDoubles(encoded.doubles, h.class_probabilities, common::kMaxClasses,
                                          "handoff class probabilities");
    encoded.items.push_back(w);
  }
  return encoded;
}

std::vector<common::TrackHandoff> decode(const dds_sequence_wsn_msg_TrackHandoff& seq) {
  return mapSequence<common::TrackHandoff>(seq, [](const wsn_msg_TrackHandoff& w) {
    common::TrackHandoff h;
    h.track = w.track;
    h.to_supernode = w.to_supernode;
    h.last_tick = w.last_tick;
    std::copy(std::begin(w.state), std::end(w.state), h.state.begin());
    std::copy(std::begin(w.covariance), std::end(w.covariance), h.covariance.begin());
    h.hits = w.hits;
    h.misses = w.misses;
    h.confirmed = w.confirmed;
    h.class_probabilities = copyOut(w.class_probabilities);
    return h;
  });
}

}  // namespace wsn::dds
