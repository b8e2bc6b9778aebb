// Command-line entry points: the `cdlab` program and the per-demo executables share option parsing.
#pragma once

#include <string>

namespace cdlab::demos {

/// `cdlab <command> [options]`: figures, golden, query, ... Returns the exit status
/// (0 ok, 1 test/comparison failure or failed queries, 2 usage or input error).
int cdlabMain(int argc, char** argv);

/// `demo_<name> [scene.json ...] [options]`: renders that demo's scenes (all under golden/<name>/
/// when no file is given) into out/figures/<name>/.
int demoMain(const std::string& demo, int argc, char** argv);

}  // namespace cdlab::demos
