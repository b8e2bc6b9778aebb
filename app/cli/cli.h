// Command-line entry points: the `cdlab` program and the per-demo executables share option parsing.
#pragma once

#include <functional>
#include <map>
#include <stdexcept>
#include <string>

namespace cdlab::demos {

/// A wrong command line: the program prints "<program>: <what>" and the usage, exit 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Commands beyond figures, render, golden and demos (query, check, bench, stress), given by the
/// program that links them: `cdlab` has them all (app/cdlab.cpp), `cdlab-figures` none
/// (app/cdlab_figures.cpp: what `./cdlab figures` builds, without compiling the tools).
/// Each is called with the whole argv (argv[1] the command).
using ToolCommands = std::map<std::string, std::function<int(int argc, char** argv)>>;

/// `cdlab <command> [options]`: figures, golden, query, ... Returns the exit status
/// (0 ok, 1 test/comparison failure or failed queries, 2 usage or input error).
int cdlabMain(int argc, char** argv, const ToolCommands& tools = {});

/// `demo_<name> [scene.json ...] [options]`: renders that demo's scenes (all under golden/<name>/
/// when no file is given) into out/figures/<name>/.
int demoMain(const std::string& demo, int argc, char** argv);

}  // namespace cdlab::demos
