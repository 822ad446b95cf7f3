// wsntrack-node: one sensor tile of a wsntrack cluster.
#include "common/dds/process_main.hpp"
#include "node/role.hpp"
#include "scenario/loader.hpp"

int main(int argc, char** argv) {
  return wsn::dds::runRoleProcess(
      argc, argv, "node",
      "Simulates one rectangular tile of sensors: per tick the signal of Oh eq. (5) at every sensor,\n"
      "threshold eta, exchange of readings within 2 Rs with neighbouring tiles over DDS, and the\n"
      "weighted centre of mass (eq. 6) reported by each local maximum.",
      true, wsn::scenario::loadScenario, wsn::node::runNodeRole);
}
