// wsntrack-aggregator: the top of the hierarchy in a wsntrack cluster.
#include "aggregator/role.hpp"
#include "common/dds/process_main.hpp"
#include "scenario/loader.hpp"

int main(int argc, char** argv) {
  return wsn::dds::runRoleProcess(
      argc, argv, "aggregator",
      "Merges the supernodes' tracks into global tracks (Oh §VI), publishes them, and scores the\n"
      "run against the truth: eps_K (eq. 9), eps_X (eq. 10) and OSPA. Writes tracks.csv,\n"
      "tracks_supernode.csv and metrics.json into the run directory.",
      false, wsn::scenario::loadScenario, wsn::aggregator::runAggregatorRole);
}
