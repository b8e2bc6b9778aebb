// `cdlab check --figures DIR`: a figure for a failing line of two convex bounded shapes (intersect,
// distance, penetration, contact): world space twice, cdlab's answer on the left and yours on the
// right (witness points, the normal, contact points), the reasons underneath.
#pragma once

#include <string>
#include <vector>

#include "app/scene/json_reader.h"
#include "render/gl_context.h"

namespace cdlab::demos {

/// Writes the figure of one failing line to `path` (PNG, atomic) and returns "", or returns why
/// there is none (an op or a shape the figure does not draw: it draws polytopes, aabbs, obbs and
/// spheres). query: the line without "answer"; cdlab / yours: the two answers.
std::string writeCheckFigure(render::GlContext& gl, const Json& query, const Json& cdlab, const Json& yours,
                             const std::string& title, const std::vector<std::string>& reasons,
                             const std::string& path);

/// For a failing closest_point_triangle line: the triangle's Voronoi regions in its plane twice,
/// cdlab's answer left and yours right (the point, the closest point, the region named and
/// outlined). Returns "" when written, else why there is none.
std::string writeRegionFigure(render::GlContext& gl, const Json& query, const Json& cdlab, const Json& yours,
                              const std::string& title, const std::vector<std::string>& reasons,
                              const std::string& path);

/// Why a trace figure of the query cannot be drawn ("no figure: ..."), or "" when it can: shapes
/// other than polytopes, aabbs, obbs and spheres, or two polytopes whose vertex counts multiply to
/// more than kMaxMinkowskiPoints (app/scene/scene_limits.h), the hull of A − B the scenes refuse
/// too. Needs no GL context: --figures asks it first.
std::string traceFigureRefusal(const Json& query);

/// For a GJK or EPA trace of yours (`algorithm`; `trace` may hold several in "algorithms") whose
/// step `step` (0-based) breaks a rule: configuration space twice, A − B and the origin with cdlab's
/// step beside yours (GJK: simplex kept, support point, search direction; EPA: the face's nearest
/// point d·n, the support point, your polytope's edges when given). Polytope, aabb and obb shapes
/// only (cdlab's GJK runs on a sphere's centre). Returns "" when written, else why there is none.
std::string writeTraceStepFigure(render::GlContext& gl, const Json& query, const Json& trace,
                                 const std::string& algorithm, int step, const std::string& title,
                                 const std::vector<std::string>& reasons, const std::string& path);

}  // namespace cdlab::demos
