// Track-level association at the aggregator (Oh et al. §VI): the interface every method
// implements ("gated" merge, "mcmcda") and the registry that maps scenario names to methods.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/messages.hpp"
#include "common/param_spec.hpp"
#include "common/registry.hpp"
#include "common/scenario_config.hpp"
#include "common/scenario_error.hpp"

namespace wsn::aggregator {

/// The confirmed tracks one supernode reported for one tick.
struct SupernodeTracks {
  std::uint32_t supernode = 0;
  std::vector<common::TrackEstimate> tracks;
};

/// Turns every supernode's tracks of a tick into the run's global tracks, ids kept stable.
class TrackAssociator {
 public:
  virtual ~TrackAssociator() = default;
  /// Global tracks of tick `tick` (called once per tick, ticks increasing), sorted by track id.
  /// The result must not depend on the order of `inputs` or of the tracks within one supernode.
  virtual std::vector<common::TrackEstimate> associate(std::int32_t tick, const std::vector<SupernodeTracks>& inputs) = 0;
  /// Supernode tracks ignored over the run because a field was not finite.
  virtual std::uint64_t droppedNonFinite() const = 0;
};

/// What an association method is built from, split off the scenario at the role edge.
struct AssociationContext {
  std::string association;                ///< the registered name (aggregator.association)
  common::Rect region;
  std::uint64_t seed = 0;                 ///< run.seed
  common::DynamicsConfig dynamics;        ///< the targets' motion model, Oh eq. (8)
  std::uint32_t supernode_count = 0;      ///< the scenario's supernodes
  std::map<std::string, common::EngineParam> params;  ///< aggregator.params, resolved
};

/// The association context of `resolved`, whose aggregator.params are resolved.
AssociationContext associationContext(const common::Scenario& resolved);

/// One registered association method.
struct AssociationSpec {
  std::string name;
  std::string description;
  std::vector<common::ParamSpec> params;
  std::function<std::unique_ptr<TrackAssociator>(const AssociationContext&)> create;
};

/// All methods, in registration order.
const common::Registry<AssociationSpec>& associationRegistry();

/// Checks scenario.aggregator.association and .params against the registry and fills in
/// defaults, deriving those with a physical meaning from `statistics` (without it: the fixed
/// defaults); throws common::ScenarioError "file:line: ..." on an unknown method or parameter or
/// a value out of range.
void resolveAssociationParams(common::Scenario& scenario, const common::StatisticsSource& statistics = {});

/// Builds the method context.association names; throws std::invalid_argument for an unknown name.
std::unique_ptr<TrackAssociator> makeAssociator(const AssociationContext& context);

}  // namespace wsn::aggregator
