#include "demos/check/check_figure.h"

#include <algorithm>

#include "demos/draw/convex_drawable.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/pair_figure.h"
#include "demos/query/query_shapes.h"
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
        default: return std::nullopt;
    }
}

bool isVec(const Json& j) {
    return j.is_array() && j.size() == 3 && std::all_of(j.begin(), j.end(), [](const Json& x) { return x.is_number(); });
}
Vec3 vec(const Json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

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

}  // namespace

std::string writeCheckFigure(render::GlContext& gl, const Json& query, const Json& cdlab, const Json& yours,
                             const std::string& title, const std::vector<std::string>& reasons,
                             const std::string& path) {
    const std::string op = query.value("op", "");
    if (op != "intersect" && op != "distance" && op != "penetration" && op != "contact")
        return "no figure for op '" + op + "'";
    if (!query.contains("a") || !query.contains("b")) return "no figure: the query has no shapes a and b";
    const std::optional<SceneShape> a = drawableShape(query["a"], "$.a"), b = drawableShape(query["b"], "$.b");
    if (!a || !b) return "no figure: it draws polytopes, aabbs, obbs and spheres";
    PairScene pair;
    pair.a = *a;
    pair.b = *b;
    std::vector<std::string> skipped;
    const PairDrawing d = makePairDrawing(pair, false, {}, skipped);

    // The reasons, cut to two caption lines of slide-legible length.
    std::vector<std::string> lines;
    for (const std::string& r : reasons) {
        if (lines.size() == 2) break;
        lines.push_back(r.size() > 110 ? r.substr(0, 107) + "..." : r);
    }
    const TwoPanelLayout layout = twoPanelLayout(1280, 640, "");
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
    render::writePngAtomic(path, composeTwoPanel(gl, layout, 1, title, "", left, right, lines));
    return "";
}

}  // namespace cdlab::demos
