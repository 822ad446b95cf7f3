// ADMAN ("an Algorithm for Detection of Multi-targets in Wireless Acoustic Sensor Networks"):
// received signal strength in dB (eq. 1), the two-stage GLRT that tells a target inside a sensor's
// radius r0 from one in between (eqs. 2-13), the attach and duplicate rules, and the Maximum
// Likelihood Monte Carlo localisation (eq. 15), joint or factorised. Pure functions: no DDS, no tiles.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "common/geometry.hpp"
#include "common/messages.hpp"

namespace wsn::node::adman {

/// Q(x) = P(N(0, 1) > x).
double upperTail(double x);
/// Q^-1(p) for p in (0, 1): the x with Q(x) = p (relative error below 1e-12); throws
/// std::invalid_argument outside (0, 1).
double upperTailInverse(double p);

/// Eq. (1)'s propagation: a target radiates Psi (dB) measured at d0, falling as d^-alpha.
struct PowerModel {
  double power_db = 40.0;          ///< Psi at the reference distance, dB
  double reference_distance = 1.0;  ///< d0
  double attenuation = 2.0;        ///< alpha >= 1
  /// Psi d0^alpha in linear units (J/s).
  double linearScale() const;
  /// The linear power one target at distance d gives (d clamped to 1e-9 d0 so that a target on a
  /// sensor stays finite).
  double linearAt(double distance) const;
};

/// theta_n of eq. (1): 10 log10 of the sum over `targets` of Psi d0^alpha / |sensor - l_k|^alpha; a
/// floor of -300 dB when there is no target.
double receivedDb(const PowerModel& model, common::Vec2 sensor, std::span<const common::Vec2> targets);
/// 10 log10 of a linear power, floored at -300 dB.
double toDb(double linear);

/// The GLRT's two thresholds on a reading y (dB), from the worst case of each composite test
/// (spec A2): tau32 = Delta1 + sigma Q^-1(P_FA), tau10 = Delta2 + sigma Q^-1(P_FA).
struct Thresholds {
  double delta1 = 0.0;       ///< Delta1 = 10 log10(Psi d0^alpha / r0^alpha): a target at r0
  double delta2 = 0.0;       ///< Delta2 = 10 log10(Psi d0^alpha / (sqrt2 r0)^alpha): at sqrt2 r0
  double tau_inside = 0.0;   ///< tau32: y above it decides H3, a target within r0
  double tau_between = 0.0;  ///< tau10: y in (tau10, tau32] decides H1, a target in between
};
/// The thresholds of sensors of inside radius r0, noise sigma (dB) and false-alarm probability
/// P_FA per stage; throws std::invalid_argument for r0 <= 0, sigma < 0 or P_FA outside (0, 1).
Thresholds thresholds(const PowerModel& model, double inside_radius, double sigma_db, double false_alarm);

/// Eq. (7): ln L_G(y) = (2 th3 y - 2 th2 y - th3^2 + th2^2) / (2 sigma^2) with th3 = max(y, Delta),
/// th2 = min(y, Delta), which is sgn(y - Delta) (y - Delta)^2 / (2 sigma^2).
double glrtLogRatio(double y, double delta, double sigma_db);
/// P(y > tau) for a reading of mean theta: Q((tau - theta) / sigma).
double detectionProbability(double theta, double tau, double sigma_db);

/// What a sensor decided about the targets around it.
enum class Kind : std::int32_t {
  inside = 3,   ///< H3: a target within r0 (its report's power_level)
  between = 1,  ///< H1: a target between r0 and sqrt2 r0
};

/// One sensor's reading as the attach rules see it.
struct Reading {
  common::SensorId sensor = 0;
  common::Vec2 at;  ///< the sensor's position (the grid rules use the true one)
  double y = 0.0;   ///< dB
};

/// A target attached to a sensor.
struct Attachment {
  common::SensorId sensor = 0;
  Kind kind = Kind::inside;
  friend bool operator==(const Attachment&, const Attachment&) = default;
};

/// The sensors of a grid of pitch p: N4 = those within 1.01 p, N8 = within 1.01 sqrt2 p. On a random
/// layout of mean spacing p the same radii are used, but the sets vary from sensor to sensor and
/// the duplicate rule's argument (a diagonal neighbour's inside target is below Delta2 here) holds
/// only on a grid.
struct Neighbourhood {
  double pitch = 1.0;
  double n4() const;
  double n8() const;
};

/// The attach rules (spec A2, proposed where [A] is ambiguous), over `view`, every reading the
/// caller knows (sorted by sensor id):
///   1. every sensor with y > tau32 gets an inside target;
///   2. a sensor with tau10 < y <= tau32 is a candidate for an in-between target unless an N4
///      neighbour holds an inside target (the same target, seen from its side);
///   3. a candidate gets an in-between target when its y beats (>=) every candidate of its N8, a
///      tie going to the lower id.
/// The spec applies 3 before 2, so that an in-between reading explained by an inside target can
/// still suppress the one in-between target near it: docs/ADMAN.md measures the difference. A rule
/// reads the readings within n8() + n4() of the sensor; a caller that knows those gets the
/// sensor's attachment right. Sorted by sensor id.
std::vector<Attachment> attach(std::span<const Reading> view, const Thresholds& thresholds,
                               const Neighbourhood& neighbours);

/// Eq. (15), completed as the spec proposes (A3): particles uniform in a disc around the attached
/// sensor (radius r0 inside, sqrt2 r0 in between), scored by the Gaussian log-likelihood of the
/// readings of the sensor's block (itself and its N8) with theta from eq. (1) over this target and
/// the others held fixed; the estimate is the best particle.
/// The most factorised sweeps (each has its own particle stream; see adman.cpp).
inline constexpr std::int32_t kMaxSweeps = 14;

struct MlmcSettings {
  PowerModel power;
  double sigma_db = 0.17321;
  double inside_radius = 0.5;
  std::int32_t particles = 3000;
  /// Factorised: sweep 1 scores a target on the block sensors no nearer to another attached sensor
  /// than to its own (the others are not placed yet); later sweeps score the whole block with the
  /// others held at the last sweep's estimates.
  std::int32_t sweeps = 2;
  bool joint = false;       ///< [A]'s joint search over a target and the targets around it
  double interaction_range = 4.0;  ///< others: targets attached within this of the target's sensor
  Neighbourhood neighbours;
  std::uint64_t seed = 1;
};

/// A target placed by MLMC: where, how sure (the likelihood-weighted spread of the particles, at
/// least the spread one particle's share of the disc leaves) and the log-likelihood of the best
/// particle.
struct Placement {
  Attachment attachment;
  common::Vec2 at;
  double cov_xx = 0.0;
  double cov_xy = 0.0;
  double cov_yy = 0.0;
  double log_likelihood = 0.0;
};

/// Gaussian log-likelihood of the readings `block` (indices into `view`) for targets at `targets`:
/// -sum (y_m - theta_m)^2 / (2 sigma^2).
double logLikelihood(std::span<const Reading> view, std::span<const std::size_t> block,
                     std::span<const common::Vec2> targets, const PowerModel& model, double sigma_db);

/// How far from a placed target's sensor place() and attach() read: the readings and attachments
/// within this distance decide the placement, so a caller that knows them gets the same answer as
/// one that knows the whole field. Factorised: (sweeps - 1) interaction ranges (sweep s holds the
/// others at sweep s - 1), plus 2 n8() (sweep 1 of the farthest target reads the attachments whose
/// sensors may be nearer to its block sensors than its own), plus n8() + n4() (the attach rules of
/// those); joint: one interaction range plus n8() + n8() + n4().
double viewReach(const MlmcSettings& settings);

/// Places the targets `attached` (indices into `attachments`) given every attachment and reading in
/// `view` at `tick` (see viewReach for what it reads). Particle draws are keyed by (seed, sensor,
/// tick, sweep), so the answer does not depend on which caller asks. In the order of `attached`.
std::vector<Placement> place(std::span<const Reading> view, std::span<const Attachment> attachments,
                             std::span<const std::size_t> attached, std::int32_t tick, const MlmcSettings& settings);

}  // namespace wsn::node::adman
