// Cyclone's deserialiser for the batch topics and the roles' receiving edge, for the sample fuzzer.
// The one file of fuzz/ that includes dds/dds.h, as common/dds/ does: it reaches into Cyclone's
// serdata interface, which the project's RAII layer has no reason to wrap.
#include "fuzz/sample_topics.hpp"

#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>

#include "common/dds/codec.hpp"
#include "common/dds/packing.hpp"
#include "common/dds/entity.hpp"
#include "scenario/loader.hpp"
#include "wsntrack.h"

namespace wsn::fuzz {
namespace {

using common::RejectReason;

/// Loopback only, multicast off, no peers, and a random port (no participant index), so that it can
/// neither reach nor collide with a run on this host; the domain is made deaf and mute as well.
constexpr const char* kIsolatedConfig =
    "<CycloneDDS><Domain id=\"any\"><General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>none</ParticipantIndex>"
    "</Discovery></Domain></CycloneDDS>";
/// A domain id no run picks (the launcher's are 1 .. dds::kMaxDomainId).
constexpr dds_domainid_t kFuzzDomain = 231;

const dds_topic_descriptor_t& descriptorOf(BatchTopic topic) {
  switch (topic) {
    case BatchTopic::kSensorBoundary: return wsn_msg_SensorBoundary_desc;
    case BatchTopic::kReportBatch: return wsn_msg_ReportBatch_desc;
    case BatchTopic::kDeliveryBatch: return wsn_msg_DeliveryBatch_desc;
    case BatchTopic::kHandoffBatch: return wsn_msg_HandoffBatch_desc;
    case BatchTopic::kTrackBatch: return wsn_msg_TrackBatch_desc;
    case BatchTopic::kGlobalTrackBatch: return wsn_msg_GlobalTrackBatch_desc;
  }
  throw std::logic_error("no such batch topic");
}

/// A sample buffer of a generated C type, zeroed (what Cyclone's to_sample expects), whose
/// sequences Cyclone allocates and dds_sample_free releases.
class SampleBuffer {
 public:
  explicit SampleBuffer(const dds_topic_descriptor_t& desc) : desc_(desc), storage_(desc.m_size / 8 + 1) {}
  ~SampleBuffer() { dds_sample_free(data(), &desc_, DDS_FREE_CONTENTS); }
  SampleBuffer(const SampleBuffer&) = delete;
  SampleBuffer& operator=(const SampleBuffer&) = delete;
  void* data() { return storage_.data(); }

 private:
  const dds_topic_descriptor_t& desc_;
  std::vector<std::uint64_t> storage_;  // 8-byte aligned, as every generated type needs at most
};

}  // namespace

const char* topicName(BatchTopic topic) {
  switch (topic) {
    case BatchTopic::kSensorBoundary: return "SensorBoundary";
    case BatchTopic::kReportBatch: return "ReportBatch";
    case BatchTopic::kDeliveryBatch: return "DeliveryBatch";
    case BatchTopic::kHandoffBatch: return "HandoffBatch";
    case BatchTopic::kTrackBatch: return "TrackBatch";
    case BatchTopic::kGlobalTrackBatch: return "GlobalTrackBatch";
  }
  return "unknown";
}

struct SampleTopics::Impl {
  dds::Domain domain{kFuzzDomain, kIsolatedConfig};
  dds::Participant participant{kFuzzDomain};
  std::array<const ddsi_sertype*, kTopicCount> sertypes{};

  Impl() {
    dds::check(dds_domain_set_deafmute(participant.handle(), true, true, DDS_INFINITY), "deaf and mute domain");
    for (std::size_t i = 0; i < kTopicCount; ++i) sertypes[i] = sertypeOf(static_cast<BatchTopic>(i));
  }
  ~Impl() {
    for (const ddsi_sertype* type : sertypes)
      if (type) ddsi_sertype_unref(const_cast<ddsi_sertype*>(type));
  }

  /// The sertype a reader of `topic` deserialises with: the one of a sample written to a reader of
  /// the same participant (delivered locally, before dds_write returns) and taken back as CDR.
  const ddsi_sertype* sertypeOf(BatchTopic topic) {
    const dds_topic_descriptor_t& desc = descriptorOf(topic);
    const std::string name = std::string("wsn_fuzz_") + topicName(topic);
    const dds::Entity topic_entity(dds::check(dds_create_topic(participant.handle(), &desc, name.c_str(), nullptr, nullptr),
                                              "fuzz topic"));
    dds::Qos qos = dds::Qos::reliableKeepAll(dds::Endpoint::kViewer);
    const dds::Entity reader(dds::check(dds_create_reader(participant.handle(), topic_entity.handle(), qos.get(), nullptr),
                                        "fuzz reader"));
    const dds::Entity writer(dds::check(dds_create_writer(participant.handle(), topic_entity.handle(), qos.get(), nullptr),
                                        "fuzz writer"));
    SampleBuffer zero(desc);
    dds::check(dds_write(writer.handle(), zero.data()), "fuzz write");
    ddsi_serdata* serdata = nullptr;
    dds_sample_info_t info;
    if (dds::check(dds_takecdr(reader.handle(), &serdata, 1, &info, DDS_ANY_STATE), "fuzz takecdr") != 1)
      throw std::runtime_error(std::string("no local sample of ") + topicName(topic) + " to find its sertype in");
    const ddsi_sertype* type = ddsi_sertype_ref(serdata->type);
    ddsi_serdata_unref(serdata);
    return type;
  }
};

SampleTopics::SampleTopics() : impl_(std::make_unique<Impl>()) {}
SampleTopics::~SampleTopics() = default;

bool SampleTopics::deserialize(BatchTopic topic, std::span<const std::uint8_t> cdr,
                               const std::function<void(const void*)>& use) const {
  if (cdr.size() < 4) return false;  // Cyclone's own precondition: the encapsulation header is there
  const ddsi_sertype* type = impl_->sertypes[static_cast<std::size_t>(topic)];
  const ddsrt_iovec_t iov{const_cast<std::uint8_t*>(cdr.data()), static_cast<ddsrt_iov_len_t>(cdr.size())};
  ddsi_serdata* serdata = ddsi_serdata_from_ser_iov(type, SDK_DATA, 1, &iov, cdr.size());
  if (!serdata) return false;
  SampleBuffer sample(descriptorOf(topic));
  const bool read = ddsi_serdata_to_sample(serdata, sample.data(), nullptr, nullptr);
  ddsi_serdata_unref(serdata);
  if (!read) return false;
  use(sample.data());
  return true;
}

std::vector<std::uint8_t> SampleTopics::serialize(BatchTopic topic, const void* sample) const {
  const ddsi_sertype* type = impl_->sertypes[static_cast<std::size_t>(topic)];
  ddsi_serdata* serdata = ddsi_serdata_from_sample(type, SDK_DATA, sample);
  if (!serdata) throw std::runtime_error(std::string("Cyclone cannot serialise this ") + topicName(topic));
  std::vector<std::uint8_t> bytes(ddsi_serdata_size(serdata));
  ddsi_serdata_to_ser(serdata, 0, bytes.size(), bytes.data());
  ddsi_serdata_unref(serdata);
  return bytes;
}

EdgeContext edgeContextOf(const common::Scenario& scenario, std::uint64_t run_id, std::uint32_t tiles) {
  return {common::edgeBounds(scenario), run_id, tiles, static_cast<std::uint32_t>(scenario.supernodes.size()),
          scenario.tracker.window_size};
}

namespace {

template <typename Item, typename Check>
std::size_t keep(std::vector<Item>& items, Check check, const char* topic, common::RejectionLog& log) {
  common::dropRejected(items, check, topic, log);
  return items.size();
}

std::size_t receiveTracks(const wsn_msg_TrackBatch& batch, const EdgeContext& edge, common::RejectionLog& log) {
  const char* topic = "TrackBatch";
  if (const auto why = common::checkBatchHeader(batch.run_id, edge.run_id, batch.supernode, edge.supernodes, batch.tick,
                                                edge.bounds.ticks))
    return log.add(topic, *why), 0;
  if (!dds::settledSpanFits(batch.settled_first, batch.settled_last, edge.window))
    return log.add(topic, RejectReason::kTooLong), 0;
  const auto check = [&](const common::TrackEstimate& t) { return common::checkTrack(t, edge.bounds); };
  auto tracks = dds::decode(batch.tracks);
  std::size_t kept = keep(tracks, check, topic, log);
  for (auto& tick_tracks : dds::decodeSettled(batch.settled, batch.settled_first, batch.settled_last, edge.window))
    kept += keep(tick_tracks, check, topic, log);
  return kept;
}

}  // namespace

std::size_t receive(BatchTopic topic, const void* sample, const EdgeContext& edge, common::RejectionLog& log) {
  const common::EdgeBounds& b = edge.bounds;
  const char* name = topicName(topic);
  switch (topic) {
    case BatchTopic::kSensorBoundary: {
      const auto& batch = *static_cast<const wsn_msg_SensorBoundary*>(sample);
      if (const auto why = common::checkBatchHeader(batch.run_id, edge.run_id, batch.tile, edge.tiles, batch.tick, b.ticks))
        return log.add(name, *why), 0;
      if (batch.readings._length > b.sensors) return log.add(name, RejectReason::kTooLong), 0;
      auto readings = dds::decode(batch.readings);
      return keep(readings, [&](const common::SensorReading& r) { return common::checkReading(r, b); }, name, log);
    }
    case BatchTopic::kReportBatch: {
      const auto& batch = *static_cast<const wsn_msg_ReportBatch*>(sample);
      if (const auto why = common::checkBatchHeader(batch.run_id, edge.run_id, batch.tile, edge.tiles, batch.tick, b.ticks))
        return log.add(name, *why), 0;
      if (dds::packedCount(batch.reports) > b.max_reports) return log.add(name, RejectReason::kTooLong), 0;
      std::vector<common::Report> reports;
      try {
        reports = dds::unpackReports(batch.reports, batch.tick);
      } catch (const dds::PackingError&) {
        return log.add(name, RejectReason::kMalformed), 0;
      }
      common::dropRejectedReports(reports, b, name, log);
      return reports.size();
    }
    case BatchTopic::kDeliveryBatch: {
      const auto& batch = *static_cast<const wsn_msg_DeliveryBatch*>(sample);
      if (const auto why = common::checkBatchHeader(batch.run_id, edge.run_id, 0, 1, batch.tick, b.ticks))
        return log.add(name, *why), 0;
      if (batch.supernode >= edge.supernodes) return log.add(name, RejectReason::kMisaddressed), 0;
      if (dds::packedCount(batch.observations) > b.max_reports) return log.add(name, RejectReason::kTooLong), 0;
      std::vector<common::Observation> observations;
      try {
        observations = dds::unpackObservations(batch.observations, batch.tick);
      } catch (const dds::PackingError&) {
        return log.add(name, RejectReason::kMalformed), 0;
      }
      return keep(observations, [&](const common::Observation& o) { return common::checkObservation(o, b); }, name, log);
    }
    case BatchTopic::kHandoffBatch: {
      const auto& batch = *static_cast<const wsn_msg_HandoffBatch*>(sample);
      if (const auto why = common::checkBatchHeader(batch.run_id, edge.run_id, batch.from_supernode, edge.supernodes,
                                                    batch.tick, b.ticks))
        return log.add(name, *why), 0;
      auto handoffs = dds::decode(batch.handoffs);
      return keep(handoffs, [&](const common::TrackHandoff& h) { return common::checkHandoff(h, b, edge.supernodes); },
                  name, log);
    }
    case BatchTopic::kTrackBatch: return receiveTracks(*static_cast<const wsn_msg_TrackBatch*>(sample), edge, log);
    case BatchTopic::kGlobalTrackBatch: {
      // wsntrack watch keeps its own run's batches; it draws the tracks, which must be decodable.
      const auto& batch = *static_cast<const wsn_msg_GlobalTrackBatch*>(sample);
      if (batch.run_id != edge.run_id) return log.add(name, RejectReason::kForeignRun), 0;
      auto tracks = dds::decode(batch.tracks);
      return keep(tracks, [&](const common::TrackEstimate& t) { return common::checkTrack(t, b); }, name, log);
    }
  }
  return 0;
}

common::Scenario shippedScenario(const std::string& name) {
  return scenario::loadScenario(std::string(WSN_SCENARIO_DIR) + "/" + name + ".yaml");
}

}  // namespace wsn::fuzz
