// Running the built `scanstation` binary from the CLI tests.
#pragma once

#include "test_support.h"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <sys/wait.h>

namespace scanstation::test {

struct Outcome {
  int exit_code;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline Outcome scanstation(const std::string& args) {
  ScratchFolder io;
  const std::string command = std::string(SCANSTATION_BINARY) + " " + args + " >" + (io / "out").string() + " 2>" +
                              (io / "err").string() + " </dev/null";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(io / "out"), slurp(io / "err")};
}

/// A report's "boundary" of the station flow over `steps` steps: grown live
/// step by step with the lines of sight carved first, a closed genus-0
/// 2-manifold with every distinct point on it.
inline void expect_live_closed_genus_zero(const nlohmann::json& boundary, int steps) {
  EXPECT_EQ(boundary["built"], "incremental, lines of sight carved first");
  EXPECT_EQ(boundary["live"]["steps"], steps);
  EXPECT_GT(boundary["live"]["sight_line_cells"].get<int>(), 0);
  EXPECT_EQ(boundary["topology"]["closed"], true);
  EXPECT_EQ(boundary["topology"]["genus"], 0);
  EXPECT_EQ(boundary["topology"]["manifold"], true);
  EXPECT_EQ(boundary["all_on_boundary"], true);
  EXPECT_EQ(boundary["vertices"], boundary["distinct_points"]);
}

/// The JSON progress lines of one kind ("step", "boundary") in `err`.
inline std::vector<nlohmann::json> progress_events(const std::string& err, const std::string& kind) {
  std::vector<nlohmann::json> events;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json event = nlohmann::json::parse(line, nullptr, false);
    if (!event.is_discarded() && event["event"] == kind) events.push_back(event);
  }
  return events;
}

}  // namespace scanstation::test
