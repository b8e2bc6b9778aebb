// The raycast family of the primitives demo: a ray or segment against a sphere (the quadratic,
// Ericson §5.3.2), an AABB or OBB (slabs, §5.3.3) or a triangle (barycentric weights, Möller &
// Trumbore 1997 / §5.3.6). The answers and the numbers that decide them come from core
// (core/overlap/intersect_ray.h with its traces); this file draws them.
#include <algorithm>
#include <cmath>

#include "core/closest/closest_point_box.h"
#include "core/overlap/intersect_ray.h"
#include "render/legibility.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/primitives/primitive_figures.h"
#include "demos/primitives/primitive_scenes.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

namespace {

using namespace render;

constexpr double kInf = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------------------------------- numbers

/// One cast: the core answer and, per shape, the trace of its deciding numbers.
struct CastRun {
    bool hit = false;
    double t = 0.0;  // first contact (hit only)
    Vec3 point = Vec3::Zero();
    SphereQuadraticTrace quadratic;  // sphere
    SlabTrace slabs;                 // aabb / obb (in the box's axes)
    RayBoxHit box;
    RayTriangleHit triangle;  // triangle
    // A triangle missed by a ray not parallel to its plane: where the ray's line meets the plane, at
    // planeT, with the weights (a, b, c) of that point — one negative, or planeT < 0.
    // primitives_demo_test "a miss by a negative weight".
    bool planeCrossing = false;
    double planeT = 0.0;
    Vec3 planePoint = Vec3::Zero(), planeWeights = Vec3::Zero();
};

CastRun runCast(const RaycastInput& in) {
    CastRun run;
    const PrimitiveShape& s = in.shape;
    const Ray ray{in.origin, in.direction};
    const Segment seg{in.origin, in.origin + in.direction};
    if (s.kind == PrimitiveShape::Kind::Sphere) {
        const Sphere sphere{s.vertices[0], s.radius};
        const RayHit h = in.segment ? intersectSegmentSphere(seg, sphere, &run.quadratic)
                                    : intersectRaySphere(ray, sphere, &run.quadratic);
        run.hit = h.hit;
        run.t = h.t;
    } else if (s.kind == PrimitiveShape::Kind::Triangle) {
        const Triangle tri{s.vertices[0], s.vertices[1], s.vertices[2]};
        run.triangle = in.segment ? intersectSegmentTriangle(seg, tri) : intersectRayTriangle(ray, tri);
        run.hit = run.triangle.hit;
        run.t = run.triangle.t;
        const Vec3 n = (tri.b - tri.a).cross(tri.c - tri.a);
        if (!run.hit && n.dot(in.direction) != 0) {
            run.planeCrossing = true;
            run.planeT = n.dot(tri.a - in.origin) / n.dot(in.direction);
            run.planePoint = in.origin + run.planeT * in.direction;
            const Vec3& q = run.planePoint;
            run.planeWeights = Vec3(n.dot((tri.b - q).cross(tri.c - q)), n.dot((tri.c - q).cross(tri.a - q)),
                                    n.dot((tri.a - q).cross(tri.b - q))) / n.squaredNorm();
        }
    } else {
        // An obb's slabs are its own axes: the cast in the box's frame, where it is an aabb (t unchanged).
        const Mat3 Rt = s.box.axes.transpose();
        const Vec3 o = Rt * (in.origin - s.box.center), d = Rt * in.direction;
        const Aabb local{-s.box.halfExtents, s.box.halfExtents};
        run.box = in.segment ? intersectSegmentAabb({o, o + d}, local, &run.slabs)
                             : intersectRayAabb({o, d}, local, &run.slabs);
        run.hit = run.box.hit;
        run.t = run.box.tEnter;
    }
    run.point = in.origin + run.t * in.direction;
    return run;
}


Json castJson(const RaycastInput& in, const CastRun& run) {
    Json j = {{"test", "raycast"},
              {"cast", in.segment ? "segment" : "ray"},
              {"origin", vec3Json(in.origin)},
              {"direction", vec3Json(in.direction)},
              {"shape", nameOf(in.shape.kind)},
              {"hit", run.hit}};
    if (run.hit) {
        j["t"] = run.t;
        j["point"] = vec3Json(run.point);
    }
    if (in.shape.kind == PrimitiveShape::Kind::Sphere) {
        const SphereQuadraticTrace& q = run.quadratic;
        j["quadratic"] = {{"a", q.a}, {"b", q.b}, {"c", q.c}, {"discriminant", q.discriminant},
                          {"outcome", nameOf(q.outcome)}};
        if (q.rootsValid) j["quadratic"]["roots"] = {q.t0, q.t1};
    } else if (in.shape.kind == PrimitiveShape::Kind::Triangle) {
        j["barycentric"] = vec3Json(run.triangle.barycentric);
        j["back_face"] = run.triangle.backFace;
        j["coplanar"] = run.triangle.coplanar;
        if (run.planeCrossing)
            j["plane_crossing"] = {{"t", run.planeT}, {"point", vec3Json(run.planePoint)}, {"weights", vec3Json(run.planeWeights)}};
    } else {
        Json slabs = Json::array();
        for (const SlabStep& s : run.slabs.steps)
            slabs.push_back({{"axis", s.axis},
                             {"parallel", s.parallel},
                             {"t_near", s.parallel ? Json(nullptr) : finiteOrNull(s.tNear)},
                             {"t_far", s.parallel ? Json(nullptr) : finiteOrNull(s.tFar)},
                             {"t_enter", finiteOrNull(s.tEnter)},
                             {"t_exit", finiteOrNull(s.tExit)},
                             {"rejected", s.rejected}});
        j["slabs"] = slabs;
        if (run.hit) {
            j["t_exit"] = run.box.tExit;
            j["enter_axis"] = run.box.enterAxis;
        }
    }
    return j;
}

// ------------------------------------------------------------------------------------ drawing

TextStyle pointLabel(float size = 20.0f) {
    TextStyle ts{size, roleColor(Role::Ink), Anchor::Center, true, false};
    ts.offsetPx = Eigen::Vector2d(0, -22);
    ts.place = true;
    return ts;
}

/// The cast drawn from its origin to `tEnd` (an arrow for a ray, the segment with its end point),
/// with the origin named; the line behind the origin dashed when `behind` > 0.
void drawCast(Canvas& c, const RaycastInput& in, double tEnd, double behind) {
    const Vec3 end = in.origin + tEnd * in.direction;
    if (behind > 0) c.drawLine(in.origin - behind * in.direction, in.origin, lineStyle(Role::Muted, 2.0f, true));
    if (in.segment) c.drawLine(in.origin, end, lineStyle(Role::Ink, 3.5f));
    else c.drawArrow(in.origin, end, lineStyle(Role::Ink, 3.5f));
    c.drawPoint(in.origin, 7.0f, roleColor(Role::Query));
    c.drawText(in.origin, in.segment ? "p (t = 0)" : "o (t = 0)", pointLabel());
    if (in.segment) {
        c.drawPoint(end, 7.0f, roleColor(Role::Query));
        c.drawText(end, "q (t = 1)", pointLabel());
    }
}

/// How far the drawn cast goes: the segment's end, or a ray past the last point of interest.
double drawnEnd(const RaycastInput& in, double lastOfInterest, double size) {
    if (in.segment) return 1.0;
    return std::max(lastOfInterest, 0.0) + 0.35 * size / in.direction.norm();
}

/// The hit point, in the answer's colour.
void drawHit(Canvas& c, const CastRun& run, const std::string& label) {
    if (!run.hit) return;
    c.drawPoint(run.point, 11.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));
    TextStyle ts = pointLabel(22.0f);
    ts.bold = true;
    ts.offsetPx = Eigen::Vector2d(0, 30);
    c.drawText(run.point, label, ts);
}

std::string verdict(const CastRun& run) {
    if (!run.hit) return "no hit";
    return "hit at t = " + formatNumber(run.t) + ", point " + formatPoint(run.point);
}

// ---------------------------------------------------------------------------------- sphere

/// The plane of the ray and the sphere's centre, seen face on: the sphere's outline there is its
/// great circle, and the line's two crossings with it are the quadratic's roots.
Frame sphereFrame(GlContext& gl, const SceneCommon& scene, int scale, const RaycastInput& in, const CastRun& run) {
    const Vec3 c0 = in.shape.vertices[0];
    const double r = in.shape.radius;
    const Vec3 d = in.direction.normalized();
    Vec3 n = d.cross(c0 - in.origin);
    if (n.norm() <= 1e-9 * ((c0 - in.origin).norm() + r)) n = d.unitOrthogonal();
    n.normalize();
    const Vec3 up = n.cross(d);
    const SphereQuadraticTrace& q = run.quadratic;
    const double tc = (c0 - in.origin).dot(in.direction) / in.direction.squaredNorm();  // closest approach
    const double size = std::max({r, (c0 - in.origin).norm(), 1e-3});
    const double tEnd = drawnEnd(in, std::max(q.rootsValid ? q.t1 : tc, tc), size);
    const double behind = q.rootsValid && q.t0 < 0 ? -q.t0 + 0.15 * size / in.direction.norm() : 0.0;
    // Frame everything drawn: the circle, the cast and the part behind its origin.
    std::vector<Vec3> drawn = {c0 + r * up, c0 - r * up, c0 + r * d, c0 - r * d, in.origin,
                               in.origin + tEnd * in.direction, in.origin - behind * in.direction};
    if (q.rootsValid) drawn.push_back(in.origin + q.t1 * in.direction);
    Canvas canvas(gl, canvasOptions(scene.image.width, scene.image.height, scale));
    canvas.setCamera(scene.camera ? *scene.camera : viewAbove(drawn, n, up, 0.7, scene.image.width, scene.image.height));
    std::vector<Vec3> circle;
    for (int i = 0; i < 144; ++i) {
        const double a = 2 * M_PI * i / 144;
        circle.push_back(c0 + r * (std::cos(a) * d + std::sin(a) * up));
    }
    canvas.drawPolygon(circle, roleColor(Role::ShapeA).withAlpha(0.22f));
    canvas.drawPolyline(circle, true, lineStyle(Role::ShapeA, 3.0f));
    canvas.drawPoint(c0, 5.0f, roleColor(Role::Ink));
    const bool labels = scene.hasLayer("labels");
    if (labels) canvas.drawText(c0, "C", pointLabel(22.0f));
    // The radius and the closest approach of the line, for the discriminant: b² − ac = a(r² − dist²).
    const Vec3 closest = in.origin + tc * in.direction;
    // In ink and named: a grey dashed 25-px segment read as two faint dashes (the review).
    // Named on the picture only where it is seen (12 px, the quantity rule); shorter, the footer
    // gives its value alone (segment_sphere_short: 0.04, 7 px).
    canvas.drawLine(c0, closest, lineStyle(Role::Ink, 2.5f, false, true));
    Eigen::Vector2d pc, pq;
    const bool seen = canvas.project(c0, pc) && canvas.project(closest, pq) && (pq - pc).norm() >= kMinQuantityPx;
    if (labels && seen) {
        canvas.noteQuantity("dist", c0, closest);
        TextStyle ts = pointLabel();
        const Vec3 along = in.direction.normalized();
        Eigen::Vector2d a, b;
        if (canvas.project(0.5 * (c0 + closest), a) && canvas.project(0.5 * (c0 + closest) + along, b))
            ts.offsetPx = 30.0 * Eigen::Vector2d((b - a).normalized());  // beside it, along the line
        canvas.drawText(0.5 * (c0 + closest), "dist", ts);
    }
    if (q.rootsValid && in.segment) {  // the segment's line, dashed, out to the roots past its end
        const double from = std::min(0.0, q.t0), to = std::max(1.0, q.t1);
        canvas.drawLine(in.origin + from * in.direction, in.origin + to * in.direction, lineStyle(Role::Muted, 2.0f, true));
    }
    drawCast(canvas, in, tEnd, behind);
    if (q.rootsValid) {
        for (int k = 0; k < 2; ++k) {
            const double t = k == 0 ? q.t0 : q.t1;
            const Vec3 p = in.origin + t * in.direction;
            canvas.drawPoint(p, 7.0f, roleColor(Role::Direction));
            if (labels && !(run.hit && k == 0 && q.outcome == SphereQuadraticTrace::Outcome::Hit))
                canvas.drawText(p, (k == 0 ? "t0 = " : "t1 = ") + formatNumber(t), pointLabel());
        }
    }
    if (labels)
        drawHit(canvas, run,
                q.outcome == SphereQuadraticTrace::Outcome::StartsInside ? "inside: t = 0"
                                                                          : "t0 = " + formatNumber(run.t) + " (hit)");
    if (scene.hasLayer("numbers")) {
        const Vec3 m = in.origin - c0;
        std::vector<std::string> lines = {
            std::string(in.segment ? "m = p − C = " : "m = o − C = ") + formatPoint(m) + ";  a = d·d = " + formatNumber(q.a) + ";  b = m·d = " + formatNumber(q.b) +
                ";  c = m·m − r² = " + formatNumber(q.c),
            "discriminant b² − a·c = " + formatNumber(q.discriminant) +
                (q.rootsValid ? ";  roots (−b ± √(b² − ac)) / a:  t0 = " + formatNumber(q.t0) +
                                    ",  t1 = " + formatNumber(q.t1)
                              : ";  < 0: the line misses the sphere"),
        };
        // The discriminant's meaning: b² − ac = a·(r² − dist²), dist the line's closest approach to C.
        lines.push_back("b² − a·c = a·(r² − dist²):  the line passes C at dist = " + formatNumber((closest - c0).norm()) +
                        ", r = " + formatNumber(r));
        using O = SphereQuadraticTrace::Outcome;
        std::string decision = "decision: ";
        switch (q.outcome) {
            case O::StartsInside: decision += "c ≤ 0, the origin is inside: hit at t = 0"; break;
            case O::PointsAway: decision += "c > 0 and b > 0: outside and moving away, no hit"; break;
            case O::NoRealRoot: decision += "b² − ac < 0: no real root, no hit"; break;
            case O::BeyondEnd: decision += "t0 > 1: the sphere is past the segment's end, no hit"; break;
            case O::Hit: decision += "t0 ≥ 0 is the first contact"; break;
            case O::PointOutside: decision += "a = 0: the segment is a point outside"; break;
            case O::Invalid: decision += "invalid input"; break;
        }
        lines.push_back(run.hit ? decision + ";  " + verdict(run) : decision);
        drawNumberBlock(canvas, lines, 52);
    }
    return finishedFrame(canvas, scene.title, scene.caption, "cast", scene.title + ": " + verdict(run));
}

// ---------------------------------------------------------------------------------- triangle

Frame triangleFrame(GlContext& gl, const SceneCommon& scene, int scale, const RaycastInput& in, const CastRun& run) {
    const Vec3 v[3] = {in.shape.vertices[0], in.shape.vertices[1], in.shape.vertices[2]};
    const Vec3 centroid = (v[0] + v[1] + v[2]) / 3.0;
    Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
    if (n.squaredNorm() == 0) n = in.direction.unitOrthogonal();
    n.normalize();
    if (n.dot(in.origin - centroid) < 0) n = -n;  // seen from the cast's side
    double size = 0;
    for (const Vec3& p : v) size = std::max(size, (p - centroid).norm());
    size = std::max({size, (in.origin - centroid).norm() * 0.5, 1e-3});
    const double tShown = run.hit ? run.t
                          : run.planeCrossing && run.planeT > 0 ? run.planeT
                                                                : (centroid - in.origin).dot(in.direction) / in.direction.squaredNorm();
    const double tEnd = drawnEnd(in, tShown, size);
    const std::vector<Vec3> drawn = {v[0], v[1], v[2], in.origin, in.origin + tEnd * in.direction};
    const Vec3 e1 = (v[1] - v[0]).normalized();
    const Vec3 view = (n + 0.55 * e1 + 0.35 * n.cross(e1)).normalized();
    Canvas canvas(gl, canvasOptions(scene.image.width, scene.image.height, scale));
    canvas.setCamera(scene.camera ? *scene.camera
                                  : viewAbove(drawn, view, n.cross(e1), 0.74, scene.image.width, scene.image.height));
    const bool labels = scene.hasLayer("labels");
    const char* names[3] = {"a", "b", "c"};
    if (run.hit || run.planeCrossing) {
        // The weight of a vertex is the area of the sub-triangle opposite it over the whole (signed:
        // a miss's plane point outside an edge makes that edge's sub-triangle negative).
        const Vec3 w = run.hit ? run.triangle.barycentric : run.planeWeights;
        const Vec3 q = run.hit ? run.point : run.planePoint;
        if (!run.hit) canvas.drawPolygon({v[0], v[1], v[2]}, roleColor(Role::ShapeA).withAlpha(0.2f));
        for (int k = 0; k < 3; ++k) {
            std::vector<Vec3> sub = {v[0], v[1], v[2]};
            sub[std::size_t(k)] = q;
            canvas.drawPolygon(sub, categorical(2 * k).withAlpha(0.35f));
            if (labels) {
                TextStyle ts{19.0f, categorical(2 * k).scaled(0.55f), Anchor::Center, true, true};
                ts.place = true;
                canvas.drawText((sub[0] + sub[1] + sub[2]) / 3.0, std::string("w_") + names[k] + " = " + formatNumber(w[k]), ts);
            }
        }
    } else {
        canvas.drawPolygon({v[0], v[1], v[2]}, roleColor(Role::ShapeA).withAlpha(0.25f));
    }
    canvas.drawPolyline({v[0], v[1], v[2]}, true, lineStyle(Role::ShapeA, 3.0f));
    if (labels)
        for (int k = 0; k < 3; ++k) drawLabelAway(canvas, v[k], centroid, names[k], labelStyle(Role::Ink, 26.0f), 14.0);
    if (run.hit) {
        // Past the hit the cast runs behind the triangle (the view is from the cast's side): dashed.
        canvas.drawLine(run.point, in.origin + tEnd * in.direction, lineStyle(Role::Muted, 2.5f, true));
        canvas.drawLine(in.origin, run.point, lineStyle(Role::Ink, 3.5f));
        canvas.drawPoint(in.origin, 7.0f, roleColor(Role::Query));
        canvas.drawText(in.origin, in.segment ? "p (t = 0)" : "o (t = 0)", pointLabel());
    } else {
        drawCast(canvas, in, tEnd, 0.0);
        if (run.planeCrossing) {
            canvas.drawPoint(run.planePoint, 6.0f, roleColor(Role::Muted));
            if (labels) canvas.drawText(run.planePoint, "plane point, t = " + formatNumber(run.planeT), pointLabel());
        }
    }
    if (labels) drawHit(canvas, run, "t = " + formatNumber(run.t));
    if (scene.hasLayer("numbers")) {
        std::vector<std::string> lines;
        if (run.hit) {
            const Vec3 w = run.triangle.barycentric;
            lines.push_back("point = a·w_a + b·w_b + c·w_c = o + t·d;  weights (w_a, w_b, w_c) = (" + formatNumber(w[0]) +
                            ", " + formatNumber(w[1]) + ", " + formatNumber(w[2]) + "), all ≥ 0, sum 1");
            lines.push_back(std::string("the ray meets the ") + (run.triangle.backFace ? "back" : "front") +
                            " face (n = (b − a) × (c − a))" + (run.triangle.coplanar ? ", lying in its plane" : "") +
                            ";  " + verdict(run));
        } else {
            if (run.planeCrossing) {
                const Vec3 w = run.planeWeights;
                int k = 0;
                w.minCoeff(&k);
                const char* edge[3] = {"bc", "ca", "ab"};
                lines.push_back("the line meets the plane at t = " + formatNumber(run.planeT) + ";  weights (w_a, w_b, w_c) = (" +
                                formatNumber(w[0]) + ", " + formatNumber(w[1]) + ", " + formatNumber(w[2]) + ")" +
                                (w[k] < 0 ? std::string(":  w_") + names[k] + " < 0, beyond edge " + edge[k] : std::string()));
            }
            lines.push_back("the signs of the triple products [d, b − o, c − o], [d, c − o, a − o], [d, a − o, b − o] "
                            "differ from the sign of d·n (or t < 0): no hit");
        }
        drawNumberBlock(canvas, lines, 52);
    }
    return finishedFrame(canvas, scene.title, scene.caption, "cast", scene.title + ": " + verdict(run));
}

// ------------------------------------------------------------------------------------- slabs

/// A miss seen across its gap: the view perpendicular to the shortest segment between the drawn
/// cast (t in [0, tEnd], sampled) and the box, so the cast passes beside the box on the picture,
/// not across it (the review: ray_aabb_miss read as a pass-through); turned towards the usual
/// view about that segment.
Vec3 viewAcrossMiss(const RaycastInput& in, double tEnd) {
    const Vec3 usual = Vec3(1.0, 0.8, 1.7).normalized();
    const Obb& box = in.shape.box;
    Vec3 gap = Vec3::Zero();
    double best = kInf;
    for (int k = 0; k <= 4096; ++k) {
        const Vec3 p = in.origin + (tEnd * k / 4096.0) * in.direction;
        const BoxRegionResult q = closestPointOnBox(p, box);
        if (q.valid && q.distance < best) best = q.distance, gap = p - q.point;
    }
    if (!(gap.norm() > 0) || !(in.direction.norm() > 0)) return usual;
    const Vec3 g = gap.normalized();
    Vec3 across = in.direction.normalized().cross(g);
    if (!(across.norm() > 1e-9)) return usual;
    across.normalize();
    if (across.dot(usual) < 0) across = -across;
    const Vec3 towards = usual - usual.dot(g) * g;  // the usual view, less its part along the gap
    const Vec3 v = across + 0.5 * towards;
    return v.norm() > 1e-9 ? Vec3(v.normalized()) : across;
}

/// The box and the cast in 3D: entry and exit points on the box.
Image boxPicture(GlContext& gl, const SceneCommon& scene, int scale, int height, const RaycastInput& in,
                 const CastRun& run) {
    const Obb& box = in.shape.box;
    const double size = std::max(box.halfExtents.norm(), 1e-3);
    double last = run.hit ? run.box.tExit : 0.0;
    if (!run.hit)
        for (const SlabStep& s : run.slabs.steps)
            if (!s.parallel) last = std::max({last, s.tNear, s.tFar});
    const double tEnd = drawnEnd(in, last, size);
    std::vector<Vec3> drawn = boxDrawable(box).vertices;
    drawn.push_back(in.origin);
    drawn.push_back(in.origin + tEnd * in.direction);
    Canvas canvas(gl, canvasOptions(scene.image.width, height, scale));
    canvas.setCamera(scene.camera ? *scene.camera
                                  : viewAbove(drawn, run.hit ? Vec3(1.0, 0.8, 1.7) : viewAcrossMiss(in, tEnd),
                                              Vec3::UnitY(), 1.0, scene.image.width, height));
    drawBody(canvas, boxDrawable(box), roleColor(Role::ShapeA), 0.22f, roleColor(Role::ShapeA).scaled(0.7f), 3.0f);
    drawCast(canvas, in, tEnd, 0.0);
    if (run.hit && run.box.tExit > run.t) {
        // Inside the box the cast runs behind its entry face: dashed over the solid line.
        LineStyle inside = lineStyle(Role::Background, 3.5f, true, true);
        canvas.drawLine(run.point, in.origin + run.box.tExit * in.direction, inside);
    }
    if (!run.hit && scene.hasLayer("labels")) {
        // Where the running interval and the slab that empties it part: the two values of t that miss.
        double prevEnter = 0.0, prevExit = in.segment ? 1.0 : kInf;
        for (const SlabStep& s : run.slabs.steps) {
            if (s.rejected && !s.parallel) {
                const double lo = std::min(s.tNear, s.tFar), hi = std::max(s.tNear, s.tFar);
                const double a = lo > prevExit ? prevExit : hi, b = lo > prevExit ? lo : prevEnter;
                for (double t : {a, b})
                    if (std::isfinite(t)) {
                        const Vec3 p = in.origin + t * in.direction;
                        canvas.drawPoint(p, 7.0f, roleColor(Role::Direction));
                        canvas.drawText(p, "t = " + formatNumber(t), pointLabel());
                    }
                break;
            }
            prevEnter = s.tEnter;
            prevExit = s.tExit;
        }
    }
    if (run.hit && scene.hasLayer("labels")) {
        const Vec3 exit = in.origin + run.box.tExit * in.direction;
        canvas.drawPoint(exit, 7.0f, roleColor(Role::Direction));
        canvas.drawText(exit, "t_exit = " + formatNumber(run.box.tExit), pointLabel());
        drawHit(canvas, run, run.box.enterAxis < 0 ? "inside: t = 0" : "t_enter = " + formatNumber(run.t));
    }
    drawTitleAndCaption(canvas, scene.title, "");
    return canvas.readPixels();
}

/// The slab intervals on a t axis, one row per axis, then their intersection (Ericson §5.3.3).
/// Round tick values (steps of 1, 2 or 5 times a power of ten) covering [lo, hi].
std::vector<double> niceTicks(double lo, double hi) {
    const double raw = (hi - lo) / 5.0;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    double step = power;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * power >= raw) {
            step = m * power;
            break;
        }
    std::vector<double> ticks;
    for (double t = std::floor(lo / step) * step; t <= hi + 0.5 * step; t += step) ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
    if (ticks.back() < hi) ticks.push_back(ticks.back() + step);
    return ticks;
}

Image slabDiagram(GlContext& gl, const SceneCommon& scene, int scale, int height, const RaycastInput& in,
                  const CastRun& run) {
    const int W = scene.image.width, H = height;
    Canvas c(gl, canvasOptions(W, H, scale), Camera::pixels(W, H));  // world = pixels, y up
    const bool obb = in.shape.kind == PrimitiveShape::Kind::Obb;
    double lo = 0.0, hi = in.segment ? 1.0 : 0.0;
    for (const SlabStep& s : run.slabs.steps)
        if (!s.parallel)
            for (double t : {s.tNear, s.tFar}) {
                lo = std::min(lo, t);
                hi = std::max(hi, t);
            }
    if (!(hi > lo)) hi = lo + 1.0;
    const std::vector<double> ticks = niceTicks(lo, hi);
    lo = ticks.front();
    hi = ticks.back();
    const double x0 = 400, x1 = W - 50;
    auto X = [&](double t) { return x0 + (std::clamp(t, lo, hi) - lo) / (hi - lo) * (x1 - x0); };
    auto P = [](double x, double y) { return Vec3(x, y, 0); };
    const double rowH = 40, top = H - 30;
    const TextStyle rowText{kNumberTextPx, roleColor(Role::Ink), Anchor::Left, true, false};
    const char* axisNames[3] = {"x", "y", "z"};
    int row = 0;
    auto bar = [&](double a, double b, double y, Role role) {
        c.drawLine(P(X(a), y), P(X(b), y), lineStyle(role, 12.0f));
    };
    bool rejected = false;
    std::string rejectedBy;
    c.drawText(P(170, top - 0.5 * rowH + 22), "interval of t", TextStyle{kNumberTextPx, roleColor(Role::Ink), Anchor::Left, true, true});
    for (const SlabStep& s : run.slabs.steps) {
        const double y = top - rowH * (row++ + 0.5);
        const std::string name = obb ? "box axis " + std::to_string(s.axis + 1) : std::string(axisNames[s.axis]) + " slab";
        c.drawText(P(20, y), name, rowText);
        if (s.parallel) {
            c.drawText(P(x0, y),
                       std::string("parallel: the origin is ") + (s.rejected ? "outside the slab, no hit" : "inside it, every t"),
                       rowText);
        } else {
            bar(std::min(s.tNear, s.tFar), std::max(s.tNear, s.tFar), y, Role::Direction);
            c.drawText(P(170, y),
                       "[" + formatNumber(std::min(s.tNear, s.tFar)) + ", " + formatNumber(std::max(s.tNear, s.tFar)) + "]",
                       rowText);

        }
        if (s.rejected) {
            rejected = true;
            rejectedBy = name;
            break;
        }
    }
    const double y = top - rowH * (row + 0.5);
    c.drawText(P(20, y), "inside the box", TextStyle{kNumberTextPx, roleColor(Role::Ink), Anchor::Left, true, true});
    if (run.hit) {
        bar(run.box.tEnter, run.box.tExit, y, Role::Result);
        c.drawText(P(170, y), "[" + formatNumber(run.box.tEnter) + ", " + formatNumber(run.box.tExit) + "]", rowText);
    } else if (rejected) {
        c.drawText(P(170, y), "empty after the " + rejectedBy + ": no hit", rowText);
    } else {
        c.drawText(P(170, y), "empty: the overlap lies outside the cast's range of t", rowText);
    }
    // The t axis under the rows, with t = 0 (and t = 1 for a segment) marked.
    const double ay = y - 34;
    c.drawLine(P(x0, ay), P(x1, ay), lineStyle(Role::Ink, 2.0f));
    const TextStyle tick{16.0f, roleColor(Role::Ink), Anchor::Top, false, false};
    for (double t : ticks) {
        c.drawLine(P(X(t), ay), P(X(t), ay - 6), lineStyle(Role::Ink, 2.0f));
        c.drawText(P(X(t), ay - 10), formatNumber(t), tick);
    }
    c.drawLine(P(X(0.0), ay + 4), P(X(0.0), top), lineStyle(Role::Muted, 1.5f, true));
    if (in.segment) c.drawLine(P(X(1.0), ay + 4), P(X(1.0), top), lineStyle(Role::Muted, 1.5f, true));
    c.drawText(P(20, ay), "t", TextStyle{kNumberTextPx, roleColor(Role::Ink), Anchor::Left, true, true});
    drawTitleAndCaption(c, "", scene.caption);
    return c.readPixels();
}

Frame slabFrame(GlContext& gl, const SceneCommon& scene, int scale, const RaycastInput& in, const CastRun& run) {
    const int rows = int(run.slabs.steps.size()) + 1;
    const int diagramH = int(40 * rows + 30 + 110);
    const int pictureH = scene.image.height - diagramH;
    Frame f;
    f.name = "cast";
    f.caption = scene.title + ": " + verdict(run);
    if (!scene.hasLayer("numbers")) {
        f.image = boxPicture(gl, scene, scale, scene.image.height, in, run);
        return f;
    }
    f.image = stackVertically(boxPicture(gl, scene, scale, pictureH, in, run),
                              slabDiagram(gl, scene, scale, diagramH, in, run));
    return f;
}

}  // namespace

DemoOutput runRaycast(const SceneCommon& scene, const RaycastInput& in, const RunContext& ctx) {
    const CastRun run = runCast(in);
    DemoOutput out;
    out.trace = castJson(in, run);
    if (numericOnly(ctx, out)) return out;
    const int scale = figureScale(scene, ctx);
    switch (in.shape.kind) {
        case PrimitiveShape::Kind::Sphere: out.frames.push_back(sphereFrame(*ctx.gl, scene, scale, in, run)); break;
        case PrimitiveShape::Kind::Triangle: out.frames.push_back(triangleFrame(*ctx.gl, scene, scale, in, run)); break;
        default: out.frames.push_back(slabFrame(*ctx.gl, scene, scale, in, run)); break;
    }
    return out;
}

}  // namespace cdlab::demos
