#include "aggregator/mcmcda_association.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "common/class_evidence.hpp"
#include "common/shared_derivations.hpp"

namespace wsn::aggregator {
namespace {

using supernode::mcmcda::McmcdaEngine;

}  // namespace

supernode::mcmcda::McmcdaParams trackLevelEngineDefaults() {
  supernode::mcmcda::McmcdaParams p;
  // A supernode reports a track only once it holds confirm_observations (3) reports; the
  // aggregator's elements are already those established tracks, so two of them suffice, and a
  // third would only delay every global track by another tick.
  p.confirm_observations = 2;
  // A false element is a supernode track confirmed on clutter, far rarer than a false report
  // (lambda_f = 6e-4 at the supernodes). On oh_quadrants, seeds 1-5, mean epsilon_K is flat in it:
  // 0.1355 / 0.1325 / 0.1355 at 1e-4 / 1e-5 / 1e-6.
  p.model.false_alarm_density = 1e-5;
  return p;
}

const common::config::FieldTable<McmcdaAssociationParams>& mcmcdaAssociationParamTable() {
  using P = McmcdaAssociationParams;
  static const common::config::FieldTable<P> table = [] {
    common::config::FieldTable<P> t{"aggregator.params (mcmcda)", {}};
    t.fields.push_back(common::config::integer<P>(
        "window_size", &P::window_size, 1, 1000, "ticks",
        "ws of the aggregator's sliding window; an element older than that is dropped"));
    for (auto& f : common::config::lift<P>(supernode::mcmcda::paramTable(), &P::engine)) t.fields.push_back(f);
    return t;
  }();
  return table;
}

AssociationSpec mcmcdaAssociationSpec() {
  AssociationSpec spec;
  spec.name = "mcmcda";
  spec.description =
      "track-level MCMCDA (Oh et al. §VI): the supernodes' tracks at the ticks they were observed form Yc, "
      "a sliding-window MCMCDA over the whole region links them into global tracks";
  // The targets' model follows the scenario as at the supernodes; the rest describes supernode
  // tracks rather than reports, and keeps the defaults above (docs/AGGREGATION.md).
  spec.params = common::paramSpecs(mcmcdaAssociationParamTable(),
                                   {{"initial_velocity_sigma", common::newTrackVelocityDerivation()},
                                    {"max_speed", common::linkSpeedDerivation()},
                                    {"termination_probability", common::terminationDerivation()},
                                    {"birth_density", common::birthDensityDerivation()}});
  spec.create = [](const AssociationContext& context) -> std::unique_ptr<TrackAssociator> {
    return std::make_unique<McmcdaAssociator>(context);
  };
  return spec;
}

McmcdaAssociator::McmcdaAssociator(const AssociationContext& context)
    : McmcdaAssociator(
          [&] {
            auto p = common::decodeParams(mcmcdaAssociationParamTable(), context.params);
            p.engine.model.process_noise_sigma = context.dynamics.process_noise_sigma;
            p.engine.model.delta = context.dynamics.delta;
            return p;
          }(),
          context.region, context.seed, context.supernode_count) {}

McmcdaAssociator::McmcdaAssociator(const McmcdaAssociationParams& params, const common::Rect& region,
                                   std::uint64_t seed, std::uint32_t stream_key)
    : engine_(std::make_unique<McmcdaEngine>(params.engine, region, seed, stream_key,
                                             common::track_id::Space::ofAggregator())),
      window_(params.window_size) {
  const auto source_of = [this](const McmcdaEngine::ObservationKey& key) -> common::TrackId {
    const auto it = source_.find(key.sensor);
    return it == source_.end() ? 0 : it->second;
  };
  engine_->setIdProposer([source_of](const std::vector<McmcdaEngine::ObservationKey>& observations) {
    return observations.empty() ? common::TrackId{0} : source_of(observations.front());
  });
  engine_->setGroupOf(source_of);
}

std::vector<common::TrackEstimate> McmcdaAssociator::associate(std::int32_t tick,
                                                                const std::vector<SupernodeTracks>& inputs) {
  window_.advanceTo(tick);
  // Canonical order, so that neither the order of inputs nor of tracks changes element ids.
  struct Element {
    ElementKey key;
    double x;
    double y;
  };
  std::vector<Element> elements;
  for (const auto& input : inputs)
    for (const auto& track : input.tracks) {
      if (!common::isFinite(track)) {
        ++dropped_non_finite_;
        continue;
      }
      // An engine that does not say when it last saw the target: every estimate is an element.
      const std::int32_t seen = track.last_seen_tick >= 1 && track.last_seen_tick <= tick ? track.last_seen_tick : tick;
      const double back = static_cast<double>(tick - seen);
      elements.push_back({{track.track, seen}, track.x - track.vx * back, track.y - track.vy * back});
    }
  std::sort(elements.begin(), elements.end(), [](const Element& a, const Element& b) {
    return std::tie(a.key, a.x, a.y) < std::tie(b.key, b.x, b.y);
  });
  for (const auto& e : elements) {
    if (seen_.contains(e.key)) continue;  // the first report of an element stands, like a delivered report
    const common::SensorId id = next_element_++;
    seen_.emplace(e.key, id);
    source_.emplace(id, e.key.first);
    common::Observation o;
    o.tick_generated = e.key.second;
    o.tick_delivered = tick;
    o.sensor = id;
    o.x = e.x;
    o.y = e.y;
    window_.insert(o);
  }
  std::erase_if(seen_, [&](const auto& entry) {
    if (entry.first.second >= window_.oldestTick()) return false;
    source_.erase(entry.second);
    return true;
  });
  engine_->step(window_);

  // The supernode tracks reported at this tick, by id. A handed-over track may be reported by both
  // supernodes for a tick: the lower supernode's estimate stands, whatever the order of inputs.
  std::vector<const SupernodeTracks*> by_supernode;
  for (const auto& input : inputs) by_supernode.push_back(&input);
  std::stable_sort(by_supernode.begin(), by_supernode.end(),
                   [](const SupernodeTracks* a, const SupernodeTracks* b) { return a->supernode < b->supernode; });
  std::map<common::TrackId, const common::TrackEstimate*> reported;
  for (const auto* input : by_supernode)
    for (const auto& track : input->tracks)
      if (common::isFinite(track)) reported.emplace(track.track, &track);
  // The global tracks to report, with the supernode tracks each holds.
  const auto views = engine_->liveTracks();
  std::vector<const supernode::mcmcda::McmcdaEngine::LiveTrackView*> chosen;
  std::vector<ReportedIds::Global> globals;
  std::set<common::TrackId> live_ids;
  std::set<common::TrackId> held;  // supernode tracks with an element in a reported global track
  for (const auto& view : views) {
    live_ids.insert(view.now.track);
    if (!view.confirmed || !view.in_region) continue;
    ReportedIds::Global global{view.now.track, {}};
    bool supported = false;
    for (const auto& key : view.observations)
      if (const auto source = source_.find(key.sensor); source != source_.end()) {
        global.sources.push_back(source->second);
        supported = supported || reported.contains(source->second);
      }
    if (!supported && !view.probably_alive) continue;
    held.insert(global.sources.begin(), global.sources.end());
    chosen.push_back(&view);
    globals.push_back(std::move(global));
  }
  std::vector<const common::TrackEstimate*> passed;
  std::vector<common::TrackId> passed_ids;
  for (const auto& [id, track] : reported)
    if (!held.contains(id)) {
      passed.push_back(track);
      passed_ids.push_back(id);
    }

  const ReportedIds::Assignment ids = reported_ids_.assign(globals, passed_ids, live_ids);
  std::vector<common::TrackEstimate> out;
  for (std::size_t n = 0; n < chosen.size(); ++n) {
    common::TrackEstimate e = chosen[n]->now;
    e.track = ids.global[n];
    // The track-level engine sees positions only; the class and stop probability are fused from the supernode tracks
    // it holds that were reported at this tick (in id order, so the result is canonical).
    std::vector<std::span<const double>> classes;
    std::vector<std::optional<double>> stopped;
    for (const common::TrackId source : std::set<common::TrackId>(globals[n].sources.begin(), globals[n].sources.end()))
      if (const auto it = reported.find(source); it != reported.end()) {
        classes.emplace_back(it->second->class_probabilities);
        stopped.push_back(it->second->stop_probability);
      }
    e.class_probabilities = common::fuseClassVectors(classes);
    e.stop_probability = common::fuseStopProbabilities(stopped);
    out.push_back(e);
  }
  for (std::size_t n = 0; n < passed.size(); ++n)
    if (ids.passed[n] != 0) out.push_back(*passed[n]);
  std::sort(out.begin(), out.end(),
            [](const common::TrackEstimate& a, const common::TrackEstimate& b) { return a.track < b.track; });
  return out;
}

ReportedIds::Assignment ReportedIds::assign(const std::vector<Global>& globals,
                                            const std::vector<common::TrackId>& passed,
                                            const std::set<common::TrackId>& live_engine_ids) {
  std::erase_if(alias_, [&](const auto& entry) { return !live_engine_ids.contains(entry.first); });
  Assignment out;
  out.global.assign(globals.size(), 0);
  std::set<common::TrackId> used;
  // First, tracks already reported at the previous tick keep their id (in input order, so a
  // conflict between an engine id and an alias of it goes to the engine id, the smaller index).
  for (std::size_t n = 0; n < globals.size(); ++n) {
    const auto alias = alias_.find(globals[n].engine_id);
    const common::TrackId id = alias != alias_.end() ? alias->second : globals[n].engine_id;
    if (previous_.contains(id) && !used.contains(id)) {
      out.global[n] = id;
      used.insert(id);
    }
  }
  // Then tracks new to the output: the free previous id most of their supernode tracks were
  // reported under (the smallest on a tie), else their engine id.
  for (std::size_t n = 0; n < globals.size(); ++n) {
    if (out.global[n] != 0) continue;
    const common::TrackId engine_id = globals[n].engine_id;
    std::map<common::TrackId, std::int32_t> votes;
    for (const auto source : globals[n].sources)
      if (const auto owner = owner_.find(source); owner != owner_.end()) ++votes[owner->second];
    common::TrackId id = engine_id;
    std::int32_t best = 0;
    for (const auto& [candidate, count] : votes)
      if (count > best && !used.contains(candidate)) {
        id = candidate;
        best = count;
      }
    if (used.contains(id)) id = engine_id;  // an engine id is unique among live tracks; an alias may not be
    if (id != engine_id) alias_[engine_id] = id;
    out.global[n] = id;
    used.insert(id);
  }
  owner_.clear();
  for (std::size_t n = 0; n < globals.size(); ++n)
    for (const auto source : globals[n].sources) owner_[source] = out.global[n];
  // A passed-through supernode track is reported under its own id unless a global track has it.
  for (const auto id : passed) {
    const bool free = !used.contains(id);
    out.passed.push_back(free ? id : 0);
    if (!free) continue;
    used.insert(id);
    owner_[id] = id;
  }
  previous_ = std::move(used);
  return out;
}

}  // namespace wsn::aggregator
