// Lin–Canny step by step: renders golden/lin_canny/*.json (or the scene files given) into
// out/figures/lin_canny/, with per-update frames (--steps), the side-by-side walk with V-Clip and
// the cycling figure, animation.gif and trace.json.
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("lin_canny", argc, argv); }
