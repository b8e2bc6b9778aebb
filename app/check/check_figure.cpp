#include "app/check/check_figure.h"

#include <algorithm>
#include <array>

#include "core/closest/voronoi_regions.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "app/check/check_values.h"
#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/pair_figure.h"
#include "app/query/query.h"
#include "app/query/query_json.h"
#include "app/query/query_shapes.h"
#include "app/scene/json_reader.h"
#include "app/scene/scene_limits.h"
#include "render/canvas.h"
#include "render/image.h"

namespace cdlab::demos {

namespace {

using render::Anchor;
using render::Canvas;
using render::Role;
using render::TextStyle;
using render::roleColor;

// The query shape as a scene shape the figures draw, or nothing.
std::optional<SceneShape> drawableShape(const Json& node, const std::string& path) {
    const QueryShape q = parseQueryShape(JsonNode(node, path, "check"));
    SceneShape s;
    s.pose = Transform{};
    switch (q.kind) {
        case QueryShape::Kind::Sphere:
            s.kind = SceneShape::Kind::Sphere;
            s.pose.position = q.vertices[0];
            s.radius = q.radius;
            return s;
        case QueryShape::Kind::Aabb:
        case QueryShape::Kind::Obb:
        case QueryShape::Kind::Polytope:
            s.kind = SceneShape::Kind::Polytope;
            s.polytope = PolytopeShape(q.vertices);  // world-frame vertices, identity pose
            return s;
        case QueryShape::Kind::Cylinder:
        case QueryShape::Kind::Cone:
            s.kind = q.kind == QueryShape::Kind::Cylinder ? SceneShape::Kind::Cylinder : SceneShape::Kind::Cone;
            s.radius = q.curved.radius;
            s.halfHeight = q.curved.halfHeight;
            s.pose.position = q.curved.center;
            s.pose.rotation = Quat(q.curved.rotation);
            return s;
        default: return std::nullopt;
    }
}

// Shapes a and b of the query as a pair the figures draw (forTrace: the trace figures, drawn in
// configuration space — polytopes, whose A − B is an exact hull, and spheres), or nothing with `why`
// set.
std::optional<PairScene> drawablePair(const Json& query, bool forTrace, std::string& why) {
    if (!query.contains("a") || !query.contains("b")) {
        why = "no figure: the query has no shapes a and b";
        return std::nullopt;
    }
    // Read as a scene reads a polytope, within its vertex limit, before any hull is built: a
    // 500 000-vertex line took a minute and 2.8 GB, then LLVM ran out of memory (check_test "check
    // --figures: no figure of a polytope over the scenes' vertex limit").
    for (const char* side : {"a", "b"}) {
        const Json* shape = member(query, side);
        const Json* polytope = shape ? member(*shape, "polytope") : nullptr;
        const Json* vertices = polytope ? member(*polytope, "vertices") : nullptr;
        if (vertices && vertices->is_array() && vertices->size() > kMaxShapeVertices) {
            why = std::string("no figure: ") + side + " is a polytope of " + std::to_string(vertices->size()) +
                  " vertices, over the limit of " + std::to_string(kMaxShapeVertices) + " the figures draw";
            return std::nullopt;
        }
    }
    const std::optional<SceneShape> a = drawableShape(query["a"], "$.a"), b = drawableShape(query["b"], "$.b");
    const auto traced = [](const std::optional<SceneShape>& s) {
        return s->kind == SceneShape::Kind::Polytope || s->kind == SceneShape::Kind::Sphere;
    };
    if (!a || !b || (forTrace && (!traced(a) || !traced(b)))) {
        why = forTrace ? "no figure: trace steps are drawn for polytopes, aabbs, obbs and spheres"
                       : "no figure: it draws polytopes, aabbs, obbs, spheres, cylinders and cones";
        return std::nullopt;
    }
    PairScene pair;
    pair.a = *a;
    pair.b = *b;
    return pair;
}

// A − B of two polytopes is drawn as the exact hull of every difference: the scenes' cap on their
// count (kMaxMinkowskiPoints, app/scene/scene_limits.h) holds here too, checked before any hull
// is built. "" within it, else why there is no figure.
std::string minkowskiTooLarge(const PairScene& pair) {
    if (!pair.a.isPolytope() || !pair.b.isPolytope()) return "";
    const std::size_t na = pair.a.polytope.vertices().size(), nb = pair.b.polytope.vertices().size();
    if (!(double(na) * double(nb) > kMaxMinkowskiPoints)) return "";
    return "no figure: A − B would be the hull of " + std::to_string(na) + " x " + std::to_string(nb) +
           " differences of vertices, over the limit of " + std::to_string(std::size_t(kMaxMinkowskiPoints)) +
           " the figures draw";
}

std::string number(const Json& j) {
    if (!j.is_number()) return j.dump();
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", j.get<double>());
    return buf;
}

// One answer drawn over the bodies: witness points (p_A, p_B), contact points, the normal.
void drawAnswer(Canvas& world, const PairDrawing& d, const Json& answer) {
    TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
    const auto point = [&](const Vec3& p) {
        world.drawPoint(p, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
    };
    Vec3 foot = d.wCenter;
    bool haveFoot = false;
    if (isVec(answer.value("point_a", Json())) && isVec(answer.value("point_b", Json()))) {
        const Vec3 pa = vec(answer["point_a"]), pb = vec(answer["point_b"]);
        world.drawLine(pa, pb, lineStyle(Role::Result, 3.0f, false, true));
        point(pa);
        point(pb);
        const bool apart = (pa - pb).norm() > 1e-3 * d.wRadius;
        drawLabelAway(world, pa, apart ? pb : d.a.center, "p_A", ts);
        drawLabelAway(world, pb, apart ? pa : d.b.center, "p_B", ts);
        foot = pb;
        haveFoot = true;
    }
    if (answer.contains("points") && answer["points"].is_array()) {
        for (const Json& c : answer["points"])
            if (c.is_object() && isVec(c.value("point_a", Json())) && isVec(c.value("point_b", Json()))) {
                point(vec(c["point_a"]));
                point(vec(c["point_b"]));
                if (!haveFoot) foot = vec(c["point_b"]), haveFoot = true;
            }
    }
    if (isVec(answer.value("normal", Json()))) {
        const Vec3 n = vec(answer["normal"]);
        if (n.norm() > 0) {
            const Vec3 tip = foot + 0.35 * d.wRadius * n.normalized();
            world.drawArrow(foot, tip, lineStyle(Role::Direction, 3.0f, false, true));
            drawLabelAway(world, tip, foot, "n", ts, 10.0);
        }
    }
}

// The panel's second heading line: the answer's numbers.
std::string summary(const Json& answer) {
    std::string s;
    for (const char* key : {"intersect", "colliding", "distance", "depth"})
        if (answer.contains(key)) s += (s.empty() ? "" : ", ") + std::string(key) + " " + number(answer[key]);
    return s.empty() ? answer.dump().substr(0, 60) : s;
}

// One step as drawn. GJK: the simplex kept, the support point, the search direction. EPA: the face
// expanded (unit normal `direction`, `distance` from the origin), the support point along it, and
// the polytope's triangles when the trace gives them.
struct StepPicture {
    std::vector<Vec3> simplex;
    Vec3 support = Vec3::Zero(), direction = Vec3::Zero();
    bool epa = false;
    double distance = 0.0;
    std::vector<std::array<Vec3, 3>> faces;
};

// The trace of `algorithm` in yours: the object itself, or the one in "algorithms" with that name.
Json traceOf(const Json& trace, const std::string& algorithm) {
    if (trace.is_object() && trace.contains("algorithms") && trace["algorithms"].is_array())
        for (const Json& one : trace["algorithms"])  // no "algorithm": GJK, as the check reads it
            if (one.is_object() && one.value("algorithm", std::string("gjk")) == algorithm) return one;
    return trace;
}

// EPA step `k` ({"steps": [...]}; normal / closest_normal, distance / closest_distance, support,
// optional polytope), or nothing when missing or malformed.
std::optional<StepPicture> epaStepOf(const Json& trace, int k) {
    const Json* steps = trace.is_object() && trace.contains("steps") ? &trace["steps"] : trace.is_array() ? &trace : nullptr;
    if (!steps || !steps->is_array() || k < 0 || k >= static_cast<int>(steps->size())) return std::nullopt;
    const Json& s = (*steps)[std::size_t(k)];
    if (!s.is_object()) return std::nullopt;
    const Json n = s.value("normal", s.value("closest_normal", Json())), d = s.value("distance", s.value("closest_distance", Json()));
    const Json w = s.value("support", Json());
    if (!isVec(n) || !d.is_number()) return std::nullopt;
    StepPicture p;
    p.epa = true;
    p.direction = vec(n);
    p.distance = d.get<double>();
    if (isVec(w)) p.support = vec(w);
    else if (w.is_object() && isVec(w.value("a", Json())) && isVec(w.value("b", Json()))) p.support = vec(w["a"]) - vec(w["b"]);
    else return std::nullopt;
    if (s.contains("polytope") && s["polytope"].is_array())
        for (const Json& f : s["polytope"])
            if (f.is_array() && f.size() == 3 && isVec(f[0]) && isVec(f[1]) && isVec(f[2]))
                p.faces.push_back({vec(f[0]), vec(f[1]), vec(f[2])});
    return p;
}

// Step `k` of a trace ({"steps": [...]} or the array; support a point of A − B or {"a", "b"}), or
// nothing when it is missing or malformed.
std::optional<StepPicture> stepOf(const Json& trace, int k) {
    const Json* steps = trace.is_object() && trace.contains("steps") ? &trace["steps"] : trace.is_array() ? &trace : nullptr;
    if (!steps || !steps->is_array() || k < 0 || k >= static_cast<int>(steps->size())) return std::nullopt;
    const Json& s = (*steps)[std::size_t(k)];
    if (!s.is_object() || !isVec(s.value("direction", Json()))) return std::nullopt;
    StepPicture p;
    p.direction = vec(s["direction"]);
    const Json support = s.value("support", Json());
    if (isVec(support)) p.support = vec(support);
    else if (support.is_object() && isVec(support.value("a", Json())) && isVec(support.value("b", Json())))
        p.support = vec(support["a"]) - vec(support["b"]);
    else return std::nullopt;
    if (s.contains("simplex") && s["simplex"].is_array())
        for (const Json& v : s["simplex"])
            if (isVec(v)) p.simplex.push_back(vec(v));
    return p;
}

// cdlab's GJK steps on the full shapes, world units, in the check schema: each bounded shape is
// conv(vertices) ⊕ ball(radius) (a sphere: its centre and radius), run through core GJK's
// RoundedShape, the radius in every support point as a student's support function has it. The
// query's own trace runs on the cores (a sphere's centre, docs/check.md), a different
// configuration space. Starts along `initial` when given.
Json fullShapeGjkSteps(const Json& query, const std::optional<Vec3>& initial) {
    const Json* ja = member(query, "a");
    const Json* jb = member(query, "b");
    if (!ja || !jb) return Json::array();
    const QueryShape qa = parseQueryShape(JsonNode(*ja, "$.a", "check"));
    const QueryShape qb = parseQueryShape(JsonNode(*jb, "$.b", "check"));
    const RoundedShape<PolytopeShape> a{PolytopeShape(qa.vertices), qa.radius}, b{PolytopeShape(qb.vertices), qb.radius};
    GjkOptions options;
    GjkSimplex start;  // one vertex whose direction gives the first support (a warm start)
    if (initial) {
        start.count = 1;
        start.vertex[0].direction = *initial;
        options.warmStart = &start;
    }
    GjkTrace trace;
    gjkDistance(a, b, options, &trace);
    Json steps = Json::array();
    for (const GjkTraceStep& t : trace.steps) {
        Json simplex = Json::array();
        for (int i = 0; i < t.simplexCount; ++i) simplex.push_back(vecJson(t.simplex[i].w));
        steps.push_back({{"direction", vecJson(t.direction)}, {"support", vecJson(t.support.w)}, {"simplex", simplex}});
    }
    return steps;
}

// EPA at one step: the polytope's edges (when given), the face's nearest point d·n as an arrow from
// the origin, the support point w along n.
void drawEpaStep(Canvas& cs, const PairDrawing& d, const StepPicture& s) {
    const TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
    for (const auto& f : s.faces)
        for (int i = 0; i < 3; ++i) cs.drawLine(f[i], f[(i + 1) % 3], lineStyle(Role::Simplex, 1.5f, false, true));
    const Vec3 foot = s.distance * s.direction.normalized();
    cs.drawArrow(Vec3::Zero(), foot, lineStyle(Role::Direction, 3.0f, false, true));
    drawLabelAway(cs, foot, Vec3::Zero(), "d·n", ts, 12.0);
    cs.drawLine(foot, s.support, lineStyle(Role::Muted, 2.0f, true, true));
    cs.drawPoint(s.support, 7.0f, roleColor(Role::Support), true, 1.5f, roleColor(Role::Ink));
    drawLabelAway(cs, s.support, foot, "w", ts);
    (void)d;
}

// Configuration space at one step: A − B, the origin, the simplex (w0.., edges), the support point
// w and the direction d from the origin (EPA: drawEpaStep).
void drawStep(Canvas& cs, const PairDrawing& d, const StepPicture& s) {
    if (d.c.valid)
        drawBody(cs, d.c, roleColor(Role::Minkowski), 0.18f, roleColor(Role::Minkowski).scaled(0.7f), 1.2f);
    drawOrigin(cs, 0.06 * d.cRadius, false);
    if (s.epa) return drawEpaStep(cs, d, s);
    const TextStyle ts{17.0f, roleColor(Role::Ink), Anchor::Center, true, true};
    Vec3 mid = Vec3::Zero();
    for (const Vec3& p : s.simplex) mid += p / double(s.simplex.size());
    for (std::size_t i = 0; i < s.simplex.size(); ++i)
        for (std::size_t j = i + 1; j < s.simplex.size(); ++j)
            cs.drawLine(s.simplex[i], s.simplex[j], lineStyle(Role::Simplex, 3.0f, false, true));
    // The support point w: its own marker, or the name of the simplex point it became.
    bool supportKept = false;
    for (std::size_t i = 0; i < s.simplex.size(); ++i) {
        const bool isSupport = (s.simplex[i] - s.support).norm() <= 1e-12 * d.cRadius;
        supportKept = supportKept || isSupport;
        cs.drawPoint(s.simplex[i], 7.0f, roleColor(isSupport ? Role::Support : Role::Simplex), true, 1.5f,
                     roleColor(Role::Ink));
        drawLabelAway(cs, s.simplex[i], s.simplex.size() > 1 ? mid : Vec3::Zero(),
                      "w" + std::to_string(i) + (isSupport ? " = w" : ""), ts);
    }
    if (!supportKept) {
        cs.drawPoint(s.support, 7.0f, roleColor(Role::Support), true, 1.5f, roleColor(Role::Ink));
        drawLabelAway(cs, s.support, mid, "w", ts);
    }
    if (s.direction.norm() > 0) {
        const Vec3 tip = 0.45 * d.cRadius * s.direction.normalized();
        cs.drawArrow(Vec3::Zero(), tip, lineStyle(Role::Direction, 3.0f, false, true));
        drawLabelAway(cs, tip, Vec3::Zero(), "d", ts, 10.0);
    }
}

}  // namespace

namespace {

// The figure's caption: the first two reasons wrapped to the frame's width (never cut mid-number:
// check_test "the figure wraps its reasons"), at most kMaxCaptionLines lines, and the layout whose
// caption band holds them.
struct CheckCaption {
    TwoPanelLayout layout;
    std::vector<std::string> lines;
};
constexpr std::size_t kMaxCaptionLines = 6;
CheckCaption checkCaption(render::GlContext& gl, const std::vector<std::string>& reasons) {
    CheckCaption c{twoPanelLayout(1280, 640, ""), {}};
    const TextStyle style{17.0f, roleColor(Role::Ink), Anchor::TopLeft, false, false};  // composeTwoPanel's
    const Canvas measure(gl, canvasOptions(c.layout.width, c.layout.height, 1));
    for (std::size_t i = 0; i < reasons.size() && i < 2; ++i)
        for (const std::string& line : wrapAtSeparator(measure, reasons[i], " ", style, c.layout.width - 36.0, true))
            c.lines.push_back(line);
    if (c.lines.size() > kMaxCaptionLines) {
        c.lines.resize(kMaxCaptionLines);
        c.lines.back() += " ...";
    }
    c.layout.captionBand = std::max(c.layout.captionBand, 8 + 25 * static_cast<int>(c.lines.size()) + 4);
    return c;
}

}  // namespace

std::string writeRegionFigure(render::GlContext& gl, const Json& query, const Json& cdlab, const Json& yours,
                              const std::string& title, const std::vector<std::string>& reasons,
                              const std::string& path) {
    const Json& t = query.value("triangle", Json());
    if (!isVec(query.value("point", Json())) || !t.is_array() || t.size() != 3 || !isVec(t[0]) || !isVec(t[1]) ||
        !isVec(t[2]))
        return "no figure: the query needs \"point\" and \"triangle\"";
    const Triangle tri{vec(t[0]), vec(t[1]), vec(t[2])};
    const Vec3 p = vec(query["point"]);
    const double size = std::max({(tri.b - tri.a).norm(), (tri.c - tri.a).norm(), (tri.c - tri.b).norm()});
    const TriangleVoronoiDiagram diagram = triangleVoronoiRegions({tri, 0.6 * size, 0.3 * size});
    if (!diagram.valid) return "no figure: the triangle is degenerate";
    std::vector<Vec3> frame(diagram.rectangle.begin(), diagram.rectangle.end());
    frame.push_back(p);
    Vec3 center;
    double radius;
    boundingSphere(frame, center, radius);
    // Nearly face-on from the point's side, tilted so the point's height above the plane shows.
    const double side = (p - tri.a).dot(diagram.normal) < 0 ? -1.0 : 1.0;
    const Vec3 view = side * diagram.normal + 0.6 * diagram.axisV;
    const CheckCaption caption = checkCaption(gl, reasons);
    const TwoPanelLayout& layout = caption.layout;
    const render::CanvasOptions po = canvasOptions(layout.panelWidth(), layout.panelHeight(), 1);
    const auto panel = [&](const Json& answer, const std::string& heading) {
        Canvas cs(gl, po, panelCamera(false, center, radius, view, layout));
        const std::string region = answer.value("region", std::string());
        for (const TriangleRegionPolygon& r : diagram.regions) {
            if (r.vertices.size() < 3) continue;
            cs.drawPolygon(r.vertices, triangleRegionColor(int(r.region)).withAlpha(0.35f));
            Vec3 mid = Vec3::Zero();
            for (const Vec3& v : r.vertices) mid += v / double(r.vertices.size());
            TextStyle ts{18.0f, triangleRegionColor(int(r.region)).scaled(0.55f), Anchor::Center, true, true};
            ts.place = true;  // off the point markers and the other names
            cs.drawText(mid, nameOf(r.region), ts);
            if (region == nameOf(r.region) || (region == "AC" && r.region == TriangleRegion::CA))
                cs.drawPolyline(r.vertices, true, lineStyle(Role::Highlight, 3.5f, false, true));
        }
        cs.drawPolyline({tri.a, tri.b, tri.c}, true, lineStyle(Role::Ink, 2.5f, false, true));
        cs.drawPoint(p, 7.0f, roleColor(Role::Query), true, 1.5f, roleColor(Role::Ink));
        drawLabelAway(cs, p, center, "p", TextStyle{17.0f, roleColor(Role::Ink), Anchor::Center, true, true});
        if (isVec(answer.value("point", Json()))) {
            const Vec3 q = vec(answer["point"]);
            cs.drawLine(p, q, lineStyle(Role::Result, 2.5f, false, true));
            cs.drawPoint(q, 7.0f, roleColor(Role::Result), true, 1.5f, roleColor(Role::Ink));
            drawLabelAway(cs, q, p, "closest", TextStyle{17.0f, roleColor(Role::Ink), Anchor::Center, true, true});
        }
        // Your region name as the verdict line prints it (escaped, cut): it cannot draw lines of its own.
        std::string sub = region.empty() ? "no region" : "region " + printable(shortText(region));
        if (answer.contains("distance")) sub += ", distance " + number(answer["distance"]);
        drawPanelHeading(cs, heading, sub);
        return cs.readPixels();
    };
    const render::Image left = panel(cdlab, "cdlab's answer"), right = panel(yours, "your answer");
    render::writePngAtomic(path, composeTwoPanel(gl, layout, 1, title, "", left, right, caption.lines));
    return "";
}

std::string traceFigureRefusal(const Json& query) {
    std::string why;
    const std::optional<PairScene> pair = drawablePair(query, true, why);
    return pair ? minkowskiTooLarge(*pair) : why;
}

std::string writeTraceStepFigure(render::GlContext& gl, const Json& query, const Json& trace,
                                 const std::string& algorithm, int step, const std::string& title,
                                 const std::vector<std::string>& reasons, const std::string& path) {
    if (algorithm != "gjk" && algorithm != "epa") return "no figure for " + algorithm + " traces";
    std::string why;
    const std::optional<PairScene> pairRead = drawablePair(query, true, why);
    if (!pairRead) return why;
    if (const std::string tooLarge = minkowskiTooLarge(*pairRead); !tooLarge.empty()) return tooLarge;
    const Json yourTrace = traceOf(trace, algorithm);
    const bool epa = algorithm == "epa";
    const std::optional<StepPicture> mine = epa ? epaStepOf(yourTrace, step) : stepOf(yourTrace, step);
    if (!mine) return "no figure: your step " + std::to_string(step) + " could not be read";
    // cdlab's trace starts at its first iteration, with the first support (along the initial
    // direction) already in the simplex. A trace of yours whose step 0 keeps one point lists
    // that first support as a step of its own: cdlab's then gets one too, so step k is step k.
    const std::optional<StepPicture> first = stepOf(yourTrace, 0);
    std::optional<Vec3> initial;
    if (isVec(query.value("initial_direction", Json()))) initial = vec(query["initial_direction"]);
    const auto alignedStep = [&](Json steps) -> std::optional<StepPicture> {
        const Json start = steps.empty() ? Json() : steps[0].value("simplex", Json::array());
        if (first && first->simplex.size() == 1 && start.is_array() && !start.empty() && isVec(start[0])) {
            const Json d = initial ? vecJson(*initial) : start[0];
            steps.insert(steps.begin(), Json{{"direction", d}, {"support", start[0]}, {"simplex", {start[0]}}});
        }
        return stepOf(Json{{"steps", steps}}, step);
    };
    const bool spheres = pairRead->a.kind == SceneShape::Kind::Sphere || pairRead->b.kind == SceneShape::Kind::Sphere;
    if (spheres && epa) return "no figure: EPA trace steps are drawn for polytopes, aabbs and obbs";
    std::optional<StepPicture> theirs;
    if (spheres) {  // from your first direction, as the query would start with "initial_direction"
        if (!initial && first) initial = first->direction;
        theirs = alignedStep(fullShapeGjkSteps(query, initial));
    } else {
        Json q = query;
        q["trace"] = true;
        const Json answer = answerQuery(q.dump());
        if (answer.contains("trace") && answer["trace"].contains("algorithms"))
            for (const Json& alg : answer["trace"]["algorithms"]) {
                if (alg.value("algorithm", "") != algorithm || !alg.contains("steps") || alg["steps"].empty()) continue;
                theirs = epa ? epaStepOf(alg, step) : alignedStep(alg["steps"]);
            }
    }
    const PairScene& pair = *pairRead;
    std::vector<Vec3> frame;
    for (const std::optional<StepPicture>* s : {&mine, const_cast<const std::optional<StepPicture>*>(&theirs)}) {
        if (!*s) continue;
        frame.insert(frame.end(), (*s)->simplex.begin(), (*s)->simplex.end());
        frame.push_back((*s)->support);
        if ((*s)->epa) frame.push_back((*s)->distance * (*s)->direction.normalized());
    }
    std::vector<std::string> skipped;
    const PairDrawing d = makePairDrawing(pair, true, frame, skipped);
    const CheckCaption caption = checkCaption(gl, reasons);
    const TwoPanelLayout& layout = caption.layout;
    const render::CanvasOptions po = canvasOptions(layout.panelWidth(), layout.panelHeight(), 1);
    const auto panel = [&](const std::optional<StepPicture>& s, const std::string& heading) {
        Canvas cs(gl, po, panelCamera(false, d.cCenter, d.cRadius, pair.view, layout));
        if (s) drawStep(cs, d, *s);
        drawPanelHeading(cs, heading,
                         !s       ? "cdlab's run stopped before this step"
                         : s->epa ? "face at d = " + number(s->distance) + " along n, support w"
                                  : std::to_string(s->simplex.size()) + (s->simplex.size() == 1 ? " point" : " points") +
                                        " kept after the support w along d");
        return cs.readPixels();
    };
    const std::string k = std::to_string(step);
    const render::Image left = panel(theirs, "cdlab's step " + k + (spheres ? ", radius in the support" : "")),
                        right = panel(mine, "your step " + k);
    render::writePngAtomic(path, composeTwoPanel(gl, layout, 1, title, "", left, right, caption.lines));
    return "";
}

std::string writeCheckFigure(render::GlContext& gl, const Json& query, const Json& cdlab, const Json& yours,
                             const std::string& title, const std::vector<std::string>& reasons,
                             const std::string& path) {
    const std::string op = query.value("op", "");
    if (op != "intersect" && op != "distance" && op != "penetration" && op != "contact")
        return "no figure for op '" + op + "'";
    std::string why;
    const std::optional<PairScene> pairRead = drawablePair(query, false, why);
    if (!pairRead) return why;
    const PairScene& pair = *pairRead;
    std::vector<std::string> skipped;
    const PairDrawing d = makePairDrawing(pair, false, {}, skipped);

    const CheckCaption caption = checkCaption(gl, reasons);
    const TwoPanelLayout& layout = caption.layout;
    const render::CanvasOptions po = canvasOptions(layout.panelWidth(), layout.panelHeight(), 1);
    const bool colliding = cdlab.value("intersect", false) || cdlab.value("colliding", false) ||
                           (op == "penetration" && cdlab.value("depth", 0.0) > 0);
    const auto panel = [&](const Json& answer, const std::string& heading) {
        Canvas world(gl, po, panelCamera(false, d.wCenter, d.wRadius, pair.view, layout));
        drawPairBodies(world, d, 0.45f, colliding, true);
        drawAnswer(world, d, answer);
        drawPanelHeading(world, heading, summary(answer));
        return world.readPixels();
    };
    const render::Image left = panel(cdlab, "cdlab's answer"), right = panel(yours, "your answer");
    render::writePngAtomic(path, composeTwoPanel(gl, layout, 1, title, "", left, right, caption.lines));
    return "";
}

}  // namespace cdlab::demos
