#include "aggregator/run_scorer.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "common/output.hpp"

namespace wsn::aggregator {
namespace {

/// A JSON string literal; scenario names are free text.
std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(c));
      out += buffer;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

std::string countsJson(const BoundaryCounts& c) {
  std::ostringstream out;
  out << "{\"target_ticks\": " << c.target_ticks << ", \"duplicate_track_ticks\": " << c.duplicate_track_ticks
      << ", \"id_switches\": " << c.id_switches << ", \"fragmentations\": " << c.fragmentations << "}";
  return out.str();
}

}  // namespace

RunScorer::RunScorer(const common::MetricsConfig& config, std::vector<common::Vec2> supernodes)
    : config_(config),
      metrics_(config),
      clear_mot_(config.mot_threshold),
      quality_(config.quality_gate),
      boundary_(std::move(supernodes), config.boundary_band, config.mot_threshold) {
  // gospaDistance checks c and p only when called; fail at construction like the others.
  (void)gospaDistance({}, {}, config_.gospa_c, config_.gospa_p);
}

TickScores RunScorer::add(std::int32_t tick, const std::vector<common::TargetState>& truth,
                          const std::vector<common::TrackEstimate>& tracks) {
  if (any_tick_ && tick <= last_tick_)
    throw std::invalid_argument("run_scorer: tick " + std::to_string(tick) + " added after tick " +
                                std::to_string(last_tick_));
  any_tick_ = true;
  last_tick_ = tick;

  std::vector<common::TrackEstimate> finite;
  finite.reserve(tracks.size());
  for (const auto& track : tracks)
    if (common::isFinite(track)) finite.push_back(track);

  const MetricsTick basic = metrics_.add(tick, truth, tracks);
  const ClearMotTick events = clear_mot_.add(tick, truth, finite);
  boundary_.add(truth, events);
  quality_.add(truth, finite);

  std::vector<common::Vec2> truth_positions, track_positions;
  truth_positions.reserve(truth.size());
  track_positions.reserve(finite.size());
  for (const auto& target : truth) truth_positions.push_back({target.x, target.y});
  for (const auto& track : finite) track_positions.push_back({track.x, track.y});
  gospa_.push_back(gospaDistance(truth_positions, track_positions, config_.gospa_c, config_.gospa_p));

  TickScores out;
  out.tick = tick;
  out.truth_targets = basic.k_true;
  out.tracks = basic.k;
  out.ospa = basic.ospa;
  out.gospa = gospa_.back();
  out.eps_k_running = basic.eps_k_running;
  out.ospa_mean_running = basic.ospa_mean_running;
  return out;
}

RunScores RunScorer::finish() const {
  RunScores s;
  s.metrics = metrics_.finish();
  s.gospa_c = config_.gospa_c;
  s.gospa_p = config_.gospa_p;
  s.gospa = meanGospa(gospa_);
  s.mot_threshold = config_.mot_threshold;
  s.clear_mot = clear_mot_.summary();
  s.quality_gate = config_.quality_gate;
  s.track_quality = quality_.summary();
  s.boundary = boundary_.summary();
  return s;
}

std::string perTickCsvRow(const TickScores& s) {
  return std::to_string(s.tick) + "," + std::to_string(s.truth_targets) + "," + std::to_string(s.tracks) + "," +
         common::fixed6(s.ospa) + "," + common::fixed6(s.gospa.distance) + "," + common::fixed6(s.gospa.localisation) +
         "," + common::fixed6(s.gospa.missed) + "," + common::fixed6(s.gospa.false_targets);
}

std::string metricsJson(const RunInfo& info, const RunScores& s, double wall_s, double ticks_per_s) {
  std::ostringstream out;
  // The top-level eps_k, eps_x and ospa come first: tools/sweep.py and the launcher's summary
  // read them (the launcher takes the first occurrence of a key).
  out << "{\n";
  out << "  \"scenario\": " << jsonString(info.scenario) << ",\n";
  out << "  \"seed\": " << info.seed << ",\n";
  out << "  \"ticks\": " << info.ticks << ",\n";
  out << "  \"engine\": " << jsonString(info.engine) << ",\n";
  out << "  \"association\": " << jsonString(info.association) << ",\n";
  out << "  \"truth_targets\": " << info.truth_targets << ",\n";
  out << "  \"eps_k\": " << jsonReal(s.metrics.eps_k) << ",\n";
  out << "  \"eps_x\": " << jsonReal(s.metrics.eps_x) << ",\n";
  out << "  \"ospa\": " << jsonReal(s.metrics.ospa_mean) << ",\n";
  out << "  \"observations_dropped_stale\": " << info.observations_dropped_stale << ",\n";
  out << "  \"metrics\": " << toJson(s.metrics) << ",\n";

  const GospaMean& g = s.gospa;
  out << "  \"gospa\": {\n";
  out << "    \"c\": " << jsonReal(s.gospa_c) << ",\n";
  out << "    \"p\": " << jsonReal(s.gospa_p) << ",\n";
  out << "    \"alpha\": 2,\n";
  out << "    \"ticks\": " << g.ticks << ",\n";
  out << "    \"mean\": " << jsonReal(g.distance) << ",\n";
  out << "    \"localisation\": " << jsonReal(g.localisation) << ",\n";
  out << "    \"missed\": " << jsonReal(g.missed) << ",\n";
  out << "    \"false\": " << jsonReal(g.false_targets) << ",\n";
  out << "    \"missed_targets\": " << jsonReal(g.missed_targets) << ",\n";
  out << "    \"false_tracks\": " << jsonReal(g.false_tracks) << "\n";
  out << "  },\n";

  const ClearMotSummary& m = s.clear_mot;
  out << "  \"clear_mot\": {\n";
  out << "    \"threshold\": " << jsonReal(s.mot_threshold) << ",\n";
  out << "    \"mota\": " << jsonReal(m.mota) << ",\n";
  out << "    \"mota_defined\": " << jsonBool(m.mota_defined) << ",\n";
  out << "    \"motp\": " << jsonReal(m.motp) << ",\n";
  out << "    \"motp_defined\": " << jsonBool(m.motp_defined) << ",\n";
  out << "    \"id_switches\": " << m.id_switches << ",\n";
  out << "    \"fragmentations\": " << m.fragmentations << ",\n";
  out << "    \"misses\": " << m.misses << ",\n";
  out << "    \"false_positives\": " << m.false_positives << ",\n";
  out << "    \"matches\": " << m.matches << ",\n";
  out << "    \"ground_truth\": " << m.ground_truth << "\n";
  out << "  },\n";

  const TrackQualitySummary& q = s.track_quality;
  out << "  \"track_quality\": {\n";
  out << "    \"gate\": " << jsonReal(s.quality_gate) << ",\n";
  out << "    \"means_defined\": " << jsonBool(q.means_defined) << ",\n";
  out << "    \"mean_rse_position\": " << jsonReal(q.mean_rse_position) << ",\n";
  out << "    \"mean_rse_velocity\": " << jsonReal(q.mean_rse_velocity) << ",\n";
  out << "    \"mean_tlr\": " << jsonReal(q.mean_tlr) << ",\n";
  out << "    \"mean_position_error\": " << jsonReal(q.mean_position_error) << ",\n";
  out << "    \"false_track_ticks\": " << q.false_track_ticks << ",\n";
  out << "    \"targets\": [";
  for (std::size_t i = 0; i < q.targets.size(); ++i) {
    const TargetQuality& t = q.targets[i];
    out << (i == 0 ? "\n" : ",\n") << "      {\"id\": " << t.id << ", \"ticks_alive\": " << t.ticks_alive
        << ", \"ticks_associated\": " << t.ticks_associated << ", \"errors_defined\": " << jsonBool(t.errors_defined)
        << ", \"rse_position\": " << jsonReal(t.rse_position) << ", \"rse_velocity\": " << jsonReal(t.rse_velocity)
        << ", \"tlr\": " << jsonReal(t.tlr) << ", \"mean_position_error\": " << jsonReal(t.mean_position_error) << "}";
  }
  out << (q.targets.empty() ? "]\n" : "\n    ]\n");
  out << "  },\n";

  const BoundarySummary& b = s.boundary;
  out << "  \"boundary\": {\n";
  out << "    \"band\": " << jsonReal(b.band) << ",\n";
  out << "    \"supernodes\": " << b.supernodes << ",\n";
  out << "    \"mot_threshold\": " << jsonReal(b.mot_threshold) << ",\n";
  out << "    \"boundary\": " << countsJson(b.boundary) << ",\n";
  out << "    \"interior\": " << countsJson(b.interior) << "\n";
  out << "  },\n";

  if (!info.provenance_json.empty()) out << "  \"provenance\": " << info.provenance_json << ",\n";
  out << "  \"timing\": {\"wall_s\": " << jsonReal(wall_s) << ", \"ticks_per_s\": " << jsonReal(ticks_per_s) << "}\n";
  out << "}\n";
  return out.str();
}

}  // namespace wsn::aggregator
