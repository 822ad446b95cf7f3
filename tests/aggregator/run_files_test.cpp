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
  // No class vector and no stop model: the class and stop columns are empty.
  const std::string fields = "1:t7s42,1.500000,-2.250000,0.125000,0.333333,0,1,2,3,11,12,13,22,23,33,,,";
  CHECK(globalTrackCsvRow(9, t) == "9," + std::to_string(t.track) + "," + fields);
  CHECK(supernodeTrackCsvRow(9, 3, t) == "9,3," + std::to_string(t.track) + "," + fields);
  CHECK(globalTracksCsvHeader() ==
        "tick,track,label,x,y,vx,vy,p_xx,p_xy,p_xvx,p_xvy,p_yy,p_yvx,p_yvy,p_vxvx,p_vxvy,p_vyvy,class,class_probability,stop_probability");
  CHECK(supernodeTracksCsvHeader() == "tick,supernode," + globalTracksCsvHeader().substr(5));
}

TEST_CASE("track CSV rows name the most likely class and its probability, or nothing without evidence",
          "[aggregator][run_files]") {
  common::TrackEstimate t;
  t.track = 5;
  t.class_probabilities = {0.05, 0.05, 0.1, 0.6, 0.15, 0.05};  // index 3: human
  CHECK(globalTrackCsvRow(1, t).ends_with(",human,0.600000,"));
  // A uniform vector is no evidence yet, and a malformed one (not summing to 1) is none either.
  t.class_probabilities = std::vector<double>(6, 1.0 / 6.0);
  CHECK(globalTrackCsvRow(1, t).ends_with(",0,,,"));
  t.class_probabilities = {0.5, 0.6, 0.0, 0.0, 0.0, 0.0};
  CHECK(globalTrackCsvRow(1, t).ends_with(",0,,,"));
}

TEST_CASE("track CSV rows end with the stop probability of an engine that has a stop model", "[aggregator][run_files]") {
  common::TrackEstimate t;
  t.track = 5;
  t.stop_probability = 0.8375;
  CHECK(globalTrackCsvRow(1, t).ends_with(",0,,,0.837500"));
  t.stop_probability = 0.0;
  CHECK(globalTrackCsvRow(1, t).ends_with(",0,,,0.000000"));
}

}  // namespace
}  // namespace wsn::aggregator
