// Bounding volumes side by side: renders golden/bounding_volumes/*.json (or the scene files given)
// into out/figures/bounding_volumes/, one panel per BV type with its tightness, and trace.json.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("bounding_volumes", argc, argv); }
