// The cdlab command line: figures, golden tests, query (see `cdlab --help`).
#include "app/cli/cli.h"

int main(int argc, char** argv) { return cdlab::demos::cdlabMain(argc, argv); }
