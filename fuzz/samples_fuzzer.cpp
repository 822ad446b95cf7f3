// libFuzzer target: a batch sample as a role receives it from the network (docs/FUZZING.md). The
// input's first byte picks the topic, the rest are the CDR bytes (encapsulation header first) that
// Cyclone's deserialiser, the codec and the role's edge checks take in turn, against the bounds of
// scenarios/oh_quadrants.yaml. Cyclone refusing the bytes is fine (a reader drops them); anything
// escaping the role's receiving code (an exception, which would end the role) is a finding.
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz/sample_topics.hpp"

namespace {

/// The run id of the corpus's batches (make_sample_corpus.cpp), so that mutations of them get past
/// the run check into the items.
constexpr std::uint64_t kRunId = 1;
/// Node tiles of the receiving run: tile indices 0 .. 3 are the run's own.
constexpr std::uint32_t kTiles = 4;

struct Harness {
  wsn::fuzz::SampleTopics topics;
  wsn::fuzz::EdgeContext edge = wsn::fuzz::edgeContextOf(wsn::fuzz::shippedScenario("oh_quadrants"), kRunId, kTiles);
};

Harness* harness = nullptr;  // made once, in LLVMFuzzerInitialize; lives as long as the process

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  harness = new Harness;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto topic = static_cast<wsn::fuzz::BatchTopic>(data[0] % wsn::fuzz::kTopicCount);
  wsn::common::RejectionLog log;
  harness->topics.deserialize(topic, std::span<const std::uint8_t>(data + 1, size - 1), [&](const void* sample) {
    (void)wsn::fuzz::receive(topic, sample, harness->edge, log);
  });
  return 0;
}
