// Compiled by the typed-topic build tests (tests/common/dds/CMakeLists.txt), never linked: with no
// WSN_PAIRING_CASE it pairs every endpoint with a topic of its own sample type and must compile; each
// case number swaps in exactly one mismatched pairing, which must not. The correct twin shares every
// other line, so a mismatch case cannot pass for an unrelated error (a missing include, say).
#include "common/dds/role_runtime.hpp"

namespace wsn::dds {

void pairings(const Participant& participant, const RunTopics& topics) {
#if WSN_PAIRING_CASE == 1
  // A reader of report batches on the status topic.
  Reader<wsn_msg_ReportBatch> reader(participant, topics.process_status, Qos::reliableKeepAll());
#else
  Reader<wsn_msg_ReportBatch> reader(participant, topics.report_batch, Qos::reliableKeepAll());
#endif
#if WSN_PAIRING_CASE == 2
  // A writer of report batches on the status topic.
  Writer<wsn_msg_ReportBatch> writer(participant, topics.process_status, Qos::reliableKeepAll());
#else
  Writer<wsn_msg_ReportBatch> writer(participant, topics.report_batch, Qos::reliableKeepAll());
#endif
  wsn_msg_ReportBatch batch{};
  wsn_msg_ProcessStatus status{};
  (void)batch;  // each mismatch case leaves one of the two unused
  (void)status;
#if WSN_PAIRING_CASE == 3
  // A status sample written by a report-batch writer.
  writer.write(status);
#else
  writer.write(batch);
#endif
#if WSN_PAIRING_CASE == 4
  // A report-batch reader's samples handed to a function of status samples.
  reader.take([](const wsn_msg_ProcessStatus&) {});
#else
  reader.take([](const wsn_msg_ReportBatch&) {});
#endif
}

}  // namespace wsn::dds
