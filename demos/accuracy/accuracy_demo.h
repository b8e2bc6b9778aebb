// demo_accuracy: teaching figures on the numerical accuracy of GJK's distance, signed volumes
// (Montanari, Petrinic, Barbieri 2017) vs Johnson's sub-algorithm (Gilbert, Johnson, Keerthi 1988;
// van den Bergen §4.3.3), from small deterministic sweeps (fixed seeds, no timings) checked against
// independent long double oracles (verification/minkowski_hull_oracle.h). Scene keys: docs/scenes.md, "accuracy".
#pragma once

#include "app/scene/demo.h"

namespace cdlab::demos {

const Demo& accuracyDemo();

}  // namespace cdlab::demos
