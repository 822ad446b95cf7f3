#include "aggregator/association.hpp"
#include "aggregator/mcmcda_association.hpp"
#include "aggregator/track_merger.hpp"

namespace wsn::aggregator {

const common::Registry<AssociationSpec>& associationRegistry() {
  static const common::Registry<AssociationSpec> registry("aggregator association", {
      mcmcdaAssociationSpec(),
      gatedMergeSpec(),
      // A new method is a new file plus one line here.
  });
  return registry;
}

void resolveAssociationParams(common::Scenario& scenario, const common::StatisticsSource& statistics) {
  auto& aggregator = scenario.aggregator;
  const AssociationSpec& spec = associationRegistry().at<common::ScenarioError>(
      aggregator.association, scenario.source_path + ":" + std::to_string(aggregator.association_line) + ": ");
  common::resolveParams(scenario.source_path, "aggregator.params", "association '" + spec.name + "'", spec.params,
                        aggregator.params, statistics, &scenario.derived);
}

AssociationContext associationContext(const common::Scenario& resolved) {
  return {resolved.aggregator.association, resolved.region, resolved.run.seed, resolved.dynamics,
          static_cast<std::uint32_t>(resolved.supernodes.size()), resolved.aggregator.params};
}

std::unique_ptr<TrackAssociator> makeAssociator(const AssociationContext& context) {
  return associationRegistry().at(context.association).create(context);
}

}  // namespace wsn::aggregator
