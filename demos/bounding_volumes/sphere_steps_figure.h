// Ritter's and Welzl's bounding spheres step by step (bounding_volumes scenes with "figure":
// "sphere_steps"): points in the plane z = 0, so every sphere is drawn as its great circle. Frames
// "ritter" and "welzl", small multiples in reading order, from core's RitterTrace and WelzlTrace
// (core/bounding/bounding_sphere.h): Ritter's starting pair and each growth to a point outside;
// each event of Welzl's move-to-front recursion with its support set. Test:
// tests/demos/bounding_volumes/sphere_steps_test.cpp.
#pragma once

#include <memory>

#include "app/scene/demo.h"

namespace cdlab::demos {

/// Reads the keys of a sphere_steps scene (docs/scenes.md, bounding_volumes) and finishes r.
std::unique_ptr<PreparedScene> readSphereStepsScene(ObjectReader& r, SceneCommon common);

}  // namespace cdlab::demos
