// Rigid-body drop: renders golden/drop/*.json (or the scene files given) into out/figures/drop/,
// with frames every k steps, a contact sheet (--steps), the energy / penetration plot and trace.json.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("drop", argc, argv); }
