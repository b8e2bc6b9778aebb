// The cdlab command line: figures, golden tests, query (see `cdlab --help`).
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::cdlabMain(argc, argv); }
