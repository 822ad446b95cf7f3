// The window replay the GNN and sbmht engines share: an engine keeps its items (tracks, track-tree
// leaves) as they stood after the last tick that left the window (the anchor) and replays the
// window's ticks from there at every step, so a delayed observation is processed at the tick it was
// generated as if it had been on time. Handoffs are events in that timeline.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "common/messages.hpp"
#include "supernode/observation_window.hpp"

namespace wsn::supernode {

/// The part of a window replay that does not depend on what the engine keeps: which ticks a step
/// folds into the anchor and which it replays, and what the replayed ticks held.
class ReplayClock {
 public:
  /// One tick of the engine: the tick and its slot, in canonical order.
  using TickVisit = std::function<void(std::int32_t tick, std::span<const common::Observation> slot)>;
  /// The ticks one step replays: the window's oldest..newest.
  struct Ticks {
    std::int32_t oldest = 0;
    std::int32_t newest = 0;
  };

  /// The ticks `window` asks to replay; nullopt while it holds no tick yet. The first call puts the
  /// anchor just before the window.
  std::optional<Ticks> start(const ObservationWindow& window);
  /// The anchor holds the items after this tick.
  std::int32_t anchorTick() const { return anchor_tick_; }
  /// The newest tick replayed (0 before the first step).
  std::int32_t currentTick() const { return current_tick_; }
  /// Visits the ticks after the anchor up to `tick` with their final contents, those the last
  /// replay saw (a tick it did not see is empty); the anchor then stands at `tick`.
  void foldAnchorTo(std::int32_t tick, const TickVisit& visit);
  /// Visits `ticks` of `window` in order and keeps their contents for the fold that follows once
  /// they leave the window.
  void replay(const ObservationWindow& window, Ticks ticks, const TickVisit& visit);

 private:
  bool started_ = false;
  std::int32_t anchor_tick_ = 0;
  std::int32_t current_tick_ = 0;
  std::int32_t cached_oldest_tick_ = 0;
  std::vector<std::vector<common::Observation>> cached_slots_;
};

/// A window replay over the engine's items of type Item, each belonging to a track (`Item::*id`).
/// An adopted item enters every replay at its tick, replacing the items of its track; a released
/// track leaves every replay after the tick it was released at. The engine hands in, at each step,
/// its tick (on items whose state is at tick - 1) and how an adopted item catches up with an anchor
/// that already passed its tick.
template <class Item>
class WindowReplay {
 public:
  using Items = std::vector<Item>;
  /// The engine's tick on items whose state is at tick - 1.
  using ProcessTick = std::function<void(Items& items, std::int32_t tick, std::span<const common::Observation> slot)>;
  /// Brings an adopted item whose state is at first_tick - 1 up to the anchor (its state then at
  /// anchor_tick): the engine's time update, anchor_tick - first_tick + 1 times.
  using CatchUp = std::function<void(Item& item, std::int32_t first_tick, std::int32_t anchor_tick)>;
  /// The engine's order of items: an adopted item is inserted where it keeps the items sorted.
  using Order = bool (*)(const Item&, const Item&);

  WindowReplay(common::TrackId Item::*track, Order order) : track_(track), order_(order) {}

  /// `item` takes part from `tick` on, its state at tick - 1.
  void adopt(std::int32_t tick, Item item) { adoptions_.push_back(Adoption{tick, std::move(item)}); }
  /// Removes `track`'s items now, and from every replay after the current tick.
  void release(common::TrackId track) {
    releases_.push_back(Release{clock_.currentTick(), track});
    removeTrack(current_, track);
  }
  /// Folds the ticks that left `window` into the anchor, then replays the window from it.
  void step(const ObservationWindow& window, const ProcessTick& process, const CatchUp& catch_up) {
    const auto ticks = clock_.start(window);
    if (!ticks) return;
    // A handoff too old to enter at its own tick enters the anchor, brought up to it.
    for (const auto& adoption : adoptions_) {
      if (adoption.tick > clock_.anchorTick()) continue;
      Item item = adoption.item;
      catch_up(item, adoption.tick, clock_.anchorTick());
      inject(anchor_, std::move(item));
    }
    forgetEventsUpToAnchor();
    clock_.foldAnchorTo(ticks->oldest - 1, [&](std::int32_t t, std::span<const common::Observation> slot) {
      processWithEvents(anchor_, t, slot, process);
    });
    forgetEventsUpToAnchor();
    current_ = anchor_;
    clock_.replay(window, *ticks, [&](std::int32_t t, std::span<const common::Observation> slot) {
      processWithEvents(current_, t, slot, process);
    });
  }

  /// The items after the newest tick.
  const Items& current() const { return current_; }
  /// The newest tick replayed (0 before the first step).
  std::int32_t currentTick() const { return clock_.currentTick(); }

 private:
  struct Adoption {
    std::int32_t tick = 0;
    Item item;
  };
  struct Release {
    std::int32_t tick = 0;
    common::TrackId track = 0;
  };

  void removeTrack(Items& items, common::TrackId track) const {
    std::erase_if(items, [&](const Item& i) { return i.*track_ == track; });
  }
  /// Adds `item` in order, replacing what its track had (a newer handoff supersedes it).
  void inject(Items& items, Item item) const {
    removeTrack(items, item.*track_);
    const auto at = std::upper_bound(items.begin(), items.end(), item, order_);
    items.insert(at, std::move(item));
  }
  void processWithEvents(Items& items, std::int32_t tick, std::span<const common::Observation> slot,
                         const ProcessTick& process) const {
    for (const auto& adoption : adoptions_)
      if (adoption.tick == tick) inject(items, adoption.item);
    process(items, tick, slot);
    for (const auto& release : releases_)
      if (release.tick == tick) removeTrack(items, release.track);
  }
  void forgetEventsUpToAnchor() {
    const std::int32_t anchor = clock_.anchorTick();
    std::erase_if(adoptions_, [&](const Adoption& a) { return a.tick <= anchor; });
    std::erase_if(releases_, [&](const Release& r) { return r.tick <= anchor; });
  }

  common::TrackId Item::*track_;
  Order order_;
  ReplayClock clock_;
  Items anchor_;
  Items current_;
  std::vector<Adoption> adoptions_;  // not yet folded into the anchor
  std::vector<Release> releases_;    // not yet folded into the anchor
};

}  // namespace wsn::supernode
