// The wire form of report and delivery batches: a packed byte sequence of their items instead of
// nested IDL sequences. Cyclone serializes an octet sequence with one copy, while nested
// structures of sequences cost it an interpreted step per field of every item (measured in
// docs/PERFORMANCE.md, "Transport"); these are the two topics that carry most of a run's bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "common/messages.hpp"
#include "wsntrack.h"

namespace wsn::dds {

/// Bytes that are not a packed batch: truncated, trailing, or a count, kind or length out of range.
class PackingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A packed batch, and an octet-sequence view of it for a sample (valid while this lives).
struct Packed {
  std::vector<std::uint8_t> bytes;
  dds_sequence_octet view();
};

/// Throws std::invalid_argument for a measurement that is not well formed, and std::length_error for
/// one beyond kMaxMeasurementDimension values or kMaxClasses classes (which no receiver would take).
Packed packReports(const std::vector<common::Report>& reports);
Packed packObservations(const std::vector<common::Observation>& observations);

/// The item count a packed batch claims (its first four bytes), or 0 for fewer bytes than that:
/// checked against a bound before the items are unpacked.
std::uint32_t packedCount(const dds_sequence_octet& bytes);

/// The items of a packed batch; throws PackingError for anything else. Every length is checked
/// against the bytes left before anything is allocated, so a forged count cannot make it allocate
/// more than the sample's own size allows.
std::vector<common::Report> unpackReports(const dds_sequence_octet& bytes, std::int32_t tick);
std::vector<common::Observation> unpackObservations(const dds_sequence_octet& bytes, std::int32_t tick_delivered);

}  // namespace wsn::dds
