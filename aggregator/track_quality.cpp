#include "aggregator/track_quality.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "common/assignment.hpp"
#include "common/near_pairs.hpp"
#include "common/output.hpp"

namespace wsn::aggregator {

std::vector<int> associateTargetsWithTracks(const std::vector<common::TargetState>& truth,
                                                     const std::vector<common::TrackEstimate>& tracks, double gate) {
  std::vector<common::Vec2> truth_at, track_at;
  for (const auto& target : truth) truth_at.push_back({target.x, target.y});
  for (const auto& track : tracks) track_at.push_back({track.x, track.y});
  std::vector<common::AssignmentPair> pairs;
  common::forEachPairWithin(truth_at, track_at, gate, [&](std::uint32_t i, std::uint32_t j) {
    const double d = std::hypot(tracks[j].x - truth[i].x, tracks[j].y - truth[i].y);
    if (d <= gate) pairs.push_back({i, j, d});
  });
  return common::solveSparseAssignment(truth.size(), tracks.size(), pairs);
}

TrackQualityAccumulator::TrackQualityAccumulator(double association_gate) : gate_(association_gate) {
  if (!(gate_ > 0.0))  // +inf is allowed: no gate
    throw std::invalid_argument("track_quality: association_gate must be > 0, got " + common::fixed6(gate_));
}

void TrackQualityAccumulator::add(const std::vector<common::TargetState>& truth,
                                  const std::vector<common::TrackEstimate>& tracks_in) {
  std::vector<common::TrackEstimate> tracks;
  tracks.reserve(tracks_in.size());
  for (const auto& h : tracks_in) {
    if (common::isFinite(h))
      tracks.push_back(h);
    else
      ++ignored_nonfinite_;
  }

  const std::size_t rows = truth.size();
  const std::size_t cols = tracks.size();
  const auto assignment = associateTargetsWithTracks(truth, tracks, gate_);

  const std::int64_t call = calls_++;
  std::int64_t associated = 0;
  for (std::size_t i = 0; i < rows; ++i) {
    Sums& s = sums_[truth[i].id];
    ++s.alive;
    // The segment ending at this tick, when the target was alive at the previous one too.
    const double segment =
        s.last_call == call - 1 ? std::hypot(truth[i].x - s.last_x, truth[i].y - s.last_y) : 0.0;
    s.path += segment;
    s.last_call = call;
    s.last_x = truth[i].x;
    s.last_y = truth[i].y;
    if (assignment[i] < 0) continue;
    s.path_associated += segment;
    const auto& h = tracks[static_cast<std::size_t>(assignment[i])];
    const double ex = h.x - truth[i].x;
    const double ey = h.y - truth[i].y;
    const double evx = h.vx - truth[i].vx;
    const double evy = h.vy - truth[i].vy;
    ++s.associated;
    ++associated;
    s.squared_position += ex * ex + ey * ey;
    s.squared_velocity += evx * evx + evy * evy;
    s.position += std::hypot(ex, ey);
  }
  false_track_ticks_ += static_cast<std::int64_t>(cols) - associated;
}

TrackQualitySummary TrackQualityAccumulator::summary() const {
  TrackQualitySummary out;
  out.false_track_ticks = false_track_ticks_;
  out.tracks_ignored_nonfinite = ignored_nonfinite_;
  out.targets.reserve(sums_.size());
  for (const auto& [id, s] : sums_) {
    TargetQuality q;
    q.id = id;
    q.ticks_alive = s.alive;
    q.ticks_associated = s.associated;
    q.tlr = static_cast<double>(s.associated) / static_cast<double>(s.alive);  // alive >= 1 by construction
    q.path_length = s.path;
    q.path_length_associated = s.path_associated;
    q.tlr_length = s.path > 0.0 ? s.path_associated / s.path : q.tlr;  // a target that never moved: its TLR
    q.errors_defined = s.associated > 0;
    if (q.errors_defined) {
      const double a = static_cast<double>(s.associated);
      q.rse_position = std::sqrt(s.squared_position / a);
      q.rse_velocity = std::sqrt(s.squared_velocity / a);
      q.mean_position_error = s.position / a;
    }
    out.targets.push_back(q);
  }
  std::int64_t with_errors = 0;
  for (const auto& q : out.targets) {
    out.mean_tlr += q.tlr;
    out.mean_tlr_length += q.tlr_length;
    if (!q.errors_defined) continue;
    ++with_errors;
    out.mean_rse_position += q.rse_position;
    out.mean_rse_velocity += q.rse_velocity;
    out.mean_position_error += q.mean_position_error;
  }
  if (!out.targets.empty()) {
    out.mean_tlr /= static_cast<double>(out.targets.size());
    out.mean_tlr_length /= static_cast<double>(out.targets.size());
  }
  out.means_defined = with_errors > 0;
  if (out.means_defined) {
    const auto n = static_cast<double>(with_errors);
    out.mean_rse_position /= n;
    out.mean_rse_velocity /= n;
    out.mean_position_error /= n;
  }
  return out;
}

}  // namespace wsn::aggregator
