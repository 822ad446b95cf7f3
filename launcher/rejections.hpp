// The run's record of what its roles refused at the edge (common/edge_checks.hpp): the launcher
// gathers each role's RUN_DIR/rejected/ROLE-INDEX.json into one RUN_DIR/rejected.json.
#pragma once

#include <cstdint>
#include <string>

namespace wsn::launcher {

/// Writes RUN_DIR/rejected.json — {"total": N, "processes": [each role's file, in name order]} —
/// and removes the role files; returns N. A role file that is not what a role writes is counted as
/// one more problem, not skipped: a run never looks cleaner than it was.
std::uint64_t gatherRejections(const std::string& run_dir);

}  // namespace wsn::launcher
