// Placeholder until the scenario loader lands (owned by the scenario work item).
#include "common/scenario.hpp"
