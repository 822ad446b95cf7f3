// Plugin of the classification scores of a run (ONERA eqs. 19-23; docs/ONERA.md §4): over the
// target-track pairs of track_quality's per-tick unique assignment, the confusion matrix of true
// against declared class and the share of pairs whose track declares the right class.
#include <array>
#include <map>
#include <memory>

#include "aggregator/metric/metric.hpp"
#include "aggregator/track_quality.hpp"
#include "common/class_evidence.hpp"

namespace wsn::aggregator {
namespace {

/// What a track declares, as the confusion matrix's column: a class's name, or "none".
const std::string& declaredName(common::TargetClass declared) {
  static const std::string none = "none";
  return declared == common::TargetClass::kUnknown ? none : common::targetClassName(declared);
}

class ClassificationMetric final : public Metric {
 public:
  explicit ClassificationMetric(double gate) : gate_(gate) {}

  MetricTickValues add(const MetricTick& tick) override {
    const auto assignment = associateTargetsWithTracks(tick.truth, tick.tracks, gate_);
    for (std::size_t i = 0; i < tick.truth.size(); ++i) {
      if (assignment[i] < 0) continue;
      const common::TargetState& target = tick.truth[i];
      const auto& track = tick.tracks[static_cast<std::size_t>(assignment[i])];
      const common::TargetClass declared = common::declaredTrackClass(track.class_probabilities).target_class;
      ++confusion_[static_cast<std::size_t>(target.target_class)][static_cast<std::size_t>(declared)];
      Counts& c = targets_[target.id];
      c.truth = target.target_class;
      ++c.associated;
      if (declared == common::TargetClass::kUnknown) continue;
      ++c.declared;
      if (declared == target.target_class) ++c.correct;
    }
    return {};
  }

  MetricReport finish() const override {
    Counts known;  // over the targets whose class the scenario gives
    Json targets = Json::array();
    for (const auto& [id, c] : targets_) {
      if (c.truth != common::TargetClass::kUnknown) {
        known.associated += c.associated;
        known.declared += c.declared;
        known.correct += c.correct;
      }
      targets.push_back(Json{{"id", id},
                             {"class", common::targetClassName(c.truth)},
                             {"ticks_associated", c.associated},
                             {"ticks_declared", c.declared},
                             {"ticks_correct", c.correct},
                             {"class_accuracy", accuracy(c)}});
    }
    // Rows: every true class met; columns: every declared class and "none", zeros included, so
    // that a reader need not guess what is absent.
    Json confusion = Json::object();
    for (std::size_t t = 0; t < kNames; ++t) {
      std::int64_t row_total = 0;
      for (const auto count : confusion_[t]) row_total += count;
      if (row_total == 0) continue;
      Json row = Json::object();
      for (std::size_t d = 1; d < kNames; ++d) row[declaredName(static_cast<common::TargetClass>(d))] = confusion_[t][d];
      row["none"] = confusion_[t][0];
      confusion[common::targetClassName(static_cast<common::TargetClass>(t))] = std::move(row);
    }
    return {Json{{"gate", gate_},
                 {"ticks_associated", known.associated},
                 {"ticks_declared", known.declared},
                 {"ticks_correct", known.correct},
                 {"declared_share", known.associated > 0 ? Json(ratio(known.declared, known.associated)) : Json()},
                 {"class_accuracy", known.declared > 0 ? Json(ratio(known.correct, known.declared)) : Json()},
                 {"confusion", std::move(confusion)},
                 {"targets", std::move(targets)}}};
  }

 private:
  struct Counts {
    common::TargetClass truth = common::TargetClass::kUnknown;
    std::int64_t associated = 0;  ///< ticks associated with a track
    std::int64_t declared = 0;    ///< of those, ticks whose track declares a class
    std::int64_t correct = 0;     ///< of those, ticks it declares the true one
  };
  static constexpr std::size_t kNames = common::kClassCount + 1;  // unknown first, as TargetClass

  static double ratio(std::int64_t a, std::int64_t b) { return static_cast<double>(a) / static_cast<double>(b); }
  /// correct / declared; null where undefined (nothing declared, or no true class to compare with).
  static Json accuracy(const Counts& c) {
    if (c.declared == 0 || c.truth == common::TargetClass::kUnknown) return Json();
    return ratio(c.correct, c.declared);
  }

  double gate_;
  std::array<std::array<std::int64_t, kNames>, kNames> confusion_{};
  std::map<common::TargetId, Counts> targets_;
};

}  // namespace

MetricSpec classificationMetric() {
  return {"classification",
          "the tracks' declared classes against the targets' true ones over track_quality's unique assignment: "
          "confusion matrix, share of associated ticks with a declared class, and accuracy per target and run",
          {"quality_gate"},
          [](const common::MetricsConfig& config, const std::vector<common::Vec2>&) -> std::unique_ptr<Metric> {
            return std::make_unique<ClassificationMetric>(config.quality_gate);
          },
          {{"class_accuracy", "class accuracy", "class accuracy", "", {"classification", "class_accuracy"}, {},
            "ticks a track declares its target's true class over ticks it declares one (null: none declared)"},
           {"declared_share", "declared share", "share of associated ticks with a declared class", "",
            {"classification", "declared_share"}, {}, "ticks a track declares a class over its associated ticks"}}};
}

}  // namespace wsn::aggregator
