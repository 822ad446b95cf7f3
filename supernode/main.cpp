// wsntrack-supernode: one supernode (tracking group) of a wsntrack cluster.
#include "common/dds/process_main.hpp"
#include "scenario/loader.hpp"
#include "supernode/role.hpp"

int main(int argc, char** argv) {
  return wsn::dds::runRoleProcess(
      argc, argv, "supernode",
      "Tracks the targets of one tracking group (the sensors nearest to this supernode, Oh §V):\n"
      "a sliding window of ws ticks of delivered observations, delayed ones in their own slots,\n"
      "processed by the scenario's tracking engine; tracks predicted to leave the group are handed\n"
      "to the neighbouring supernode under the same id (Oh §VI).",
      true, wsn::scenario::loadScenario, wsn::supernode::runSupernodeRole);
}
