// Track identities, the one place their bit layout is written: engines mint them, associations
// keep or mint them, and `wsntrack watch`, the track CSVs and tools/plot_run.py read them.
//
//   (supernode + 1) << 48 | serial     a supernode's track; the serial is a counter (MCMCDA), or
//                                      a birth id index << 44 | tick << 24 | sensor (GNN,
//                                      rule-based, sbmht) so that a replay of the window names a
//                                      track the same way again; index (4 bits, 0 but for sbmht)
//                                      tells apart the trees one sensor starts in one tick
//   serial < 1 << 48                   a global id the aggregator minted
#pragma once

#include <cstdint>
#include <string>

namespace wsn::common {

/// Global track id (see above).
using TrackId = std::uint64_t;
/// Identifies a sensor: its index in the layout (row-major for grids).
using SensorId = std::uint32_t;

namespace track_id {

inline constexpr int kOwnerShift = 48;     ///< the owning supernode + 1 sits above this bit
inline constexpr int kBirthTickShift = 24;  ///< a birth serial's tick sits above this bit
inline constexpr int kBirthIndexShift = 44;  ///< and its index above this one: the tick has 20 bits
/// How many tracks one sensor's reports of one tick can start (the index's 4 bits).
inline constexpr std::uint32_t kMaxBirthsPerSensorTick = 16;
/// Serials at or above this are birth ids; below it, counters. Ticks start at 1, so the two never meet.
inline constexpr std::uint64_t kBirthSerialFloor = std::uint64_t{1} << kBirthTickShift;
inline constexpr std::uint64_t kSerialLimit = std::uint64_t{1} << kOwnerShift;

/// Serial `serial` (< 2^48) of supernode `supernode` (< 2^16 - 1).
TrackId supernodeSerial(std::uint32_t supernode, std::uint64_t serial);
/// The track supernode `supernode` starts at `tick` from sensor `sensor`'s observation, the
/// `index`-th (from 0) it starts from that sensor's reports of the tick; throws std::out_of_range
/// when the tick does not fit in 20 bits (run.ticks is at most 10^6 < 2^20), the sensor in 24, the
/// index below kMaxBirthsPerSensorTick or the supernode in 16.
TrackId birth(std::uint32_t supernode, std::int32_t tick, SensorId sensor, std::uint32_t index = 0);

/// True for a supernode's id, false for one the aggregator minted.
inline bool ownedBySupernode(TrackId id) { return (id >> kOwnerShift) != 0; }
/// The supernode whose space the id is in (ownedBySupernode(id) must hold).
inline std::uint32_t supernodeOf(TrackId id) { return static_cast<std::uint32_t>((id >> kOwnerShift) - 1); }
inline std::uint64_t serialOf(TrackId id) { return id & (kSerialLimit - 1); }
inline bool isBirth(TrackId id) { return ownedBySupernode(id) && serialOf(id) >= kBirthSerialFloor; }
/// The tick, sensor and index of a birth id.
inline std::int32_t birthTick(TrackId id) {
  return static_cast<std::int32_t>((serialOf(id) >> kBirthTickShift) & ((std::uint64_t{1} << (kBirthIndexShift - kBirthTickShift)) - 1));
}
inline SensorId birthSensor(TrackId id) { return static_cast<SensorId>(serialOf(id) & (kBirthSerialFloor - 1)); }
inline std::uint32_t birthIndex(TrackId id) { return static_cast<std::uint32_t>(serialOf(id) >> kBirthIndexShift); }

/// Where an engine's new track ids come from: a supernode's serials, or the aggregator's global
/// ids ("gN"), the one space every track association mints in.
class Space {
 public:
  static Space ofSupernode(std::uint32_t supernode) { return Space(std::uint64_t{supernode} + 1); }
  static Space ofAggregator() { return Space(0); }
  /// The id of serial `serial` in this space; throws std::out_of_range when it does not fit.
  TrackId mint(std::uint64_t serial) const;
  bool isAggregator() const { return owner_ == 0; }
  friend bool operator==(const Space&, const Space&) = default;

 private:
  explicit Space(std::uint64_t owner) : owner_(owner) {}
  std::uint64_t owner_;  ///< supernode + 1, or 0 for the aggregator
};

/// A track id as people read it: "S:N" for serial N of supernode S; "S:tTsK" for a track that
/// supernode S started at tick T from sensor K's report, "S:tTsK.J" for the J-th further one it
/// started from K's reports of that tick; "gN" for an id the aggregator minted.
std::string label(TrackId id);

}  // namespace track_id
}  // namespace wsn::common
