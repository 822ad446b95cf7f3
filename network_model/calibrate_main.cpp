// wsntrack-network-calibrate: sweeps the communication range over the geometry of Oh et al. §VII
// and prints the expected loss and delay ratios (§V, eq. 7), the range that best matches the
// §VII-E counts, and the Fig. 6 curves. See docs/NETWORK.md for the recorded results.
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <limits>
#include <string>

#include <boost/program_options.hpp>

#include "network_model/calibration.hpp"
#include "network_model/link_model.hpp"
#include "network_model/topology.hpp"

namespace po = boost::program_options;
namespace nm = wsn::network_model;

namespace {

struct Options {
  double range_min = 1.0;
  double range_max = 40.0;
  double step = 0.1;
  double pte = 0.3;
  double pde = 0.3;
  std::int32_t window_size = 10;
  nm::SupernodePlacement placement = nm::SupernodePlacement::kQuadrants;
  bool fig6 = false;
  double range = std::numeric_limits<double>::quiet_NaN();  // Fig. 6 range; NaN: best of the sweep
};

nm::Topology topologyFor(const Options& options, double range) {
  return nm::ohCalibrationTopology(range, options.placement);
}

/// Prints the sweep table and returns the range with the smallest paper mismatch (the lowest
/// such range on ties).
double sweep(const Options& options) {
  std::printf("Sweep: pte = %.2f, pde = %.2f, ws = %d, supernodes = %s\n", options.pte, options.pde,
              options.window_size, options.placement == nm::SupernodePlacement::kQuadrants ? "quadrants" : "centre");
  std::printf("Target (Oh §VII-E): lost/total = 319/1174 = %.4f, delayed/received = 449/855 = %.4f\n\n",
              nm::kPaperLost / nm::kPaperReports, nm::kPaperDelayed / nm::kPaperReceived);
  std::printf("| range | mean hops | max hops | unreachable | lost/total | delayed/received | delayed/total |     chi2 |\n");
  std::printf("|------:|----------:|---------:|------------:|-----------:|-----------------:|--------------:|---------:|\n");
  double best_range = options.range_min;
  double best_mismatch = std::numeric_limits<double>::infinity();
  const auto steps = static_cast<long>(std::floor((options.range_max - options.range_min) / options.step + 1e-9));
  for (long i = 0; i <= steps; ++i) {
    const double range = options.range_min + static_cast<double>(i) * options.step;
    const nm::Topology topology = topologyFor(options, range);
    const nm::ExpectedRatios ratios = nm::expectedRatios(topology, options.pte, options.pde, options.window_size);
    const double mismatch = nm::paperMismatch(ratios);
    std::printf("| %5.2f | %9.3f | %8d | %11zu | %10.4f | %16.4f | %13.4f | %8.2f |\n", range, topology.meanHops(),
                topology.maxHops(), topology.unreachableCount(), ratios.lost_to_total, ratios.delayed_to_received,
                ratios.delayed_to_total, mismatch);
    if (mismatch < best_mismatch) {
      best_mismatch = mismatch;
      best_range = range;
    }
  }
  const nm::Topology best = topologyFor(options, best_range);
  std::printf("\nBest range (min chi2 of lost/total and delayed/received against the paper counts): %.2f\n",
              best_range);
  std::printf("  mean hops %.3f, max hops %d, chi2 %.3f\n", best.meanHops(), best.maxHops(), best_mismatch);
  std::printf("  hop histogram:");
  for (std::size_t k = 1; k < best.hopHistogram().size(); ++k)
    std::printf(" k=%zu:%zu", k, best.hopHistogram()[k]);
  std::printf("\n");
  return best_range;
}

void fig6(const Options& options, double range) {
  const nm::Topology topology = topologyFor(options, range);
  std::printf("\nFig. 6 series at range %.2f (%s; mean hops %.3f, max hops %d)\n", range,
              options.placement == nm::SupernodePlacement::kQuadrants ? "quadrants" : "centre", topology.meanHops(),
              topology.maxHops());
  std::printf("\nLeft: lost/total vs pte (E[1 - pts])\n\n| pte | lost/total |\n|----:|-----------:|\n");
  for (int i = 0; i <= 20; ++i) {
    const double pte = 0.05 * i;
    std::printf("| %.2f | %.4f |\n", pte, nm::expectedRatios(topology, pte, 0.0, options.window_size).lost_to_total);
  }
  std::printf("\nRight: delayed/total vs pde, no transmission failures (pte = 0) as in Oh §VII-D\n\n");
  std::printf("| pde | delayed/total | delayed within ws/total |\n|----:|--------------:|------------------------:|\n");
  for (int i = 0; i <= 20; ++i) {
    const double pde = 0.05 * i;
    const auto ratios = nm::expectedRatios(topology, 0.0, pde, options.window_size);
    std::printf("| %.2f | %.4f | %.4f |\n", pde, ratios.delayed_to_total, ratios.delayed_in_window_to_total);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  std::string placement = "quadrants";
  po::options_description description(
      "wsntrack-network-calibrate: expected loss and delay ratios of the network model (Oh et al. §V)\n"
      "over the communication range, on the 100 x 100 grid (spacing 1) of Oh §VII.\n"
      "Every sensor is weighted equally; unreachable sensors count as lost.\n\nOptions");
  description.add_options()
      ("help,h", "show this help")
      ("range-min", po::value(&options.range_min)->default_value(options.range_min), "smallest communication range")
      ("range-max", po::value(&options.range_max)->default_value(options.range_max), "largest communication range")
      ("step", po::value(&options.step)->default_value(options.step), "range step (> 0)")
      ("pte", po::value(&options.pte)->default_value(options.pte), "transmission failure rate per edge, in [0, 1]")
      ("pde", po::value(&options.pde)->default_value(options.pde), "per-hop delay rate, in [0, 1)")
      ("window-size", po::value(&options.window_size)->default_value(options.window_size),
       "supernode window ws (ticks), for the within-window delay ratio")
      ("supernodes", po::value(&placement)->default_value(placement),
       "quadrants (Oh §VII-E, 4 supernodes) or centre (Oh §VII-C/D, 1 supernode)")
      ("fig6", po::bool_switch(&options.fig6),
       "also print the Fig. 6 curves (lost/total vs pte, delayed/total vs pde) at --range")
      ("range", po::value(&options.range),
       "range for --fig6 (default: the best range of the sweep)");
  try {
    po::variables_map vm;
    po::store(po::parse_command_line(argc, argv, description), vm);
    if (vm.count("help")) {
      std::cout << description << "\nExample: wsntrack-network-calibrate --range-min 5 --range-max 20 --step 0.25 --fig6\n";
      return 0;
    }
    po::notify(vm);
    if (placement == "quadrants")
      options.placement = nm::SupernodePlacement::kQuadrants;
    else if (placement == "centre" || placement == "center")
      options.placement = nm::SupernodePlacement::kCentre;
    else
      throw std::invalid_argument("--supernodes must be quadrants or centre, got '" + placement + "'");
    if (!(options.step > 0.0)) throw std::invalid_argument("--step must be > 0");
    if (!(options.range_min >= 0.0) || !(options.range_max >= options.range_min))
      throw std::invalid_argument("need 0 <= --range-min <= --range-max");
    if ((options.range_max - options.range_min) / options.step > 10000.0)
      throw std::invalid_argument("more than 10000 ranges: increase --step");
    if (!(options.pte >= 0.0 && options.pte <= 1.0)) throw std::invalid_argument("--pte must be in [0, 1]");
    if (!(options.pde >= 0.0 && options.pde < 1.0)) throw std::invalid_argument("--pde must be in [0, 1)");
    if (options.window_size < 1) throw std::invalid_argument("--window-size must be >= 1");
    if (vm.count("range") && !(options.range >= 0.0)) throw std::invalid_argument("--range must be >= 0");
  } catch (const std::exception& error) {
    std::cerr << "wsntrack-network-calibrate: " << error.what() << "\n(see --help)\n";
    return 2;
  }

  const double best = sweep(options);
  if (options.fig6) fig6(options, std::isnan(options.range) ? best : options.range);
  return 0;
}
