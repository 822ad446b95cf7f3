// The batch topics a role takes from the network, for the sample fuzzer and its corpus generator:
// each topic's Cyclone sertype (what a reader deserialises received CDR bytes with) and what the
// receiving role does with a sample (batch header, length, decode, edge checks).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/edge_checks.hpp"
#include "common/scenario_config.hpp"

namespace wsn::fuzz {

/// The topics a role reads batches of; an input's first byte picks one (modulo kTopicCount).
enum class BatchTopic : std::uint8_t {
  kSensorBoundary,    ///< node tiles from their neighbours
  kReportBatch,       ///< the network model from the tiles
  kDeliveryBatch,     ///< a supernode from the network model
  kHandoffBatch,      ///< a supernode from its neighbours (handoffs and re-homed tracks)
  kTrackBatch,        ///< the aggregator from the supernodes
  kGlobalTrackBatch,  ///< live viewers from the aggregator
};
inline constexpr std::size_t kTopicCount = 6;

/// "ReportBatch", ...: the corpus files' names.
const char* topicName(BatchTopic topic);

/// Cyclone's own (de)serialisation of the batch topics. Cyclone 0.10 exports no way to make a
/// topic's sertype without a domain, so one is made deaf and mute on loopback with multicast off
/// (nothing leaves the process), and each sertype is taken from a sample written and taken back.
class SampleTopics {
 public:
  SampleTopics();
  ~SampleTopics();
  SampleTopics(const SampleTopics&) = delete;
  SampleTopics& operator=(const SampleTopics&) = delete;

  /// Deserialises `cdr` (its 4-byte encapsulation header first) as a reader of `topic` receiving
  /// it: Cyclone's from_ser (which validates and normalises the CDR) then to_sample. Calls
  /// `use(sample)` with the C sample of the topic's type, freed after, and returns true; returns
  /// false when Cyclone refuses the bytes (a reader drops such a sample).
  bool deserialize(BatchTopic topic, std::span<const std::uint8_t> cdr, const std::function<void(const void*)>& use) const;

  /// The CDR bytes, encapsulation header first, of the C sample `sample` of `topic`'s type.
  std::vector<std::uint8_t> serialize(BatchTopic topic, const void* sample) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// What a receiving role knows about its run: the bounds every sample must meet and its shape.
struct EdgeContext {
  common::EdgeBounds bounds;
  std::uint64_t run_id = 0;
  std::uint32_t tiles = 0;
  std::uint32_t supernodes = 0;
  std::int32_t window = 0;  ///< tracker.window_size: the most ticks one track batch settles
};

/// The edge of a run of `scenario` (whose run id is `run_id`) split into `tiles` node tiles.
EdgeContext edgeContextOf(const common::Scenario& scenario, std::uint64_t run_id, std::uint32_t tiles);

/// What the role reading `topic` does with `sample` before anything of it counts (node/role.cpp,
/// network_model/role.cpp, supernode/role.cpp, aggregator/role.cpp, launcher/watch): the batch
/// header, the item count, the decode into common/messages.hpp and each item's edge check, every
/// refusal counted in `log`. Returns the number of items accepted. Throws what the role would
/// let escape, which ends that role's process.
std::size_t receive(BatchTopic topic, const void* sample, const EdgeContext& edge, common::RejectionLog& log);

/// A shipped scenario (scenarios/NAME.yaml) loaded as the launcher would.
common::Scenario shippedScenario(const std::string& name);

}  // namespace wsn::fuzz
