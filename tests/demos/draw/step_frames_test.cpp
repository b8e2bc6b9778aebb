// What a stepping demo's contact sheet says it shows (demos/draw/step_frames.h): the title names the
// iterations it skips, never "one frame per iteration" over a gap (figure review 2026-11-29:
// gjk/sliver's sheet jumped from iteration 3 to 7 under that title; epa/touching had no iteration).
#include <doctest/doctest.h>

#include "demos/draw/step_frames.h"

using namespace cdlab::demos;

TEST_CASE("iterationCoverage names the skipped iterations of framedSteps") {
    CHECK(iterationCoverage(7, framedSteps(7, 4)) == "iterations 4–6 not shown");
    CHECK(iterationCoverage(3, framedSteps(3, 4)) == "one frame per iteration");
    // The feature walks' steps, numbered from 0: edge_edge's nine steps in eight frames.
    CHECK(iterationCoverage(9, framedSteps(9, 8), "step", 0) == "step 7 not shown");
    CHECK(iterationCoverage(8, framedSteps(8, 8), "step", 0) == "one frame per step");
    CHECK(iterationCoverage(12, framedSteps(12, 4), "step", 0) == "steps 3–10 not shown");
    CHECK(iterationCoverage(5, framedSteps(5, 4)) == "iteration 4 not shown");
    CHECK(iterationCoverage(0, framedSteps(0, 4)) == "no iteration ran");
    CHECK(iterationCoverage(9, {0, 3, 8}) == "iterations 2–3, 5–8 not shown");
    CHECK(iterationCoverage(30, framedSteps(30, 4)) == "iterations 4–29 not shown");
}
