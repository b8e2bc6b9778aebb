// The collision response on the board (drop scenes with "figure": "impulse"): one box touching the
// ground (z = its lowest vertex) at the vertices within 1e-9 of the lowest, with given velocities;
// core's solveContacts (core/dynamics/impulse_solver.h) answers once, recording each sweep. Frame
// "impulse": the relative velocity at the contact, the effective mass 1/k = 1/m + n·((I⁻¹(r×n))×r)
// term by term, the closed-form j = −(1 + e) v_n k, the solver's normal and friction impulses (the
// Coulomb clamp), velocities before and after. Frame "iterations" (two or more contacts): λ_n per
// point after each sequential-impulse sweep. Test: tests/demos/drop/impulse_figure_test.cpp.
#pragma once

#include <memory>

#include "app/scene/demo.h"

namespace cdlab::demos {

/// Reads the keys of an impulse scene (docs/scenes.md, drop) and finishes r.
std::unique_ptr<PreparedScene> readImpulseScene(ObjectReader& r, SceneCommon common);

}  // namespace cdlab::demos
