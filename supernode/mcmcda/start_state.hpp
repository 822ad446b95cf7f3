// How the chain's state carries over from one tick to the next (Oh et al. §VI): the start state
// ω_init built from the previous tracks, and after the chain the new track set read from its best
// partition ω̂, each track under the id of the track it continues.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "common/track_id.hpp"
#include "supernode/mcmcda/live_track.hpp"
#include "supernode/mcmcda/mcmcda_params.hpp"
#include "supernode/mcmcda/sampler.hpp"

namespace wsn::supernode::mcmcda {

/// Names a group of observations known to belong together (the aggregator: elements of one
/// supernode track); 0 means none.
using GroupOf = std::function<std::uint64_t(const ObservationKey& observation)>;

/// Chooses the id of a track that continues no previous track, from its observations in the
/// window; 0 (or an id in use) means "mint one".
using IdProposer = std::function<common::TrackId(const std::vector<ObservationKey>& observations)>;

/// Where the ids of tracks that continue no previous track come from.
struct NewTrackIds {
  IdProposer propose;                      ///< empty: every id is minted
  std::function<common::TrackId()> mint;  ///< a fresh id of the engine's id space
};

/// The chain's start state and, per problem element, the previous track that held it.
struct StartState {
  Partition partition;
  std::vector<std::int32_t> owner;  ///< per element of the problem: index into the previous tracks, or -1
};

/// Step 3: the previous tracks' ω̂ restricted to the window, cut where a link no longer holds; new
/// observations appended to the track of their group's latest member (when `group_of` is set: ω_init
/// "from the tracks themselves"); the newest tick's observations joined greedily, nearest first, to
/// tracks whose last element they can follow; then two tracks (or a track and a lone observation) whose
/// ticks interleave joined into one where eq. (3) prefers it, best gain first. `tracks` are the
/// tracks `wp` was built from.
StartState startState(const WindowProblem& wp, const std::vector<LiveTrack>& tracks, const GroupOf& group_of,
                      const McmcdaParams& params);

/// Step 5: the track set after the chain, sorted by id. A track of ω̂ that starts at an anchor is
/// that anchor's track; any other keeps the id of the previous track it shares most observations
/// with (`owner`, from startState), or gets a new one from `ids`. With confirmation at one report, a
/// report of the newest tick left out of every track is a newborn track of its own, and a previous
/// one-report track whose report is still left out goes on. Previous anchored tracks nobody
/// continued stay while a report in a window starting at `next_oldest` could still continue them.
std::vector<LiveTrack> adoptBest(std::vector<LiveTrack> previous, const WindowProblem& wp, const Partition& best,
                                 std::span<const std::int32_t> owner, const NewTrackIds& ids,
                                 const McmcdaParams& params, std::int32_t next_oldest);

}  // namespace wsn::supernode::mcmcda
