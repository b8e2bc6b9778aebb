// GJK's witness pair is one of many when the closest features are parallel (gjk scenes, frame
// "closest_set"): core's closestSetOfPolytopes (core/closest/closest_set.h) gives the whole set,
// drawn on both bodies with a few pairs joined, beside the one pair GJK returned. Test:
// tests/demos/gjk/gjk_closest_set_test.cpp.
#pragma once

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "core/closest/closest_set.h"
#include "core/gjk_epa/gjk.h"
#include "demos/draw/pair_figure.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

/// The closest set of a separated polytope pair (empty onA when either shape is not a polytope or
/// they are not separated).
ClosestSet gjkClosestSet(const PairScene& pair, const GjkResult& r);

Json closestSetJson(const ClosestSet& set);

/// The frame: both bodies, the set on each (filled for a polygon, thick for a segment), its corners
/// joined to their partners, GJK's pair marked; two caption lines with the numbers.
render::Image drawClosestSet(render::GlContext& gl, const SceneCommon& common, int scale, const PairScene& pair,
                             const PairDrawing& d, const GjkResult& r, const ClosestSet& set);

}  // namespace cdlab::demos
