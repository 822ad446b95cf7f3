#include "supernode/sbmht/hypotheses.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

namespace wsn::supernode::sbmht {
namespace {

/// Leaves with a posterior below this are pruned (docs/ONERA.md §3, B&P ch. 16).
constexpr double kMinTrackProbability = 1e-3;
/// Nodes the k-best search of one cluster may visit; beyond it the k best found so far are used
/// (counted by weighHypotheses).
constexpr std::uint64_t kSearchBudget = 200000;

/// The k best global hypotheses of one cluster: one leaf or none per tree, no report used twice,
/// the largest sums of leaf scores. Exact depth-first branch and bound (the bound: every later tree
/// adds at most its best positive score), within kSearchBudget nodes.
class HypothesisSearch {
 public:
  struct Hypothesis {
    double score = 0.0;
    std::vector<int> chosen;  ///< per tree: the cluster leaf, or -1 (the tree is absent)
  };

  HypothesisSearch(const std::vector<std::vector<int>>& options, const std::vector<double>& scores,
                   const std::vector<std::vector<int>>& reports, std::size_t report_count, std::size_t k)
      : options_(options), scores_(scores), reports_(reports), used_(report_count, 0), k_(k) {
    bound_.assign(options_.size() + 1, 0.0);
    for (std::size_t t = options_.size(); t-- > 0;) {
      double best = 0.0;
      for (int leaf : options_[t]) best = std::max(best, scores_[static_cast<std::size_t>(leaf)]);
      bound_[t] = bound_[t + 1] + best;
    }
    chosen_.assign(options_.size(), -1);
  }

  void run() { search(0, 0.0); }
  const std::vector<Hypothesis>& results() const { return results_; }
  bool truncated() const { return truncated_; }

 private:
  void search(std::size_t t, double score) {
    if (++nodes_ > kSearchBudget) {
      truncated_ = true;
      return;
    }
    if (results_.size() == k_ && score + bound_[t] <= results_.back().score) return;
    if (t == options_.size()) {
      // Insert after equal scores: the first found (better-ordered options) ranks first.
      const auto at = std::upper_bound(results_.begin(), results_.end(), score,
                                       [](double s, const Hypothesis& h) { return s > h.score; });
      results_.insert(at, Hypothesis{score, chosen_});
      if (results_.size() > k_) results_.pop_back();
      return;
    }
    // Options in order of score (sorted by the caller), the tree's absence where 0 falls.
    bool absent_tried = false;
    for (int leaf : options_[t]) {
      const double s = scores_[static_cast<std::size_t>(leaf)];
      if (!absent_tried && s <= 0.0) {
        absent_tried = true;
        chosen_[t] = -1;
        search(t + 1, score);
      }
      const auto& used = reports_[static_cast<std::size_t>(leaf)];
      if (std::any_of(used.begin(), used.end(), [&](int r) { return used_[static_cast<std::size_t>(r)] != 0; }))
        continue;
      for (int r : used) used_[static_cast<std::size_t>(r)] = 1;
      chosen_[t] = leaf;
      search(t + 1, score + s);
      for (int r : used) used_[static_cast<std::size_t>(r)] = 0;
    }
    if (!absent_tried) {
      chosen_[t] = -1;
      search(t + 1, score);
    }
    chosen_[t] = -1;
  }

  const std::vector<std::vector<int>>& options_;
  const std::vector<double>& scores_;
  const std::vector<std::vector<int>>& reports_;
  std::vector<char> used_;
  std::size_t k_;
  std::vector<double> bound_;
  std::vector<int> chosen_;
  std::vector<Hypothesis> results_;
  std::uint64_t nodes_ = 0;
  bool truncated_ = false;
};

std::size_t findRoot(std::vector<std::size_t>& parent, std::size_t k) {
  while (parent[k] != k) k = parent[k] = parent[parent[k]];
  return k;
}

void unite(std::vector<std::size_t>& parent, std::size_t a, std::size_t b) {
  a = findRoot(parent, a);
  b = findRoot(parent, b);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

constexpr int kNone = -1;

/// Each report (tick, index) any leaf took, with the first leaf that took it, in a table per tick
/// rather than a sort of every entry, which cost more than the rest of the engine.
class TakenReports {
 public:
  struct Entry {
    int first_leaf = kNone;
    bool shared = false;  ///< by leaves of two trees
    int id = kNone;       ///< compact id, set when shared
  };

  explicit TakenReports(const std::vector<Leaf>& leaves) : leaves_(leaves), first_tick_(leaves.front().first_tick) {
    for (const auto& leaf : leaves) first_tick_ = std::min(first_tick_, leaf.first_tick);
  }

  /// Calls visit(entry) for each report leaf k took, in the order of its history.
  template <class Visit>
  void forEachReportOf(std::size_t k, Visit&& visit) {
    std::int32_t t = leaves_[k].first_tick;
    for (const std::int32_t e : leaves_[k].history) {
      if (e == kTickEnd) {
        ++t;
        continue;
      }
      const auto row = static_cast<std::size_t>(t - first_tick_);
      if (row >= rows_.size()) rows_.resize(row + 1);
      if (static_cast<std::size_t>(e) >= rows_[row].size()) rows_[row].resize(static_cast<std::size_t>(e) + 1);
      visit(rows_[row][static_cast<std::size_t>(e)]);
    }
  }

 private:
  const std::vector<Leaf>& leaves_;
  std::int32_t first_tick_;
  std::vector<std::vector<Entry>> rows_;  // by tick - first_tick_, then report index
};

/// The clusters of leaves that exclude one another, and the reports by which leaves of two trees
/// conflict in the search.
struct Conflicts {
  std::vector<std::vector<std::size_t>> clusters;  ///< leaf indices in order, by cluster root (many empty)
  std::vector<std::vector<int>> shared_reports;    ///< per leaf: its reports another tree took too, as compact ids
  std::size_t shared_report_count = 0;
};

/// A tree's leaves exclude one another, and so do leaves that share a report. Only a report taken by
/// leaves of two trees can conflict in the search (one tree contributes one leaf), so only those get
/// a compact id; the search depends on which reports conflict, not on their ids.
Conflicts findConflicts(const std::vector<Leaf>& leaves) {
  const std::size_t count = leaves.size();
  std::vector<std::size_t> parent(count);
  for (std::size_t k = 0; k < count; ++k) parent[k] = k;
  for (std::size_t k = 1; k < count; ++k)
    if (leaves[k].tree == leaves[k - 1].tree) unite(parent, k, k - 1);
  TakenReports taken(leaves);
  for (std::size_t k = 0; k < count; ++k)
    taken.forEachReportOf(k, [&](TakenReports::Entry& report) {
      if (report.first_leaf == kNone) {
        report.first_leaf = static_cast<int>(k);
        return;
      }
      unite(parent, static_cast<std::size_t>(report.first_leaf), k);
      if (leaves[static_cast<std::size_t>(report.first_leaf)].tree != leaves[k].tree) report.shared = true;
    });
  Conflicts conflicts;
  conflicts.shared_reports.resize(count);
  int shared_count = 0;
  for (std::size_t k = 0; k < count; ++k)
    taken.forEachReportOf(k, [&](TakenReports::Entry& report) {
      if (!report.shared) return;
      if (report.id == kNone) report.id = shared_count++;
      conflicts.shared_reports[k].push_back(report.id);
    });
  conflicts.shared_report_count = static_cast<std::size_t>(shared_count);
  conflicts.clusters.resize(count);
  for (std::size_t k = 0; k < count; ++k) conflicts.clusters[findRoot(parent, k)].push_back(k);
  return conflicts;
}

/// The k best hypotheses of one cluster: P(T) = sum over those containing T of e^{L_H}, normalised,
/// and the best one's leaves marked. True when the search was truncated.
bool weighCluster(std::vector<Leaf>& leaves, const std::vector<std::size_t>& members, const std::vector<double>& scores,
                  const Conflicts& conflicts, std::size_t k) {
  // Trees in order, each tree's leaves by score (ties: leaf order): the search tries good options first.
  std::vector<std::vector<int>> options;
  for (std::size_t m = 0; m < members.size(); ++m) {
    if (m == 0 || leaves[members[m]].tree != leaves[members[m - 1]].tree) options.emplace_back();
    options.back().push_back(static_cast<int>(members[m]));
  }
  for (auto& tree : options)
    std::stable_sort(tree.begin(), tree.end(), [&](int a, int b) {
      return scores[static_cast<std::size_t>(a)] > scores[static_cast<std::size_t>(b)];
    });
  HypothesisSearch search(options, scores, conflicts.shared_reports, conflicts.shared_report_count, k);
  search.run();
  const auto& found = search.results();
  if (found.empty()) return search.truncated();
  double total = 0.0;
  for (const auto& h : found) total += std::exp(h.score - found.front().score);
  for (const auto& h : found) {
    const double weight = std::exp(h.score - found.front().score) / total;
    for (int leaf : h.chosen)
      if (leaf >= 0) leaves[static_cast<std::size_t>(leaf)].probability += weight;
  }
  for (int leaf : found.front().chosen)
    if (leaf >= 0) leaves[static_cast<std::size_t>(leaf)].best = true;
  return search.truncated();
}

/// Algorithm 1's N-scan rule for the tree in leaves[begin, end): of the branches `keep` drops, keeps
/// the best-scoring one on each road section no kept branch is on, up to road_sections_kept.
void keepOtherSections(const std::vector<Leaf>& leaves, std::size_t begin, std::size_t end,
                       std::int32_t road_sections_kept, std::vector<char>& keep) {
  std::vector<std::int32_t> sections;  // the sections the tree keeps a branch on
  for (std::size_t k = begin; k < end; ++k)
    if (keep[k] && leaves[k].road_section >= 0) sections.push_back(leaves[k].road_section);
  std::vector<std::size_t> others;
  for (std::size_t k = begin; k < end; ++k)
    if (!keep[k] && leaves[k].road_section >= 0) others.push_back(k);
  std::stable_sort(others.begin(), others.end(), [&](std::size_t a, std::size_t b) {
    return leaves[a].score.score > leaves[b].score.score;
  });
  // The agreeing branches count as the sections they are on, and as one when they are off road.
  std::sort(sections.begin(), sections.end());
  sections.erase(std::unique(sections.begin(), sections.end()), sections.end());
  std::size_t kept = std::max<std::size_t>(1, sections.size());
  for (const std::size_t k : others) {
    if (kept >= static_cast<std::size_t>(road_sections_kept)) break;
    if (std::find(sections.begin(), sections.end(), leaves[k].road_section) != sections.end()) continue;
    keep[k] = 1;
    sections.push_back(leaves[k].road_section);
    ++kept;
  }
}

/// Where the last n ticks of a closed history start, or nullopt when it holds fewer ticks.
std::optional<std::size_t> lastTicksStart(const std::vector<std::int32_t>& history, std::size_t n) {
  std::size_t ends = 0;
  for (std::size_t k = history.size(); k-- > 0;) {
    if (history[k] != kTickEnd) continue;
    if (ends == n) return k + 1;
    ++ends;
  }
  if (ends == n) return 0;
  return std::nullopt;
}

}  // namespace

std::uint64_t weighHypotheses(std::vector<Leaf>& leaves, std::size_t k) {
  const std::size_t count = leaves.size();
  if (count == 0) return 0;
  const Conflicts conflicts = findConflicts(leaves);
  std::vector<double> scores(count);
  for (std::size_t l = 0; l < count; ++l) {
    scores[l] = leaves[l].score.score;
    leaves[l].probability = 0.0;
    leaves[l].best = false;
  }
  std::uint64_t truncated = 0;
  for (const auto& members : conflicts.clusters)
    if (!members.empty() && weighCluster(leaves, members, scores, conflicts, k)) ++truncated;
  return truncated;
}

void pruneUnlikelyLeaves(std::vector<Leaf>& leaves) {
  std::erase_if(leaves, [](const Leaf& l) { return !l.best && l.probability < kMinTrackProbability; });
}

// A tree keeps the branches that agree, through the tick N scans back, with its leaf in the best
// hypothesis (or its most probable leaf when it has none). Algorithm 1 also keeps, of the branches
// that do not, the best-scoring one on each other road section, up to road_sections_kept sections a
// tree (Pannetier et al., Fig. 2 step 5): branches that took different reports near a junction and so
// follow different roads both stay until the reports decide (C7). A leaf is not split per road: its
// road model follows the section nearest its prediction.
void pruneNScan(std::vector<Leaf>& leaves, std::int32_t tick, const NScanRule& rule) {
  std::vector<char> keep(leaves.size(), 1);
  for (std::size_t begin = 0; begin < leaves.size();) {
    std::size_t end = begin;
    while (end < leaves.size() && leaves[end].tree == leaves[begin].tree) ++end;
    const Leaf& ref = *representative(std::span<const Leaf>(leaves).subspan(begin, end - begin));
    const std::int32_t back = tick - rule.n_scan;
    if (back >= ref.first_tick) {
      const auto agreed = historyThrough(ref, back);
      for (std::size_t k = begin; k < end; ++k) {
        const auto here = historyThrough(leaves[k], back);
        keep[k] = std::equal(here.begin(), here.end(), agreed.begin(), agreed.end());
      }
      if (rule.roads) keepOtherSections(leaves, begin, end, rule.road_sections_kept, keep);
    }
    begin = end;
  }
  keepMarked(leaves, keep);
}

void mergeDuplicates(std::vector<Leaf>& leaves, std::int32_t n_scan) {
  const auto n = static_cast<std::size_t>(n_scan);
  if (n < 1) return;
  struct Candidate {
    std::size_t leaf;
    std::size_t tail;  // where its last n ticks start in its history
  };
  std::vector<Candidate> candidates;
  const auto tail = [&](const Candidate& c) { return std::span(leaves[c.leaf].history).subspan(c.tail); };
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    const auto start = lastTicksStart(leaves[k].history, n);
    if (!start) continue;
    // Only leaves that took a report at each of those ticks: no tick entry is kTickEnd alone.
    const auto last = std::span(leaves[k].history).subspan(*start);
    bool every_tick = true;
    for (std::size_t e = 0; e < last.size() && every_tick; ++e)
      every_tick = last[e] != kTickEnd || (e > 0 && last[e - 1] != kTickEnd);
    if (every_tick) candidates.push_back({k, *start});
  }
  std::sort(candidates.begin(), candidates.end(), [&](const Candidate& a, const Candidate& b) {
    const auto ta = tail(a);
    const auto tb = tail(b);
    if (!std::equal(ta.begin(), ta.end(), tb.begin(), tb.end()))
      return std::lexicographical_compare(ta.begin(), ta.end(), tb.begin(), tb.end());
    if (leaves[a.leaf].score.score != leaves[b.leaf].score.score)
      return leaves[a.leaf].score.score > leaves[b.leaf].score.score;
    return leafOrder(leaves[a.leaf], leaves[b.leaf]);
  });
  std::vector<char> keep(leaves.size(), 1);
  for (std::size_t c = 1; c < candidates.size(); ++c) {
    const auto prev = tail(candidates[c - 1]);
    const auto here = tail(candidates[c]);
    if (std::equal(prev.begin(), prev.end(), here.begin(), here.end())) keep[candidates[c].leaf] = 0;
  }
  keepMarked(leaves, keep);
}

}  // namespace wsn::supernode::sbmht
