// Accuracy figures: renders golden/accuracy/*.json (or the scene files given) into
// out/figures/accuracy/ (GJK distance error vs scale / offset / edge angle, signed volumes vs Johnson).
#include "demos/app/cli.h"

int main(int argc, char** argv) { return cdlab::demos::demoMain("accuracy", argc, argv); }
