#include "supernode/sbmht/params.hpp"

#include <algorithm>

#include "common/shared_derivations.hpp"
#include "common/track_confirmation.hpp"

namespace wsn::supernode::sbmht {
namespace {

using common::Derived;
using common::shortNumber;
using Statistics = common::ObservationStatistics;
using Resolved = std::map<std::string, common::EngineParam>;

}  // namespace

std::map<std::string, common::ParamDerivation> paramDerivations() {
  std::map<std::string, common::ParamDerivation> d;
  d["measurement_sigma"] = common::reportErrorDerivation();
  d["merge_radius"] = common::mergeRadiusDerivation();
  d["initial_velocity_sigma"] = common::newTrackVelocityDerivation();
  d["birth_density"] = common::birthDensityDerivation();
  d["detection_probability"] = {
      "the sensor model's sensing probability x the network's delivery into the window",
      [](const common::StatisticsSource& stats, const Resolved&) {
        const Statistics& s = stats();
        return Derived{s.detectionProbability(), "sensing " + shortNumber(s.sensing_probability.value) +
                                                     " x delivery " + shortNumber(s.delivery_probability.value)};
      }};
  d["false_alarm_density"] = {
      "the sensor model's false reports x the network's delivery, at least one per 100 ticks over the region",
      [](const common::StatisticsSource& stats, const Resolved&) {
        const Statistics& s = stats();
        const double floor = 1.0 / (common::kClutterFloorTicks * std::max(s.region_area, 1e-12));
        return Derived{std::max(s.falseAlarmDensity(), floor),
                       "max(" + shortNumber(s.falseAlarmDensity()) + ", 1 / (100 x area " + shortNumber(s.region_area) +
                           "))"};
      }};
  // At least 2: one target's report hides another's where they cross (one report for two
  // targets), and the miss branch must outlive that tick to bridge it. Judged at the newest tick,
  // where late reports have not arrived yet (common::liveEdgeMissDerivation).
  d["max_misses"] = common::liveEdgeMissDerivation(2, 1000);
  d["confirm_reports"] = {
      "reports that balance chains of clutter against the wait of every new target (as MCMCDA's "
      "confirm_observations)",
      [](const common::StatisticsSource& stats, const Resolved& r) {
        // The SPRT's alpha is a design value: with alpha = 1e-3 a clutter-free scenario would wait
        // for a second report though a single one is decisive there. The count is derived from
        // the same false-track economics as the other engines' confirmation.
        return common::clutterConfirmation(stats(), r, "gate_chi2", "max_misses", 10);
      }};
  d["delivery_probability"] = {"the network's delivery into the window",
                                [](const common::StatisticsSource& stats, const Resolved&) {
                                  const Statistics& s = stats();
                                  return Derived{std::clamp(s.delivery_probability.value, 0.001, 1.0),
                                                 "delivery " + shortNumber(s.delivery_probability.value)};
                                }};
  d["cv_slow_sigma"] = {"the targets' process noise q (dynamics.process_noise_sigma)",
                        [](const common::StatisticsSource& stats, const Resolved&) {
                          return Derived{stats().process_noise_sigma, "q"};
                        }};
  // docs/ONERA.md §2 proposes sigma_d = 1.0 and sigma_n = 0.1 m/s^2 beside sigma_a = 0.3: a road lets a
  // target change speed along it more freely than a quiet CV model, and hardly leave it.
  d["road_along_sigma"] = {"10/3 x the targets' process noise q (docs/ONERA.md §2: 1.0 against 0.3 m/s^2)",
                           [](const common::StatisticsSource& stats, const Resolved&) {
                             return Derived{10.0 / 3.0 * stats().process_noise_sigma, "10/3 q"};
                           }};
  d["road_across_sigma"] = {"q / 3 (docs/ONERA.md §2: 0.1 against 0.3 m/s^2)",
                            [](const common::StatisticsSource& stats, const Resolved&) {
                              return Derived{stats().process_noise_sigma / 3.0, "q / 3"};
                            }};
  d["cv_fast_sigma"] = {"5 x the targets' process noise q (docs/ONERA.md §2: 1.5 against 0.3 m/s^2)",
                        [](const common::StatisticsSource& stats, const Resolved&) {
                          return Derived{5.0 * stats().process_noise_sigma, "5 q"};
                        }};
  return d;
}

const config::FieldTable<SbmhtParams>& paramTable() {
  using config::integer;
  using config::real;
  using P = SbmhtParams;
  static const config::FieldTable<SbmhtParams> table{
      "tracker.params (sbmht)",
      {
          real<P>("detection_probability", &P::detection_probability, config::closed(0.001, 0.999), "",
                  "PD: probability that a live target's report reaches the window at a tick (detection times delivery)"),
          real<P>("false_alarm_density", &P::false_alarm_density, config::closed(1e-12, 1.0), "1/(separation² tick)",
                  "lambda_fa of eq. (17): delivered false reports per unit area per tick"),
          real<P>("birth_density", &P::birth_density, config::closed(1e-12, 1.0), "1/(separation² tick)",
                  "lambda_nt of eq. (18): new targets per unit area per tick"),
          real<P>("measurement_sigma", &P::measurement_sigma, config::closed(1e-3, 100.0), "separations",
                  "std. deviation of a position report's error per axis, R = sigma^2 I"),
          real<P>("initial_velocity_sigma", &P::initial_velocity_sigma, config::closed(1e-3, 100.0), "separations/tick",
                  "prior std. deviation of a new track's velocity per axis (the track starts at rest)"),
          real<P>("gate_chi2", &P::gate_chi2, config::closed(0.1, 1000.0), "",
                  "gate on a report's squared Mahalanobis distance under the best moving model (9.21: chi^2, 2 dof, 99%)"),
          real<P>("sprt_alpha", &P::sprt_alpha, config::closed(1e-9, 0.5), "",
                  "SPRT alpha, P(confirming a false track): confirm at L >= ln((1 - beta) / alpha)"),
          real<P>("sprt_beta", &P::sprt_beta, config::closed(1e-9, 0.5), "",
                  "SPRT beta, P(deleting a true track): delete a tentative track at L <= ln(beta / (1 - alpha))"),
          real<P>("drop_score", &P::drop_score, config::closed(0.1, 1e6), "",
                  "T_drop: a confirmed track whose score falls this far below its best is deleted"),
          integer<P>("max_misses", &P::max_misses, 1.0, 1000.0, "ticks",
                     "without a sensor list: a leaf that missed this many consecutive ticks is deleted (the stop model "
                     "makes coasting cheap, so T_drop alone keeps a vanished target's track for about 100 scans); with "
                     "one, max_coast_ticks and T_drop end leaves instead"),
          integer<P>("n_scan", &P::n_scan, 0.0, 50.0, "scans",
                     "N of N-scan pruning: a tree keeps only the branches that agree with the best hypothesis N ticks "
                     "back; leaves that took the same reports in their last N ticks are merged"),
          integer<P>("hypotheses", &P::hypotheses, 1.0, 1000.0, "",
                     "N_Hypo: global hypotheses kept per cluster (the k best), over which track posteriors are computed"),
          integer<P>("initial_score", &P::initial_score, 0.0, 1.0, "",
                     "a new track's score: 0 blackman, ln(PD lambda_nt / lambda_fa); 1 paper, eq. (18) "
                     "ln(lambda_fa / (lambda_fa + lambda_nt))"),
          real<P>("stop_sigma", &P::stop_sigma, config::closed(1e-6, 100.0), "separations",
                  "stop model: the position wanders by this std. deviation per tick"),
          real<P>("cv_slow_sigma", &P::cv_slow_sigma, config::closed(1e-3, 100.0), "separations/tick²",
                  "acceleration std. deviation of the quiet constant-velocity model"),
          real<P>("cv_fast_sigma", &P::cv_fast_sigma, config::closed(1e-3, 100.0), "separations/tick²",
                  "acceleration std. deviation of the manoeuvring constant-velocity model"),
          real<P>("stop_time_constant", &P::stop_time_constant, config::closed(1e-3, 1e6), "ticks",
                  "mean sojourn in the stop model: p_00 = exp(-delta / tau)"),
          real<P>("slow_time_constant", &P::slow_time_constant, config::closed(1e-3, 1e6), "ticks",
                  "mean sojourn in the quiet constant-velocity model"),
          real<P>("fast_time_constant", &P::fast_time_constant, config::closed(1e-3, 1e6), "ticks",
                  "mean sojourn in the manoeuvring constant-velocity model"),
          real<P>("merge_radius", &P::merge_radius, config::closed(0.0, 1e6), "separations",
                  common::kMergeRadiusMeaning),
          integer<P>("confirm_reports", &P::confirm_reports, 1.0, 1000.0, "ticks",
                     "a tentative track that took reports at this many ticks is confirmed, even before its score reaches the "
                     "SPRT's threshold: the evidence the scenario's clutter makes decisive (1 without clutter)"),
          real<P>("delivery_probability", &P::delivery_probability, config::closed(0.001, 1.0), "",
                  "where sensors are listed: the share of a sensor's reports that reach the window; a sensor's PD "
                  "at a target it covers and sees is its type's PD times this"),
          integer<P>("max_coast_ticks", &P::max_coast_ticks, 1.0, 1e6, "ticks",
                     "where sensors are listed: a leaf that no sensor could see (behind a mask, in a gap between "
                     "sensor areas) for this many ticks running is deleted; a miss costs nothing there"),
          integer<P>("bearing_pair_births", &P::bearing_pair_births, 0.0, 1.0, "",
                     "1: two bearings of one tick from two listed sensors that no track took start a tentative track "
                     "where their rays cross within both sensors' sight (the composite report of Pannetier et al. "
                     "§II-C); 0: bearings only update tracks"),
          integer<P>("use_road_network", &P::use_road_network, 0.0, 1.0, "",
                     "1: algorithm 1 of Pannetier et al., where the scenario has roads: a road-constrained model in the "
                     "IMM near a road, its estimate projected onto the road, and N-scan pruning that keeps the best "
                     "branch per road section; 0: algorithm 2, the roads unused"),
          real<P>("road_along_sigma", &P::road_along_sigma, config::closed(1e-3, 100.0), "separations/tick²",
                  "road model (eq. 6): acceleration std. deviation along the road"),
          real<P>("road_across_sigma", &P::road_across_sigma, config::closed(1e-4, 100.0), "separations/tick²",
                  "road model (eq. 6): acceleration std. deviation across the road"),
          real<P>("road_location_sigma", &P::road_location_sigma, config::closed(0.0, 1e6), "separations",
                  "how well the scenario's road centre lines are known: added across the road to a projected "
                  "estimate's position variance"),
          real<P>("road_gate_distance", &P::road_gate_distance, config::closed(0.0, 1e6), "separations",
                  "the road model is active while a track's predicted position lies this close to a road section"),
          real<P>("road_time_constant", &P::road_time_constant, config::closed(1e-3, 1e6), "ticks",
                  "mean sojourn in the road model"),
          integer<P>("road_sections_kept", &P::road_sections_kept, 1.0, 100.0, "",
                     "Nk of algorithm 1: N-scan pruning keeps, beside the branches that agree with the best "
                     "hypothesis, the best branch on each other road section, up to this many sections a tree"),
      }};
  return table;
}

SbmhtParams SbmhtParams::fromContext(const EngineContext& context) {
  return common::decodeParams(paramTable(), context.params);
}

}  // namespace wsn::supernode::sbmht
