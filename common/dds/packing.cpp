// The packed wire form of report and delivery batches (packing.hpp). Layout, little-endian, fields
// in this order without padding:
//   batch:        u32 item count, then the items
//   report:       u32 sensor, f64 x, f64 y, i32 target, i32 power level, measurement
//   observation:  i32 tick generated, then as a report
//   measurement:  u8 kind (255: none, a plain position), and for a kind: u8 values, u8 noise,
//                 u8 classes, u8 pose (0 or 1), f64 clutter density, the values, the noise, the class
//                 likelihoods, the pose (x, y, heading, height)
#include "common/dds/packing.hpp"

#include <bit>
#include <cstring>
#include <string>
#include <type_traits>

namespace wsn::dds {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the packed batches are little-endian, as every host a run spans is assumed to be");

constexpr std::uint8_t kPlainPosition = 255;
constexpr std::size_t kMaxNoise = common::kMaxMeasurementDimension * common::kMaxMeasurementDimension;
/// The fewest bytes an item takes: a report with no measurement. Bounds a batch's claimed count.
constexpr std::size_t kMinItemBytes = 4 + 8 + 8 + 4 + 4 + 1;

/// Writes into a buffer sized up front (packedBytes), so that each field is one copy.
class Writer {
 public:
  explicit Writer(std::uint8_t* at) : at_(at) {}
  template <typename T>
  void put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::memcpy(at_, &value, sizeof(T));
    at_ += sizeof(T);
  }
  void put(const std::vector<double>& values) {
    if (values.empty()) return;
    std::memcpy(at_, values.data(), values.size() * sizeof(double));
    at_ += values.size() * sizeof(double);
  }
  const std::uint8_t* at() const { return at_; }

 private:
  std::uint8_t* at_;
};

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), left_(size) {}
  template <typename T>
  T take() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, data_, sizeof(T));
    advance(sizeof(T));
    return value;
  }
  std::vector<double> doubles(std::size_t n) {
    need(n * sizeof(double));
    std::vector<double> values(n);
    if (n > 0) std::memcpy(values.data(), data_, n * sizeof(double));
    advance(n * sizeof(double));
    return values;
  }
  std::size_t left() const { return left_; }

 private:
  void need(std::size_t n) const {
    if (n > left_) throw PackingError("packed batch truncated: " + std::to_string(n) + " bytes needed, " +
                                      std::to_string(left_) + " left");
  }
  void advance(std::size_t n) {
    data_ += n;
    left_ -= n;
  }
  const std::uint8_t* data_;
  std::size_t left_;
};

void checkLength(std::size_t n, std::size_t bound, const char* what) {
  if (n > bound)
    throw std::length_error(std::string(what) + ": " + std::to_string(n) + " values, the wire holds at most " +
                            std::to_string(bound));
}

void packMeasurement(Writer& w, const common::MeasurementRef& ref) {
  if (!ref) {
    w.put(kPlainPosition);
    return;
  }
  const common::Measurement& m = *ref;
  // A malformed one would read back as something else (an empty position as a plain one).
  if (!common::wellFormed(m))
    throw std::invalid_argument("codec: a " + std::string(common::measurementKindName(m.kind)) +
                                " measurement that is not well formed (wrong dimension, noise or pose)");
  checkLength(m.values.size(), common::kMaxMeasurementDimension, "measurement values");
  checkLength(m.noise.size(), kMaxNoise, "measurement noise");
  checkLength(m.class_likelihoods.size(), common::kMaxClasses, "measurement class likelihoods");
  w.put(static_cast<std::uint8_t>(m.kind));
  w.put(static_cast<std::uint8_t>(m.values.size()));
  w.put(static_cast<std::uint8_t>(m.noise.size()));
  w.put(static_cast<std::uint8_t>(m.class_likelihoods.size()));
  w.put(static_cast<std::uint8_t>(m.sensor ? 1 : 0));
  w.put(m.clutter_density);
  w.put(m.values);
  w.put(m.noise);
  w.put(m.class_likelihoods);
  if (m.sensor) {
    w.put(m.sensor->x);
    w.put(m.sensor->y);
    w.put(m.sensor->heading);
    w.put(m.sensor->height);
  }
}

common::MeasurementRef unpackMeasurement(Reader& r) {
  const auto kind = r.take<std::uint8_t>();
  if (kind == kPlainPosition) return {};
  if (kind > static_cast<std::uint8_t>(common::MeasurementKind::presence))
    throw PackingError("packed batch: measurement kind " + std::to_string(kind) + " is none of the kinds");
  const auto values = r.take<std::uint8_t>(), noise = r.take<std::uint8_t>(), classes = r.take<std::uint8_t>(),
             pose = r.take<std::uint8_t>();
  if (values > common::kMaxMeasurementDimension || noise > kMaxNoise || classes > common::kMaxClasses || pose > 1)
    throw PackingError("packed batch: a measurement of " + std::to_string(values) + " values, " + std::to_string(noise) +
                       " noise terms, " + std::to_string(classes) + " classes and " + std::to_string(pose) +
                       " poses, beyond what the wire holds");
  common::Measurement m;
  m.kind = static_cast<common::MeasurementKind>(kind);
  m.clutter_density = r.take<double>();
  m.values = r.doubles(values);
  m.noise = r.doubles(noise);
  m.class_likelihoods = r.doubles(classes);
  if (pose == 1) {
    common::SensorPose p;
    p.x = r.take<double>();
    p.y = r.take<double>();
    p.heading = r.take<double>();
    p.height = r.take<double>();
    m.sensor = p;
  }
  return common::MeasurementRef(std::move(m));
}

template <typename Item>
void packSensed(Writer& w, const Item& item) {
  w.put(item.sensor);
  w.put(item.x);
  w.put(item.y);
  w.put(item.target);
  w.put(item.power_level);
  packMeasurement(w, item.measurement);
}

template <typename Item>
void unpackSensed(Reader& r, Item& item) {
  item.sensor = r.take<decltype(item.sensor)>();
  item.x = r.take<double>();
  item.y = r.take<double>();
  item.target = r.take<decltype(item.target)>();
  item.power_level = r.take<std::int32_t>();
  item.measurement = unpackMeasurement(r);
}

/// Reads the item count and checks that that many items can fit in what is left.
std::uint32_t itemCount(Reader& r) {
  const auto count = r.take<std::uint32_t>();
  if (count > r.left() / kMinItemBytes)
    throw PackingError("packed batch: " + std::to_string(count) + " items claimed in " + std::to_string(r.left()) +
                       " bytes");
  return count;
}

void checkEnd(const Reader& r) {
  if (r.left() != 0) throw PackingError("packed batch: " + std::to_string(r.left()) + " bytes after its last item");
}

/// The bytes an item's measurement takes.
std::size_t measurementBytes(const common::MeasurementRef& ref) {
  if (!ref) return 1;
  const common::Measurement& m = *ref;
  return 5 + 8 * (1 + m.values.size() + m.noise.size() + m.class_likelihoods.size() + (m.sensor ? 4 : 0));
}

template <typename Item, typename PackItem>
Packed pack(const std::vector<Item>& items, std::size_t item_bytes, PackItem pack_item) {
  std::size_t size = 4;
  for (const auto& item : items) size += item_bytes - 1 + measurementBytes(item.measurement);
  Packed packed;
  packed.bytes.resize(size);
  Writer w(packed.bytes.data());
  w.put(static_cast<std::uint32_t>(items.size()));
  for (const auto& item : items) pack_item(w, item);
  if (w.at() != packed.bytes.data() + size) throw std::logic_error("packing: the sizes of the layout disagree");
  return packed;
}

/// The items of a packed batch, each read by `unpack_item(reader, item)`.
template <typename Item, typename UnpackItem>
std::vector<Item> unpack(const dds_sequence_octet& bytes, UnpackItem unpack_item) {
  Reader r(bytes._buffer, bytes._length);
  std::vector<Item> items(itemCount(r));
  for (auto& item : items) unpack_item(r, item);
  checkEnd(r);
  return items;
}

}  // namespace

dds_sequence_octet Packed::view() {
  dds_sequence_octet seq{};
  seq._maximum = seq._length = static_cast<std::uint32_t>(bytes.size());
  seq._buffer = bytes.data();
  seq._release = false;
  return seq;
}

Packed packReports(const std::vector<common::Report>& reports) {
  return pack(reports, kMinItemBytes, [](Writer& w, const common::Report& r) { packSensed(w, r); });
}

Packed packObservations(const std::vector<common::Observation>& observations) {
  return pack(observations, kMinItemBytes + 4, [](Writer& w, const common::Observation& o) {
    w.put(o.tick_generated);
    packSensed(w, o);
  });
}

std::uint32_t packedCount(const dds_sequence_octet& bytes) {
  std::uint32_t count = 0;
  if (bytes._length >= sizeof count) std::memcpy(&count, bytes._buffer, sizeof count);
  return count;
}

std::vector<common::Report> unpackReports(const dds_sequence_octet& bytes, std::int32_t tick) {
  return unpack<common::Report>(bytes, [tick](Reader& r, common::Report& report) {
    report.tick = tick;
    unpackSensed(r, report);
  });
}

std::vector<common::Observation> unpackObservations(const dds_sequence_octet& bytes, std::int32_t tick_delivered) {
  return unpack<common::Observation>(bytes, [tick_delivered](Reader& r, common::Observation& o) {
    o.tick_delivered = tick_delivered;
    o.tick_generated = r.take<std::int32_t>();
    unpackSensed(r, o);
  });
}

}  // namespace wsn::dds
