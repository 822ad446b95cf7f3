#include "common/dds/codec.hpp"

#include <algorithm>

namespace wsn::dds {

std::vector<wsn_msg_SensorReading> encode(const std::vector<common::SensorReading>& readings) {
  std::vector<wsn_msg_SensorReading> out;
  out.reserve(readings.size());
  for (const auto& r : readings) out.push_back({r.sensor, r.z});
  return out;
}

std::vector<common::SensorReading> decode(const dds_sequence_wsn_msg_SensorReading& seq) {
  std::vector<common::SensorReading> out;
  out.reserve(seq._length);
  for (std::uint32_t i = 0; i < seq._length; ++i) out.push_back({seq._buffer[i].sensor, seq._buffer[i].z});
  return out;
}

std::vector<wsn_msg_Report> encode(const std::vector<common::Report>& reports) {
  std::vector<wsn_msg_Report> out;
  out.reserve(reports.size());
  for (const auto& r : reports) out.push_back({r.sensor, r.x, r.y, r.target});
  return out;
}

std::vector<common::Report> decode(const dds_sequence_wsn_msg_Report& seq, std::int32_t tick) {
  std::vector<common::Report> out;
  out.reserve(seq._length);
  for (std::uint32_t i = 0; i < seq._length; ++i) {
    const auto& r = seq._buffer[i];
    out.push_back({tick, r.sensor, r.x, r.y, r.target});
  }
  return out;
}

std::vector<wsn_msg_Observation> encode(const std::vector<common::Observation>& observations) {
  std::vector<wsn_msg_Observation> out;
  out.reserve(observations.size());
  for (const auto& o : observations) out.push_back({o.tick_generated, o.sensor, o.x, o.y, o.target});
  return out;
}

std::vector<common::Observation> decode(const dds_sequence_wsn_msg_Observation& seq, std::int32_t tick_delivered) {
  std::vector<common::Observation> out;
  out.reserve(seq._length);
  for (std::uint32_t i = 0; i < seq._length; ++i) {
    const auto& o = seq._buffer[i];
    out.push_back({o.tick_generated, tick_delivered, o.sensor, o.x, o.y, o.target});
  }
  return out;
}

std::vector<wsn_msg_TrackEstimate> encode(const std::vector<common::TrackEstimate>& tracks) {
  std::vector<wsn_msg_TrackEstimate> out;
  out.reserve(tracks.size());
  for (const auto& t : tracks) out.push_back({t.track, t.x, t.y, t.vx, t.vy});
  return out;
}

std::vector<common::TrackEstimate> decode(const dds_sequence_wsn_msg_TrackEstimate& seq) {
  std::vector<common::TrackEstimate> out;
  out.reserve(seq._length);
  for (std::uint32_t i = 0; i < seq._length; ++i) {
    const auto& t = seq._buffer[i];
    out.push_back({t.track, t.x, t.y, t.vx, t.vy});
  }
  return out;
}

std::vector<wsn_msg_TrackHandoff> encode(const std::vector<common::TrackHandoff>& handoffs) {
  std::vector<wsn_msg_TrackHandoff> out;
  out.reserve(handoffs.size());
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
    out.push_back(w);
  }
  return out;
}

std::vector<common::TrackHandoff> decode(const dds_sequence_wsn_msg_TrackHandoff& seq) {
  std::vector<common::TrackHandoff> out;
  out.reserve(seq._length);
  for (std::uint32_t i = 0; i < seq._length; ++i) {
    const auto& w = seq._buffer[i];
    common::TrackHandoff h;
    h.track = w.track;
    h.to_supernode = w.to_supernode;
    h.last_tick = w.last_tick;
    std::copy(std::begin(w.state), std::end(w.state), h.state.begin());
    std::copy(std::begin(w.covariance), std::end(w.covariance), h.covariance.begin());
    h.hits = w.hits;
    h.misses = w.misses;
    h.confirmed = w.confirmed;
    out.push_back(h);
  }
  return out;
}

}  // namespace wsn::dds
