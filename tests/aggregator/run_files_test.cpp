#include "aggregator/run_files.hpp"

#include <catch2/catch.hpp>

#include "common/track_id.hpp"

namespace wsn::aggregator {
namespace {

TEST_CASE("track CSV rows carry the tick, the label, the state and the covariance's upper triangle",
          "[aggregator][run_files]") {
  common::TrackEstimate t;
  t.track = common::track_id::birth(1, 7, 42);
  t.x = 1.5;
  t.y = -2.25;
  t.vx = 0.125;
  t.vy = 1.0 / 3.0;
  for (int i = 0; i < 16; ++i) t.covariance[static_cast<std::size_t>(i)] = 10.0 * (i / 4) + (i % 4);  // row r, col c: 10r + c
  // Upper triangle row by row: (0,0) (0,1) (0,2) (0,3) (1,1) (1,2) (1,3) (2,2) (2,3) (3,3).
  const std::string fields = "1:t7s42,1.500000,-2.250000,0.125000,0.333333,0,1,2,3,11,12,13,22,23,33";
  CHECK(globalTrackCsvRow(9, t) == "9," + std::to_string(t.track) + "," + fields);
  CHECK(supernodeTrackCsvRow(9, 3, t) == "9,3," + std::to_string(t.track) + "," + fields);
  CHECK(globalTracksCsvHeader() ==
        "tick,track,label,x,y,vx,vy,p_xx,p_xy,p_xvx,p_xvy,p_yy,p_yvx,p_yvy,p_vxvx,p_vxvy,p_vyvy");
  CHECK(supernodeTracksCsvHeader() == "tick,supernode," + globalTracksCsvHeader().substr(5));
}

}  // namespace
}  // namespace wsn::aggregator
