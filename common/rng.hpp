// Counter-based random streams: every random number in a run is drawn from a stream keyed by
// (seed, purpose, entity id, tick), so results never depend on process layout or call order.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace wsn::common {

/// What a stream is used for; part of the key so that two purposes never share numbers.
enum class Purpose : std::uint64_t {
  kTruthBirth = 1,
  kTruthInitial = 2,
  kTruthProcessNoise = 3,
  kTruthDeath = 4,
  kSensorPlacement = 5,
  kSensorLocalisation = 6,
  kSensorNoise = 7,
  kNoiseExceedance = 8,
  kNetworkLoss = 9,
  kNetworkDelay = 10,
  kTracker = 11,
  kAcousticPower = 12,         ///< per (target, emission index): sound-power fluctuation (An 2014 §5.2)
  kEnvironmentalNoisePhase = 13,  ///< per (sensor, component): offset of its noise episodes
  kEnvironmentalNoise = 14,    ///< per (sensor, component, episode): noisy or not, and its power
  kDerivationProbe = 15,       ///< per generation: the probe targets that measure a sensor model (observation_model/)
  kTruthDrawn = 16,            ///< per drawn target (targets.count): its lifetime, appear tick, velocity and start
  kMagnetometerOffset = 17,    ///< per sensor: a magnetometer's constant offset per axis
  kMagnetometerSample = 18,    ///< per (sensor, sample): its read noise, bias drift and bias jump
  kRssNoise = 19,              ///< per (sensor, tick): the noise v of an ADMAN reading (eq. 1)
  kMlmcParticles = 20,         ///< per (attached sensor, tick x 16 + sweep): ADMAN's MLMC particles
  kFieldSensorDetection = 21,  ///< per (sensor x 2^32 + target, tick): a field sensor's detection and noise
  kFieldSensorFalseAlarm = 22,  ///< per (sensor, tick): a field sensor's false alarms
  kFieldSensorClass = 23,      ///< per (sensor x 2^32 + target, tick): the class a field sensor declares (ONERA eq. 19)
  kFaultDraw = 24,             ///< per fault item: the processes a kill with a count takes
};

/// SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// A small deterministic generator (xoshiro256**), seeded from a hashed key. All
/// distributions are implemented here rather than taken from <random>, whose algorithms
/// differ between standard libraries and would break bit-for-bit reproducibility.
class Stream {
 public:
  Stream(std::uint64_t seed, Purpose purpose, std::uint64_t id, std::int64_t tick) {
    std::uint64_t h = mix64(seed);
    h = mix64(h ^ static_cast<std::uint64_t>(purpose));
    h = mix64(h ^ id);
    h = mix64(h ^ static_cast<std::uint64_t>(tick));
    for (auto& word : s_) {
      h = mix64(h);
      word = h;
    }
  }

  /// Uniform 64-bit integer.
  std::uint64_t nextU64() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  /// Uniform on [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(nextU64() >> 11) * 0x1.0p-53; }

  /// Uniform on (0, 1], safe for log().
  double uniformPositive() { return 1.0 - uniform(); }

  /// Uniform on [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }

  /// Uniform integer on [0, n) (n > 0), by Lemire's multiply-shift with rejection.
  std::uint64_t below(std::uint64_t n) {
    while (true) {
      __extension__ using U128 = unsigned __int128;
      const U128 m = static_cast<U128>(nextU64()) * n;
      const auto low = static_cast<std::uint64_t>(m);
      if (low >= n || low >= (-n) % n) return static_cast<std::uint64_t>(m >> 64);
    }
  }

  /// Standard normal by the Box-Muller transform (one value per call: no hidden state).
  double normal() {
    const double u1 = uniformPositive();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

  /// True with probability p.
  bool bernoulli(double p) { return uniform() < p; }

  /// Number of failures before the first success, success probability p in (0, 1].
  std::uint64_t geometric(double p) {
    if (p >= 1.0) return 0;
    if (p <= 0.0) return UINT64_MAX;
    const double g = std::floor(std::log(uniformPositive()) / std::log1p(-p));
    return g >= 1.8e19 ? UINT64_MAX : static_cast<std::uint64_t>(g);
  }

  /// Poisson(mean) by inversion for small means and by a normal approximation guard for
  /// very large ones (means here are at most a few hundred).
  std::uint64_t poisson(double mean) {
    if (mean <= 0.0) return 0;
    // Inversion in blocks of 500 keeps exp() from underflowing for large means.
    std::uint64_t count = 0;
    while (mean > 500.0) {
      count += poisson(500.0);
      mean -= 500.0;
    }
    double p = std::exp(-mean);
    double cumulative = p;
    const double u = uniform();
    std::uint64_t k = 0;
    while (u > cumulative && k < 100000) {
      ++k;
      p *= mean / static_cast<double>(k);
      cumulative += p;
    }
    return count + k;
  }

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

}  // namespace wsn::common
