// wsntrack-network: the network model of a wsntrack cluster.
#include "common/dds/process_main.hpp"
#include "network_model/role.hpp"
#include "scenario/loader.hpp"

int main(int argc, char** argv) {
  return wsn::dds::runRoleProcess(
      argc, argv, "network",
      "Routes the sensor tiles' reports to their nearest supernodes over a multi-hop network\n"
      "(Oh et al. §V): delivery succeeds with pts(pte, k) over k independent k-hop paths and\n"
      "arrives after NegBin(k, pde) extra ticks (eq. 7). Writes observations.csv and network.json.",
      false, wsn::scenario::loadScenario, wsn::network_model::runNetworkRole);
}
