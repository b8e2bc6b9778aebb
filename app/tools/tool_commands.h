// The tools' commands (query, check, bench, stress) for cdlabMain: the full `cdlab` program passes
// them (app/cdlab.cpp), and so do tests that run a tool in-process; cdlab-figures links none.
#pragma once

#include "app/cli/cli.h"

namespace cdlab::demos {

/// "query", "check", "bench", "stress": each parses its own options (a bad one: UsageError).
ToolCommands toolCommands();

}  // namespace cdlab::demos
