// A leaf of an sbmht track tree (one track hypothesis) and the encoding of the reports it took, tick
// by tick: what the engine's scans, births and hypothesis management all work on.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/class_evidence.hpp"
#include "common/track_id.hpp"
#include "supernode/sbmht/imm.hpp"
#include "supernode/sbmht/track_score.hpp"

namespace wsn::supernode::sbmht {

/// Ends a tick's entries in Leaf::history.
inline constexpr std::int32_t kTickEnd = -1;

/// A track hypothesis: one leaf of a track tree.
struct Leaf {
  common::TrackId tree = 0;        ///< the tree's id, the track id it reports under
  std::int32_t first_tick = 0;     ///< the tick history starts at
  /// Tick by tick since first_tick: the indices (into that tick's slot, canonical order) of the
  /// reports it took, then kTickEnd; a tick it missed is kTickEnd alone. While a tick's scans
  /// run, its entries are open (no kTickEnd yet). Two leaves of one tree differ only in their
  /// last n_scan ticks (N-scan pruning).
  std::vector<std::int32_t> history;
  ImmState imm;
  TrackScore score;
  std::int32_t last_seen_tick = 0;
  std::int32_t hits = 0;           ///< ticks at which it took a report
  std::int32_t misses = 0;         ///< consecutive ticks without a report
  std::int32_t unseen_ticks = 0;   ///< consecutive ticks without a report that no sensor could see it
  bool perceivable = false;        ///< some sensor could have seen it at the current tick
  bool born_this_tick = false;     ///< its tree started in a scan of the current tick
  double probability = 1.0;        ///< P(T) over the cluster's k best hypotheses
  /// beta of eqs. 19-20 over common::kClassCount classes: eq. 20 from its first report's class
  /// likelihoods (uniform without them), then eq. 19 at every report that carries them.
  /// Of fixed capacity, so that copying a leaf at every branch allocates nothing for it.
  ClassVector classes = common::uniformClassVector();
  bool best = false;               ///< in the best global hypothesis
  /// Algorithm 1: the road section (index into common::Terrain::sections()) its road model
  /// follows this tick, or -1 when no section is within road_gate_distance (the model is off).
  std::int32_t road_section = -1;

  /// The reports it took at `tick` (empty: a miss, or a tick outside its history).
  std::span<const std::int32_t> reportsAt(std::int32_t tick) const;
};

/// a < b lexicographically, as std::vector's operator<: the history order of leafOrder. Faster on
/// the long common prefix two leaves of one tree share.
bool historyLess(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b);
/// The order the engine keeps its leaves in: by tree, then history.
bool leafOrder(const Leaf& a, const Leaf& b);
/// The history up to and including `tick`'s kTickEnd (the whole history when it ends sooner).
std::span<const std::int32_t> historyThrough(const Leaf& leaf, std::int32_t tick);
/// Keeps the leaves whose flag is set, in order.
void keepMarked(std::vector<Leaf>& leaves, const std::vector<char>& keep);
/// The leaves of tree `tree` in `leaves`, which are in leafOrder.
std::span<const Leaf> leavesOfTree(std::span<const Leaf> leaves, common::TrackId tree);
/// Of one tree's leaves, the one that speaks for it: its leaf in the best hypothesis, else the most
/// probable (ties: the best scoring, then the first); null when there is none.
const Leaf* representative(std::span<const Leaf> tree);
/// Confirms a tentative leaf that took reports at confirm_reports ticks (the SPRT may confirm it sooner).
void confirmByCount(Leaf& leaf, std::int32_t confirm_reports);

}  // namespace wsn::supernode::sbmht
