// What a role accepts from the wire, whatever DDS Security says (DESIGN.md principle 7): bounds
// derived from the scenario that every received report must meet, and the count of what was
// refused, by topic and reason, that each role leaves in the run directory (rejected.json).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"
#include "common/scenario_config.hpp"

namespace wsn::common {

/// Why a sample, or an item of one, was refused.
enum class RejectReason {
  kForeignRun,           ///< another run's id
  kProducerOutOfRange,   ///< a tile or supernode index the run does not have
  kTickOutOfRange,       ///< a tick outside [1, T]
  kDuplicate,            ///< a second sample of the same producer and tick, or of a tick already handled
  kTooLong,              ///< more items than the scenario can produce in one sample
  kSensorOutOfRange,     ///< a sensor id the run does not have
  kNotFinite,            ///< NaN or infinity
  kOutOfRegion,          ///< a position beyond the region and its margin, or a value beyond any bound
  kMalformedMeasurement, ///< a measurement of the wrong dimension, noise or pose
  kMisaddressed,         ///< for another supernode, or from one that does not border this one
  kUnauthenticated,      ///< a status sample not signed with the run's status key
  kMalformed             ///< packed items that do not decode (common/dds/packing.hpp)
};

/// "foreign_run", "producer_out_of_range", ...: the names rejected.json uses.
const char* rejectReasonName(RejectReason reason);

/// The bounds a run's received reports must meet.
struct EdgeBounds {
  Rect region;            ///< the scenario's region grown by the margin on every side
  double margin = 0.0;
  std::uint64_t sensors = 0;
  std::int32_t ticks = 0;
  std::size_t max_reports = 0;  ///< per sample: kMaxReportsPerSensor per sensor
};

/// The most reports one sensor can make in a tick, far above what any does: a field sensor
/// reports each target it detects and its clutter (a scalar sensor at most one). A genuine batch
/// refused as too long would leave its consumer waiting for it until the run stalls, so the bound
/// only has to stop absurd batches (two million reports), never a real one.
inline constexpr std::size_t kMaxReportsPerSensor = 64;

/// The largest magnitude any received value may have: far beyond every physical quantity of a run
/// (positions, speeds, covariances, likelihoods), and far below where arithmetic on it overflows
/// (a 1e308 passed the old finiteness check and reached observations.csv as a 300-digit number).
inline constexpr double kMaxMagnitude = 1e12;

/// The bounds of `scenario`. The margin is the region's larger side plus the
/// sensing range and six localisation deviations: a report is a sensor's position or a centre of
/// mass of sensors' positions (Oh eq. 6), or a measured position near one, so a genuine report is
/// never near the margin, while garbage (1e308, a forged far-away report) is.
EdgeBounds edgeBounds(const Scenario& scenario);

/// The run id, producer index and tick of a received batch, checked before anything in it:
/// another run's id, a producer index of `producers` or more, a tick outside [1, ticks].
std::optional<RejectReason> checkBatchHeader(std::uint64_t run_id, std::uint64_t expected_run_id, std::uint32_t producer,
                                             std::uint32_t producers, std::int32_t tick, std::int32_t ticks);

/// Why `report` is refused under `bounds`, or nothing when it is acceptable.
std::optional<RejectReason> checkReport(const Report& report, const EdgeBounds& bounds);
/// As for a report, and generated at a tick in [1, its delivery tick].
std::optional<RejectReason> checkObservation(const Observation& observation, const EdgeBounds& bounds);
/// A sensor the run has, and a finite, bounded reading.
std::optional<RejectReason> checkReading(const SensorReading& reading, const EdgeBounds& bounds);
/// A finite, bounded state, covariance, class vector and stop probability, the position within the
/// region and its margin, and the tick of its last observation in [0, T].
std::optional<RejectReason> checkTrack(const TrackEstimate& track, const EdgeBounds& bounds);
/// As for a track, addressed to one of the run's `supernodes` (a batch carries the handoffs to
/// every neighbour; each reader keeps its own), of a tick in [1, T].
std::optional<RejectReason> checkHandoff(const TrackHandoff& handoff, const EdgeBounds& bounds, std::uint32_t supernodes);

/// Counts of refused samples and items, by topic and reason.
class RejectionLog {
 public:
  void add(const std::string& topic, RejectReason reason, std::uint64_t count = 1);
  std::uint64_t total() const;
  std::uint64_t count(const std::string& topic, RejectReason reason) const;
  /// {"role": ..., "index": ..., "rejected": [{"topic": ..., "reason": ..., "count": N}, ...]},
  /// in topic and reason order.
  std::string json(const std::string& role, std::uint32_t index) const;

 private:
  std::map<std::pair<std::string, RejectReason>, std::uint64_t> counts_;
};

/// Removes the items `check` refuses from `items`, counting each under `topic`.
template <typename Item, typename Check>
void dropRejected(std::vector<Item>& items, Check check, const std::string& topic, RejectionLog& log) {
  std::erase_if(items, [&](const Item& item) {
    const std::optional<RejectReason> why = check(item);
    if (why) log.add(topic, *why);
    return why.has_value();
  });
}

/// Removes the reports `bounds` refuses from `reports`, counting each under `topic`.
void dropRejectedReports(std::vector<Report>& reports, const EdgeBounds& bounds, const std::string& topic,
                         RejectionLog& log);

}  // namespace wsn::common
