#include "aggregator/run_files.hpp"

#include "common/class_evidence.hpp"
#include "common/output.hpp"
#include "common/track_id.hpp"

namespace wsn::aggregator {
namespace {

constexpr const char* kTrackColumns =
    "track,label,x,y,vx,vy,p_xx,p_xy,p_xvx,p_xvy,p_yy,p_yvx,p_yvy,p_vxvx,p_vxvy,p_vyvy,class,class_probability,stop_probability";

std::string trackFields(const common::TrackEstimate& track) {
  std::string row = std::to_string(track.track) + "," + common::track_id::label(track.track);
  for (const double value : {track.x, track.y, track.vx, track.vy}) row += "," + common::fixed6(value);
  for (int i = 0; i < 4; ++i)
    for (int j = i; j < 4; ++j) row += "," + common::significant9(track.covariance[static_cast<std::size_t>(4 * i + j)]);
  // Empty for a track without class evidence; else its most likely class and that probability.
  const common::DeclaredClass declared = common::declaredTrackClass(track.class_probabilities);
  if (declared.target_class == common::TargetClass::kUnknown)
    row += ",,";
  else
    row += "," + common::targetClassName(declared.target_class) + "," + common::fixed6(declared.probability);
  // Empty for an engine without a stop model.
  return row + "," + (track.stop_probability ? common::fixed6(*track.stop_probability) : std::string());
}

}  // namespace

std::string globalTracksCsvHeader() { return std::string("tick,") + kTrackColumns; }
std::string supernodeTracksCsvHeader() { return std::string("tick,supernode,") + kTrackColumns; }

std::string globalTrackCsvRow(std::int32_t tick, const common::TrackEstimate& track) {
  return std::to_string(tick) + "," + trackFields(track);
}

std::string supernodeTrackCsvRow(std::int32_t tick, std::uint32_t supernode, const common::TrackEstimate& track) {
  return std::to_string(tick) + "," + std::to_string(supernode) + "," + trackFields(track);
}

}  // namespace wsn::aggregator
