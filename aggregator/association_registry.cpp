#include <algorithm>

#include "aggregator/association.hpp"
#include "aggregator/mcmcda_association.hpp"
#include "aggregator/track_merger.hpp"

namespace wsn::aggregator {
namespace {

const AssociationSpec* findAssociation(const std::string& name) {
  const auto& registry = associationRegistry();
  const auto it =
      std::find_if(registry.begin(), registry.end(), [&](const AssociationSpec& a) { return a.name == name; });
  return it == registry.end() ? nullptr : &*it;
}

}  // namespace

const std::vector<AssociationSpec>& associationRegistry() {
  static const std::vector<AssociationSpec> registry = {
      mcmcdaAssociationSpec(),
      gatedMergeSpec(),
      // A new method is a new file plus one line here.
  };
  return registry;
}

void resolveAssociationParams(common::Scenario& scenario) {
  auto& aggregator = scenario.aggregator;
  const AssociationSpec* spec = findAssociation(aggregator.association);
  if (spec == nullptr) {
    std::string names;
    for (const auto& a : associationRegistry()) names += (names.empty() ? "" : ", ") + a.name;
    throw common::ScenarioError(scenario.source_path + ":" + std::to_string(aggregator.association_line) +
                                ": unknown aggregator association '" + aggregator.association +
                                "'; expected one of: " + names);
  }
  common::resolveParams(scenario.source_path, "aggregator.params", "association '" + spec->name + "'", spec->params,
                        aggregator.params);
}

std::unique_ptr<TrackAssociator> makeAssociator(const common::Scenario& scenario) {
  common::Scenario resolved = scenario;
  resolveAssociationParams(resolved);
  return findAssociation(resolved.aggregator.association)->create(resolved);
}

}  // namespace wsn::aggregator
