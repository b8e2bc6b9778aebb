// GJK's reduction step in the simplex's own plane (gjk scenes, frame "regions"): the first step that
// drops a vertex from a segment or a triangle, drawn in the plane of the triangle (or of the segment
// and the origin): every Voronoi region of the simplex's vertices, edges and face, the origin's
// projection in one of them, the tests that place it there (Ericson §5.1.5 / §9.5.2) and the
// vertices dropped. Test: tests/demos/gjk/gjk_regions_test.cpp.
#pragma once

#include <string>
#include <vector>

#include "app/scene/json_reader.h"
#include "core/gjk_epa/gjk.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

/// The index in `steps` of the first step whose reduction drops a vertex of a 2- or 3-vertex
/// simplex, or -1.
int firstDroppingStep(const std::vector<GjkTraceStep>& steps);

/// The step's region tests for trace.json: per feature test its name and value (the dot products
/// that decide the origin's region), the kept and the dropped vertices.
Json reductionRegionsJson(const GjkTraceStep& step);

/// The frame (width × height layout pixels at `scale`): title, the plane picture, two caption lines.
render::Image drawReductionRegions(render::GlContext& gl, int width, int height, int scale, const std::string& title,
                                   const GjkTraceStep& step);

}  // namespace cdlab::demos
