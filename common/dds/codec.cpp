#include "common/dds/codec.hpp"

#include <algorithm>
#include <iterator>

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

std::vector<wsn_msg_Report> encode(const std::vector<common::Report>& reports) {
  return mapVector<wsn_msg_Report>(reports, [](const common::Report& r) {
    return wsn_msg_Report{r.sensor, r.x, r.y, r.target, r.power_level};
  });
}

std::vector<common::Report> decode(const dds_sequence_wsn_msg_Report& seq, std::int32_t tick) {
  return mapSequence<common::Report>(seq, [tick](const wsn_msg_Report& r) {
    return common::Report{tick, r.sensor, r.x, r.y, r.target, r.power_level};
  });
}

std::vector<wsn_msg_Observation> encode(const std::vector<common::Observation>& observations) {
  return mapVector<wsn_msg_Observation>(observations, [](const common::Observation& o) {
    return wsn_msg_Observation{o.tick_generated, o.sensor, o.x, o.y, o.target, o.power_level};
  });
}

std::vector<common::Observation> decode(const dds_sequence_wsn_msg_Observation& seq, std::int32_t tick_delivered) {
  return mapSequence<common::Observation>(seq, [tick_delivered](const wsn_msg_Observation& o) {
    return common::Observation{o.tick_generated, tick_delivered, o.sensor, o.x, o.y, o.target, o.power_level};
  });
}

std::vector<wsn_msg_TrackEstimate> encode(const std::vector<common::TrackEstimate>& tracks) {
  return mapVector<wsn_msg_TrackEstimate>(tracks, [](const common::TrackEstimate& t) {
    wsn_msg_TrackEstimate w{t.track, t.x, t.y, t.vx, t.vy, {}, t.last_seen_tick};
    std::copy(t.covariance.begin(), t.covariance.end(), w.covariance);
    return w;
  });
}

std::vector<common::TrackEstimate> decode(const dds_sequence_wsn_msg_TrackEstimate& seq) {
  return mapSequence<common::TrackEstimate>(seq, [](const wsn_msg_TrackEstimate& t) {
    common::TrackEstimate e{t.track, t.x, t.y, t.vx, t.vy, {}, t.last_seen_tick};
    std::copy(std::begin(t.covariance), std::end(t.covariance), e.covariance.begin());
    return e;
  });
}

std::vector<wsn_msg_TrackHandoff> encode(const std::vector<common::TrackHandoff>& handoffs) {
  return mapVector<wsn_msg_TrackHandoff>(handoffs, [](const common::TrackHandoff& h) {
    wsn_msg_TrackHandoff w{};
    w.track = h.track;
    w.to_supernode = h.to_supernode;
    w.last_tick = h.last_tick;
    std::copy(h.state.begin(), h.state.end(), w.state);
    std::copy(h.covariance.begin(), h.covariance.end(), w.covariance);
    w.hits = h.hits;
    w.misses = h.misses;
    w.confirmed = h.confirmed;
    return w;
  });
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
    return h;
  });
}

}  // namespace wsn::dds
