// Where a run came from: the build (version, commit, Cyclone DDS), the command line, when, on which
// host and from which scenario file (its sha256), recorded in run.json and metrics.json so that a
// run directory alone says what made it.
#pragma once

#include <string>
#include <vector>

namespace wsn::common {

struct Provenance {
  std::string version;                    ///< the project's version, e.g. "0.1.0"
  std::string commit;                     ///< full git hash, "+dirty" when the tree was modified
  std::string cyclone_dds;                ///< Cyclone DDS version built against
  std::vector<std::string> command_line;  ///< argv as given, argv[0] first
  std::string cwd;                        ///< the working directory the command line is relative to
  std::string started_utc;                ///< ISO 8601, e.g. "2026-11-25T12:01:02Z"
  std::string host;                       ///< gethostname()
  std::string scenario_file;              ///< the scenario path as given on the command line
  std::string scenario_sha256;            ///< of that file's bytes as read (before any --set)
  friend bool operator==(const Provenance&, const Provenance&) = default;
};

/// The provenance of a run started now by this build with this command line from this scenario
/// file. Throws std::runtime_error when the scenario file cannot be read.
Provenance captureProvenance(const std::vector<std::string>& command_line, const std::string& scenario_file);

/// Provenance as one line of JSON (an object with the keys above and "cyclone_dds"), so that it is
/// one line of run.json and metrics.json that comparisons of equal runs can leave out.
std::string provenanceJson(const Provenance& provenance);

/// Reads the object provenanceJson writes; throws std::runtime_error naming what is missing.
Provenance parseProvenanceJson(const std::string& json);

/// The provenance a launcher wrote into RUN_DIR/run.json, as provenanceJson gives it; empty when
/// the file or its "provenance" key is absent (a role started by hand). Throws
/// std::runtime_error when the file is there but malformed.
std::string readRunProvenance(const std::string& run_json_path);

/// The lower-case hex SHA-256 of a file's bytes; throws std::runtime_error when it cannot be read.
std::string sha256OfFile(const std::string& path);

/// The lower-case hex SHA-256 of a byte string.
std::string sha256Hex(const std::string& bytes);

}  // namespace wsn::common
