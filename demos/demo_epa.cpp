// EPA step by step: renders golden/epa/*.json (or the scene files given) into out/figures/epa/,
// with GJK's simplex, per-iteration frames, a bounds plot, a contact sheet (--steps), animation.gif and trace.json.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("epa", argc, argv); }
