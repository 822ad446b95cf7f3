#include "supernode/mcmcda/start_state.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <utility>

namespace wsn::supernode::mcmcda {
namespace {

/// Element lists, one per (possibly future) track; a list of two or more is a track of the start state.
using TrackLists = std::vector<std::vector<std::int32_t>>;

/// The previous ω̂ restricted to the window, cut where a link no longer holds (the chain places what
/// is left out): one list per previous track, its anchor first. Marks each element found as
/// `claimed` and its previous track in `owner`.
TrackLists previousTracksInWindow(const WindowProblem& wp, const std::vector<LiveTrack>& tracks,
                                  std::vector<std::int32_t>& owner, std::vector<bool>& claimed) {
  const Problem& problem = wp.problem;
  const auto n = static_cast<std::size_t>(problem.size());
  // Observation key -> problem index (first unclaimed match, so duplicate reports stay distinct).
  std::vector<std::pair<ObservationKey, std::int32_t>> index_of;
  for (std::size_t i = 0; i < n; ++i)
    if (wp.anchor_of[i] < 0) index_of.emplace_back(wp.keys[i], static_cast<std::int32_t>(i));
  std::sort(index_of.begin(), index_of.end());
  const auto lookup = [&](const ObservationKey& key) -> std::int32_t {
    auto it = std::lower_bound(index_of.begin(), index_of.end(), std::make_pair(key, std::int32_t{-1}));
    for (; it != index_of.end() && it->first == key; ++it)
      if (!claimed[static_cast<std::size_t>(it->second)]) return it->second;
    return -1;
  };

  TrackLists lists(tracks.size());
  for (std::size_t k = 0; k < tracks.size(); ++k) {
    auto& list = lists[k];
    if (wp.anchor_index[k] >= 0) list.push_back(wp.anchor_index[k]);
    for (const auto& key : tracks[k].observations) {
      const std::int32_t i = lookup(key);
      // Gone from the window: an identical report arrived twice, or (merge_radius > 0) a late report
      // joined the cluster and moved its centre; the chain places what is left out.
      if (i < 0) continue;
      claimed[static_cast<std::size_t>(i)] = true;
      owner[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(k);
      if (!list.empty() && !problem.linked(list.back(), i)) continue;
      list.push_back(i);
    }
  }
  return lists;
}

/// Step 3a: new observations appended to the list that holds their group's latest member.
void joinGroups(const WindowProblem& wp, const std::vector<bool>& claimed, const GroupOf& group_of,
                TrackLists& lists) {
  const Problem& problem = wp.problem;
  // group -> the list holding its latest member so far
  std::map<std::uint64_t, std::size_t> holder;
  const auto note = [&](std::int32_t i, std::size_t k) {
    if (problem.isAnchor(i)) return;
    const std::uint64_t group = group_of(wp.keys[static_cast<std::size_t>(i)]);
    if (group != 0) holder[group] = k;
  };
  // Elements in tick order, so a group's later member finds the list its earlier one joined.
  std::vector<std::int32_t> list_of(static_cast<std::size_t>(problem.size()), -1);
  for (std::size_t k = 0; k < lists.size(); ++k)
    for (const auto i : lists[k]) list_of[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(k);
  for (std::int32_t i = 0; i < problem.size(); ++i) {
    if (problem.isAnchor(i)) continue;
    if (list_of[static_cast<std::size_t>(i)] >= 0) {
      note(i, static_cast<std::size_t>(list_of[static_cast<std::size_t>(i)]));
      continue;
    }
    if (claimed[static_cast<std::size_t>(i)]) continue;
    const std::uint64_t group = group_of(wp.keys[static_cast<std::size_t>(i)]);
    const auto it = group == 0 ? holder.end() : holder.find(group);
    if (it == holder.end()) {
      // The group's first element in the window starts a list of its own; a second member makes
      // it a track.
      lists.push_back({i});
      list_of[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(lists.size() - 1);
      if (group != 0) holder[group] = lists.size() - 1;
      continue;
    }
    auto& list = lists[it->second];
    if (!problem.linked(list.back(), i)) continue;
    list.push_back(i);
    list_of[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(it->second);
  }
}

/// Step 3b: the newest tick's observations joined greedily to lists whose last element they can
/// follow (up to d-bar ticks before: under heavy loss a target's previous report is seldom of the
/// tick before), nearest (in Mahalanobis distance over the gap) first, within the gate.
void joinNewestGreedily(const Problem& problem, const McmcdaParams& params, TrackLists& lists) {
  std::vector<bool> used(static_cast<std::size_t>(problem.size()), false);
  for (const auto& list : lists)
    if (list.size() >= 2)
      for (const auto i : list) used[static_cast<std::size_t>(i)] = true;
  struct Candidate {
    double d2;
    std::int32_t track;
    std::int32_t observation;
  };
  std::vector<Candidate> candidates;
  const double r2 = params.model.measurement_sigma * params.model.measurement_sigma;
  const std::int32_t newest_begin = problem.newestBegin();
  for (std::size_t k = 0; k < lists.size(); ++k) {
    const auto& list = lists[k];
    if (list.empty() || problem.tick(list.back()) >= problem.lastTick()) continue;
    // A lone report starts a list only as a newborn track (confirmation at one report).
    if (list.size() == 1 && !problem.isAnchor(list.front()) && params.confirm_observations > 1) continue;
    TrackState last;
    if (list.size() >= 2 || !problem.isAnchor(list.front()))
      problem.trackScore(list, &last);
    else
      last = problem.observation(list.front()).prior;
    const TrackState predicted = problem.motion().predict(last, problem.lastTick() - last.tick);
    const double S = predicted.cov.pp + r2;
    for (std::int32_t i = newest_begin; i < problem.size(); ++i) {
      if (used[static_cast<std::size_t>(i)] || !problem.linked(list.back(), i)) continue;
      const double dx = problem.observation(i).x - predicted.x;
      const double dy = problem.observation(i).y - predicted.y;
      const double d2 = (dx * dx + dy * dy) / S;
      if (d2 <= params.greedy_gate_chi2) candidates.push_back({d2, static_cast<std::int32_t>(k), i});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.d2, a.track, a.observation) < std::tie(b.d2, b.track, b.observation);
  });
  std::vector<bool> extended(lists.size(), false);
  for (const auto& c : candidates) {
    if (extended[static_cast<std::size_t>(c.track)] || used[static_cast<std::size_t>(c.observation)]) continue;
    extended[static_cast<std::size_t>(c.track)] = true;
    used[static_cast<std::size_t>(c.observation)] = true;
    lists[static_cast<std::size_t>(c.track)].push_back(c.observation);
  }
}

/// The one list of `a` and `b`'s elements in tick order, when it is a track: at most one anchor,
/// first; no two elements at one tick; every consecutive pair linked. Empty otherwise.
std::vector<std::int32_t> interleaved(const Problem& problem, const std::vector<std::int32_t>& a,
                                      const std::vector<std::int32_t>& b) {
  std::vector<std::int32_t> merged;
  merged.reserve(a.size() + b.size());
  std::merge(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(merged),
             [&](std::int32_t i, std::int32_t j) { return problem.tick(i) < problem.tick(j); });
  for (std::size_t k = 1; k < merged.size(); ++k)
    if (!problem.linked(merged[k - 1], merged[k])) return {};  // also refuses a second anchor and a shared tick
  return merged;
}

/// Step 3c: two lists that hold one target's elements in turns become one, when the one track
/// scores higher under eq. (3) than the two (a list of fewer than two elements scores 0: its
/// element is a false alarm, or its anchor's target ended). A delayed network hands a target's
/// reports over out of order: its newest reports start a track of their own while the older are on
/// their way, and a late report arrives for a tick inside a track. The chain's moves can seldom
/// repair this: merge joins one track's end to another's start, and interleaving two tracks needs a
/// death first, which the posterior all but forbids. Only lists whose spans overlap are tried
/// (the others are merge's), best gain first, each list in one merge per tick.
void mergeInterleaved(const Problem& problem, TrackLists& lists) {
  const auto score = [&](const std::vector<std::int32_t>& list) {
    return list.size() >= 2 ? problem.trackScore(list) : 0.0;
  };
  // Each list's own score, computed when a pair that holds it first passes the cheap tests.
  std::vector<std::optional<double>> scores(lists.size());
  const auto scoreOf = [&](std::size_t k) {
    if (!scores[k]) scores[k] = score(lists[k]);
    return *scores[k];
  };
  struct Candidate {
    double gain;
    std::size_t first;
    std::size_t second;
  };
  std::vector<Candidate> candidates;
  const double reach_per_tick = problem.params().max_speed;
  // Two lone observations never interleave (their spans are ticks), so every pair holds a track:
  // each track against every other list, a pair of tracks once.
  for (std::size_t i = 0; i < lists.size(); ++i) {
    if (lists[i].size() < 2) continue;
    for (std::size_t j = 0; j < lists.size(); ++j) {
      const auto& a = lists[i];
      const auto& b = lists[j];
      if (j == i || b.empty() || (b.size() >= 2 && j < i)) continue;
      const std::int32_t a_first = problem.tick(a.front()), a_last = problem.tick(a.back());
      const std::int32_t b_first = problem.tick(b.front()), b_last = problem.tick(b.back());
      if (a_last < b_first || b_last < a_first) continue;  // one after the other: the chain's merge
      // The two last elements of one track lie within reach of each other.
      const auto& ea = problem.observation(a.back());
      const auto& eb = problem.observation(b.back());
      if (!Problem::withinReach(ea.x - eb.x, ea.y - eb.y, reach_per_tick * std::abs(a_last - b_last))) continue;
      const auto merged = interleaved(problem, a, b);
      if (merged.empty()) continue;
      const double gain = score(merged) - scoreOf(i) - scoreOf(j);
      if (gain > 0.0) candidates.push_back({gain, std::min(i, j), std::max(i, j)});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(y.gain, x.first, x.second) < std::tie(x.gain, y.first, y.second);
  });
  std::vector<bool> changed(lists.size(), false);
  for (const auto& c : candidates) {
    if (changed[c.first] || changed[c.second]) continue;
    lists[c.first] = interleaved(problem, lists[c.first], lists[c.second]);
    lists[c.second].clear();
    changed[c.first] = changed[c.second] = true;
  }
}

/// Which previous track each track of ω̂ continues, and the reverse; -1 for none.
struct Continuation {
  std::vector<std::int32_t> previous_of;   ///< track of ω̂ -> previous track
  std::vector<std::int32_t> successor_of;  ///< previous track -> track of ω̂
};

/// A track that starts at an anchor is that anchor's track. Any other keeps the id of the previous
/// track it shares most observations with (each id once, ties to the smaller id); the rest are new.
Continuation continuations(const WindowProblem& wp, const Partition& best, std::span<const std::int32_t> owner,
                           const std::vector<LiveTrack>& previous) {
  Continuation c{std::vector<std::int32_t>(best.size(), -1), std::vector<std::int32_t>(previous.size(), -1)};
  const auto link = [&](std::size_t n, std::int32_t k) {
    c.previous_of[n] = k;
    c.successor_of[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(n);
  };
  for (std::size_t n = 0; n < best.size(); ++n) {
    const std::int32_t k = wp.anchor_of[static_cast<std::size_t>(best[n].front())];
    if (k >= 0) link(n, k);
  }
  struct Overlap {
    std::int32_t shared;
    std::int32_t track;  // new
    std::int32_t previous;
  };
  std::vector<Overlap> overlaps;
  for (std::size_t n = 0; n < best.size(); ++n) {
    if (c.previous_of[n] >= 0) continue;
    std::map<std::int32_t, std::int32_t> shared;
    for (const auto i : best[n])
      if (owner[static_cast<std::size_t>(i)] >= 0) ++shared[owner[static_cast<std::size_t>(i)]];
    for (const auto& [k, count] : shared) overlaps.push_back({count, static_cast<std::int32_t>(n), k});
  }
  std::sort(overlaps.begin(), overlaps.end(), [&](const Overlap& a, const Overlap& b) {
    if (a.shared != b.shared) return a.shared > b.shared;
    const auto ida = previous[static_cast<std::size_t>(a.previous)].id;
    const auto idb = previous[static_cast<std::size_t>(b.previous)].id;
    return std::tie(ida, a.track) < std::tie(idb, b.track);
  });
  for (const auto& o : overlaps)
    if (c.previous_of[static_cast<std::size_t>(o.track)] < 0 &&
        c.successor_of[static_cast<std::size_t>(o.previous)] < 0)
      link(static_cast<std::size_t>(o.track), o.previous);
  return c;
}

/// Ids for tracks that continue no previous track, never one still in use.
class TrackNamer {
 public:
  /// `in_use`: the ids that stay whatever the new tracks are called.
  TrackNamer(const WindowProblem& wp, const NewTrackIds& ids, std::set<common::TrackId> in_use)
      : wp_(wp), ids_(ids), in_use_(std::move(in_use)) {}

  common::TrackId name(std::span<const std::int32_t> elements) {
    common::TrackId proposed = 0;
    if (ids_.propose) {
      std::vector<ObservationKey> keys;
      for (const auto i : elements) keys.push_back(wp_.keys[static_cast<std::size_t>(i)]);
      proposed = ids_.propose(keys);
    }
    const common::TrackId id = proposed != 0 && !in_use_.contains(proposed) ? proposed : ids_.mint();
    in_use_.insert(id);
    return id;
  }

 private:
  const WindowProblem& wp_;
  const NewTrackIds& ids_;
  std::set<common::TrackId> in_use_;
};

/// Confirmation at one report means a report is decisive: nothing but a target could have made it
/// (lambda_f ~ 0), so a report that ω̂ leaves out of every track is a target of its own, a track of
/// one report. A report of the newest tick is such a target born now, reported at once; a previous
/// one-report track whose report ω̂ still leaves out goes on under its id (its report, once it
/// leaves the window, becomes its anchor like any track's), and its next report makes it a track of
/// ω̂, which keeps its id by the overlap of continuations(). How long one is reported without a
/// further report is the engine's coasting rule, as for any track.
void addNewborns(const WindowProblem& wp, const Partition& best, std::span<const std::int32_t> owner,
                 std::vector<LiveTrack>& previous, TrackNamer& namer, std::vector<LiveTrack>& next) {
  const Problem& problem = wp.problem;
  std::vector<bool> in_track(static_cast<std::size_t>(problem.size()), false);
  for (const auto& track : best)
    for (const auto i : track) in_track[static_cast<std::size_t>(i)] = true;
  std::vector<TrackState> states;
  for (std::int32_t i = 0; i < problem.size(); ++i) {
    if (in_track[static_cast<std::size_t>(i)] || problem.isAnchor(i)) continue;
    const std::int32_t k = owner[static_cast<std::size_t>(i)];
    if (k >= 0 && previous[static_cast<std::size_t>(k)].isOneReport()) {
      next.push_back(std::move(previous[static_cast<std::size_t>(k)]));
      continue;
    }
    if (k >= 0 || i < problem.newestBegin()) continue;
    const std::int32_t lone[] = {i};
    LiveTrack track;
    track.id = namer.name(lone);
    problem.filterTrack(lone, states);
    track.observations.push_back(wp.keys[static_cast<std::size_t>(i)]);
    track.states.push_back(states.front());
    next.push_back(std::move(track));
  }
}

}  // namespace

StartState startState(const WindowProblem& wp, const std::vector<LiveTrack>& tracks, const GroupOf& group_of,
                      const McmcdaParams& params) {
  const auto n = static_cast<std::size_t>(wp.problem.size());
  StartState start;
  start.owner.assign(n, -1);
  std::vector<bool> claimed(n, false);
  TrackLists lists = previousTracksInWindow(wp, tracks, start.owner, claimed);
  // New observations of a known group follow the track that holds their group's latest member.
  if (group_of) joinGroups(wp, claimed, group_of, lists);
  joinNewestGreedily(wp.problem, params, lists);
  // Every element no list holds (a late report, one cut out above) is a list of its own, which
  // mergeInterleaved may place inside a track.
  std::vector<bool> in_list(n, false);
  for (const auto& list : lists)
    for (const auto i : list) in_list[static_cast<std::size_t>(i)] = true;
  for (std::int32_t i = 0; i < wp.problem.size(); ++i)
    if (!in_list[static_cast<std::size_t>(i)] && !wp.problem.isAnchor(i)) lists.push_back({i});
  mergeInterleaved(wp.problem, lists);
  for (auto& list : lists)
    if (list.size() >= 2) start.partition.push_back(std::move(list));
  return start;
}

std::vector<LiveTrack> adoptBest(std::vector<LiveTrack> previous, const WindowProblem& wp, const Partition& best,
                                 std::span<const std::int32_t> owner, const NewTrackIds& ids,
                                 const McmcdaParams& params, std::int32_t next_oldest) {
  const Problem& problem = wp.problem;
  const Continuation continued = continuations(wp, best, owner, previous);
  // Ids that stay in use whatever the new tracks are called: continued tracks and the anchored
  // tracks kept below for a late continuation.
  std::set<common::TrackId> in_use;
  for (std::size_t k = 0; k < previous.size(); ++k)
    if (continued.successor_of[k] >= 0 || previous[k].anchor || previous[k].isOneReport())
      in_use.insert(previous[k].id);
  TrackNamer namer(wp, ids, std::move(in_use));

  // The new track set: ω̂'s tracks, plus the previous anchored tracks nobody continued that a later
  // (or late) observation can still continue.
  std::vector<LiveTrack> next;
  std::vector<TrackState> states;
  for (std::size_t n = 0; n < best.size(); ++n) {
    LiveTrack track;
    const std::int32_t k = continued.previous_of[n];
    if (k >= 0) {
      const LiveTrack& before = previous[static_cast<std::size_t>(k)];
      track.id = before.id;
      track.past_observations = before.past_observations;
    } else {
      track.id = namer.name(best[n]);
    }
    problem.filterTrack(best[n], states);
    std::size_t from = 0;
    if (problem.isAnchor(best[n].front())) {
      track.anchor = problem.observation(best[n].front());
      from = 1;
    }
    for (std::size_t m = from; m < best[n].size(); ++m) {
      track.observations.push_back(wp.keys[static_cast<std::size_t>(best[n][m])]);
      track.states.push_back(states[m]);
    }
    next.push_back(std::move(track));
  }
  if (params.confirm_observations <= 1) addNewborns(wp, best, owner, previous, namer, next);
  for (std::size_t k = 0; k < previous.size(); ++k) {
    auto& track = previous[k];
    if (continued.successor_of[k] >= 0 || !track.anchor) continue;
    track.observations.clear();  // whatever it had in the window now belongs elsewhere or is clutter
    track.states.clear();
    if (track.canContinue(next_oldest, params.model.max_gap)) next.push_back(std::move(track));
  }
  std::sort(next.begin(), next.end(), [](const LiveTrack& a, const LiveTrack& b) { return a.id < b.id; });
  return next;
}

}  // namespace wsn::supernode::mcmcda
