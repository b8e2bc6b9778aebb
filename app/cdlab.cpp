// The cdlab command line with every command: figures, render, golden and demos (app/cli) and the
// tools query, check, bench and stress (app/tools; see `cdlab --help`). `./cdlab figures` builds
// the program of app/cdlab_figures.cpp instead, which links no tool.
#include "app/cli/cli.h"
#include "app/tools/tool_commands.h"

int main(int argc, char** argv) { return cdlab::demos::cdlabMain(argc, argv, cdlab::demos::toolCommands()); }
