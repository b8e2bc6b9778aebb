// GJK step by step: renders golden/gjk/*.json (or the scene files given) into out/figures/gjk/,
// with per-iteration frames, a contact sheet (--steps), animation.gif and trace.json.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("gjk", argc, argv); }
