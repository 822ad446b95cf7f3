#include "common/track_id.hpp"

#include <stdexcept>

namespace wsn::common::track_id {

TrackId supernodeSerial(std::uint32_t supernode, std::uint64_t serial) {
  if (serial >= kSerialLimit) throw std::out_of_range("track id: serial " + std::to_string(serial) + " exceeds 48 bits");
  if (std::uint64_t{supernode} + 1 >= (std::uint64_t{1} << (64 - kOwnerShift)))
    throw std::out_of_range("track id: supernode " + std::to_string(supernode) + " does not fit in 16 bits");
  return ((std::uint64_t{supernode} + 1) << kOwnerShift) | serial;
}

TrackId birth(std::uint32_t supernode, std::int32_t tick, SensorId sensor, std::uint32_t index) {
  if (tick < 0 || static_cast<std::uint64_t>(tick) >= (std::uint64_t{1} << (kBirthIndexShift - kBirthTickShift)))
    throw std::out_of_range("track id: tick " + std::to_string(tick) + " does not fit in 20 bits");
  if (static_cast<std::uint64_t>(sensor) >= kBirthSerialFloor)
    throw std::out_of_range("track id: sensor " + std::to_string(sensor) + " does not fit in 24 bits");
  if (index >= kMaxBirthsPerSensorTick)
    throw std::out_of_range("track id: birth index " + std::to_string(index) + " of one sensor and tick exceeds " +
                            std::to_string(kMaxBirthsPerSensorTick - 1));
  return supernodeSerial(supernode, (std::uint64_t{index} << kBirthIndexShift) |
                                        (static_cast<std::uint64_t>(tick) << kBirthTickShift) | sensor);
}

TrackId Space::mint(std::uint64_t serial) const {
  if (owner_ != 0) return supernodeSerial(static_cast<std::uint32_t>(owner_ - 1), serial);
  if (serial >= kSerialLimit) throw std::out_of_range("track id: serial " + std::to_string(serial) + " exceeds 48 bits");
  return serial;
}

std::string label(TrackId id) {
  if (!ownedBySupernode(id)) return "g" + std::to_string(serialOf(id));
  const std::string supernode = std::to_string(supernodeOf(id)) + ":";
  if (!isBirth(id)) return supernode + std::to_string(serialOf(id));
  const std::string first = supernode + "t" + std::to_string(birthTick(id)) + "s" + std::to_string(birthSensor(id));
  return birthIndex(id) == 0 ? first : first + "." + std::to_string(birthIndex(id));
}

}  // namespace wsn::common::track_id
