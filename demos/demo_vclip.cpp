// V-Clip step by step: renders golden/vclip/*.json (or the scene files given) into out/figures/vclip/,
// with per-update frames and a contact sheet (--steps), animation.gif and trace.json.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("vclip", argc, argv); }
