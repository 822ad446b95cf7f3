#include "aggregator/mcmcda_association.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "aggregator/track_fusion.hpp"
#include "common/shared_derivations.hpp"

namespace wsn::aggregator {
namespace {

using supernode::mcmcda::McmcdaEngine;

/// The supernode tracks each engine view holds now, by view index, in id order. Each reported
/// supernode track belongs to the view that holds its newest element: the state it publishes is the
/// target's since that element, and the chain may have given its older elements to another view
/// when it re-decided a supernode's identities.
std::map<std::size_t, std::vector<const common::TrackEstimate*>> tracksNow(
    const std::vector<McmcdaEngine::LiveTrackView>& views,
    const std::map<common::TrackId, const common::TrackEstimate*>& reported,
    const std::map<common::SensorId, common::TrackId>& source_of) {
  std::map<common::TrackId, std::pair<std::int32_t, std::size_t>> newest;  // source -> (tick, view)
  for (std::size_t v = 0; v < views.size(); ++v)
    for (const auto& key : views[v].observations)
      if (const auto source = source_of.find(key.sensor);
          source != source_of.end() && reported.contains(source->second)) {
        const auto [it, inserted] = newest.try_emplace(source->second, key.tick, v);
        if (!inserted && key.tick > it->second.first) it->second = {key.tick, v};
      }
  // A view's tracks now: the one whose element is the newest (the smaller id on a tie) and those
  // whose estimates now pass the track-to-track test against it (aggregator/track_fusion.hpp); one
  // that fails is another target the chain linked over a long gap, and is passed through as its
  // supernode reports it. A supernode's two tracks of one target (its chain broke the track under
  // delays) fuse like two supernodes' tracks.
  std::map<std::size_t, std::vector<std::pair<std::int32_t, common::TrackId>>> candidates;  // view -> (tick, id)
  for (const auto& [source, where] : newest) candidates[where.second].emplace_back(where.first, source);
  std::map<std::size_t, std::vector<const common::TrackEstimate*>> members;  // view -> its tracks now, id order
  for (auto& [view, found] : candidates) {
    std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const common::TrackEstimate* primary = reported.at(found.front().second);
    auto& kept = members[view];
    for (const auto& [element_tick, source] : found)
      if (const auto* track = reported.at(source); track == primary || sameTarget(*primary, *track))
        kept.push_back(track);
    std::sort(kept.begin(), kept.end(), [](const auto* a, const auto* b) { return a->track < b->track; });
  }
  return members;
}

}  // namespace

supernode::mcmcda::McmcdaParams trackLevelEngineDefaults() {
  supernode::mcmcda::McmcdaParams p;
  // A supernode reports a track only once it holds confirm_observations reports; the aggregator's
  // elements are already those established tracks, so two of them suffice, and a third would only
  // delay every global track by another tick.
  p.confirm_observations = 2;
  return p;
}

std::map<std::string, common::ParamDerivation> trackLevelDerivations() {
  // An element is a supernode track at a tick its target was observed, so the model of eq. (3) over
  // Yc is the supernodes' own: it is observed when a report of it reached its supernode (the same
  // pd, by lag, and max_gap), its position errs by at most a report's error (a filtered position
  // errs less), every false element is a false report a supernode confirmed (the supernodes'
  // delivered false-report density bounds theirs), and targets are born, move and end as there.
  auto derivations = supernode::mcmcda::paramDerivations();
  // Not of the elements: they are already confirmed tracks (above), and one target gives one
  // element per supernode track and tick, with nothing to merge.
  derivations.erase("confirm_observations");
  derivations.erase("merge_radius");
  return derivations;
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
  // The model follows the scenario as at the supernodes (docs/AGGREGATION.md).
  spec.params = common::paramSpecs(mcmcdaAssociationParamTable(), trackLevelDerivations());
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

void McmcdaAssociator::addElements(std::int32_t tick, const std::vector<SupernodeTracks>& inputs) {
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
}

std::vector<common::TrackEstimate> McmcdaAssociator::associate(std::int32_t tick,
                                                                const std::vector<SupernodeTracks>& inputs) {
  addElements(tick, inputs);
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
  const auto views = engine_->liveTracks();
  const auto members = tracksNow(views, reported, source_);
  // The global tracks to report: a confirmed one while a supernode reports a track it holds now. It
  // ends when they end: a supernode sees the raw reports and their delays, the aggregator only
  // their outcome, so a supernode's judgement that its target has gone outranks the aggregator's.
  std::vector<std::size_t> chosen;
  std::vector<ReportedIds::Global> globals;
  std::set<common::TrackId> live_ids;
  std::set<common::TrackId> held;  // supernode tracks a reported global track holds now
  for (std::size_t v = 0; v < views.size(); ++v) {
    live_ids.insert(views[v].now.track);
    const auto now = members.find(v);
    if (!views[v].confirmed || now == members.end()) continue;
    ReportedIds::Global global{views[v].now.track, {}};
    for (const auto* track : now->second) {
      global.sources.push_back(track->track);
      held.insert(track->track);
    }
    chosen.push_back(v);
    globals.push_back(std::move(global));
  }
  std::vector<const common::TrackEstimate*> passed;
  std::vector<common::TrackId> passed_ids;
  for (const auto& [id, track] : reported)
    if (!held.contains(id)) {
      passed.push_back(track);
      passed_ids.push_back(id);
    }

  const ReportedIds::Assignment ids =
      reported_ids_.assign(globals, passed_ids, live_ids, [this] { return engine_->mintId(); });
  std::vector<common::TrackEstimate> out;
  // A global track's estimate is fused from its supernode tracks as they published them.
  for (std::size_t n = 0; n < chosen.size(); ++n) out.push_back(fuseTrackEstimates(ids.global[n], members.at(chosen[n])));
  for (std::size_t n = 0; n < passed.size(); ++n) {
    out.push_back(*passed[n]);
    out.back().track = ids.passed[n];
  }
  std::sort(out.begin(), out.end(),
            [](const common::TrackEstimate& a, const common::TrackEstimate& b) { return a.track < b.track; });
  return out;
}

ReportedIds::Assignment ReportedIds::assign(const std::vector<Global>& globals,
                                            const std::vector<common::TrackId>& passed,
                                            const std::set<common::TrackId>& live_engine_ids,
                                            const std::function<common::TrackId()>& mint) {
  std::erase_if(alias_, [&](const auto& entry) { return !live_engine_ids.contains(entry.first); });
  Assignment out;
  out.global.assign(globals.size(), 0);
  std::set<common::TrackId> used;
  const auto take = [&](common::TrackId& slot, common::TrackId id) {
    slot = id;
    used.insert(id);
  };
  // First, the id its supernode tracks were reported under at the previous tick (the most of them,
  // the smallest on a tie), when free: a supernode's identities are decided on the raw reports, and
  // the chain may re-form a target's global track under another engine id.
  for (std::size_t n = 0; n < globals.size(); ++n) {
    std::map<common::TrackId, std::int32_t> votes;
    for (const auto source : globals[n].sources)
      if (const auto owner = owner_.find(source); owner != owner_.end()) ++votes[owner->second];
    common::TrackId best_id = 0;
    std::int32_t best = 0;
    for (const auto& [candidate, count] : votes)
      if (count > best && !used.contains(candidate)) {
        best_id = candidate;
        best = count;
      }
    if (best_id != 0) take(out.global[n], best_id);
  }
  // Then a track the engine continues keeps the id it was reported under at the previous tick (a
  // target's new supernode track joining its global track), in input order.
  for (std::size_t n = 0; n < globals.size(); ++n) {
    if (out.global[n] != 0) continue;
    const auto alias = alias_.find(globals[n].engine_id);
    const common::TrackId id = alias != alias_.end() ? alias->second : globals[n].engine_id;
    if (previous_.contains(id) && !used.contains(id)) take(out.global[n], id);
  }
  // Else its engine id, or a fresh one when another track has that.
  for (std::size_t n = 0; n < globals.size(); ++n) {
    if (out.global[n] != 0) continue;
    take(out.global[n], used.contains(globals[n].engine_id) ? mint() : globals[n].engine_id);
  }
  for (std::size_t n = 0; n < globals.size(); ++n)
    if (out.global[n] != globals[n].engine_id) alias_[globals[n].engine_id] = out.global[n];
  const auto previous_owner = std::exchange(owner_, {});
  for (std::size_t n = 0; n < globals.size(); ++n)
    for (const auto source : globals[n].sources) owner_[source] = out.global[n];
  // A passed-through supernode track is reported under the id it was reported under at the previous
  // tick, else its own, else a fresh one: every track a supernode reports is in the output.
  for (const auto id : passed) {
    const auto before = previous_owner.find(id);
    common::TrackId chosen = before != previous_owner.end() && !used.contains(before->second) ? before->second : id;
    if (used.contains(chosen)) chosen = mint();
    out.passed.push_back(0);
    take(out.passed.back(), chosen);
    owner_[id] = chosen;
  }
  previous_ = std::move(used);
  return out;
}

}  // namespace wsn::aggregator
