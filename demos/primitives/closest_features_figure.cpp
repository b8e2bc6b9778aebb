// The closest-features family of the primitives demo: simplex vs simplex (point, segment, triangle,
// tetrahedron) — which feature pair is closest, its closest points and distance, by trying every
// pair (core/closest/simplex_pair.h), and GJK's distance beside it as the check the trace records.
#include <algorithm>
#include <cmath>

#include "core/closest/simplex_pair.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/primitives/primitive_figures.h"
#include "demos/primitives/primitive_scenes.h"
#include "app/scene/json_reader.h"

namespace cdlab::demos {

namespace {

using namespace render;
using K = PrimitiveShape::Kind;

struct FeaturesRun {
    SimplexPairResult result;
    std::vector<SimplexPairCandidate> candidates;
    GjkResult gjk;
};

FeaturesRun runFeatures(const ClosestFeaturesInput& in) {
    FeaturesRun run;
    run.result = closestFeaturesOfSimplices(in.a.vertices, in.b.vertices, &run.candidates);
    run.gjk = gjkDistance(PolytopeShape(in.a.vertices), PolytopeShape(in.b.vertices));
    return run;
}

/// "edge a0a1", "face b0b1b2", "vertex a2", "inside of a" (its vertices named by the body's letter).
std::string featureName(const SimplexFeature& f, char body) {
    static const char* kKinds[4] = {"vertex ", "edge ", "face ", "inside of "};
    std::string name = kKinds[std::clamp(f.dimension(), 0, 3)];
    if (f.dimension() == 3) return name + body;
    for (int i : f.vertices) name += std::string(1, body) + std::to_string(i);
    return name;
}


Json featuresJson(const ClosestFeaturesInput& in, const FeaturesRun& run) {
    const SimplexPairResult& r = run.result;
    Json runnersUp = Json::array();
    for (std::size_t k = 0; k < run.candidates.size() && runnersUp.size() < 5; ++k)
        runnersUp.push_back({{"a", featureName(run.candidates[k].a, 'a')},
                             {"b", featureName(run.candidates[k].b, 'b')},
                             {"distance", run.candidates[k].distance}});
    const double gjkDistance = run.gjk.intersect() ? 0.0 : run.gjk.distance;
    return {{"test", "closest_features"},
            {"a", nameOf(in.a.kind)},
            {"b", nameOf(in.b.kind)},
            {"intersect", r.intersect},
            {"distance", r.distance},
            {"point_a", vec3Json(r.pointA)},
            {"point_b", vec3Json(r.pointB)},
            {"feature_a", featureName(r.featureA, 'a')},
            {"feature_b", featureName(r.featureB, 'b')},
            {"pairs_tested", r.pairsTested},
            {"nearest_pairs", runnersUp},
            {"gjk", {{"intersect", run.gjk.intersect()}, {"distance", gjkDistance},
                     {"difference", std::abs(gjkDistance - r.distance)}}}};
}

void drawSimplex(Canvas& c, const PrimitiveShape& s, Role role) {
    const std::vector<Vec3>& v = s.vertices;
    if (s.kind == K::Tetrahedron) {
        c.drawMesh(v, {Eigen::Vector3i(0, 2, 1), Eigen::Vector3i(0, 1, 3), Eigen::Vector3i(0, 3, 2), Eigen::Vector3i(1, 2, 3)},
                   roleColor(role).withAlpha(0.22f), true);
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) c.drawLine(v[std::size_t(i)], v[std::size_t(j)], lineStyle(role, 2.5f));
    } else if (s.kind == K::Triangle) {
        c.drawPolygon(v, roleColor(role).withAlpha(0.3f), true);
        c.drawPolyline(v, true, lineStyle(role, 2.5f));
    } else if (s.kind == K::Segment) {
        c.drawLine(v[0], v[1], lineStyle(role, 4.0f));
    }
    for (const Vec3& p : v) c.drawPoint(p, 5.0f, roleColor(role));
}

/// The closest feature, over its simplex: a vertex ringed, an edge thick, a face tinted.
void drawFeature(Canvas& c, const PrimitiveShape& s, const SimplexFeature& f) {
    std::vector<Vec3> pts;
    for (int i : f.vertices) pts.push_back(s.vertices[std::size_t(i)]);
    const Color hi = roleColor(Role::Simplex);
    if (pts.size() == 1) c.drawPoint(pts[0], 11.0f, hi, true, 2.0f, roleColor(Role::Ink));
    else if (pts.size() == 2) c.drawLine(pts[0], pts[1], lineStyle(Role::Simplex, 7.0f, false, true));
    else if (pts.size() == 3) {
        c.drawPolygon(pts, hi.withAlpha(0.35f));
        c.drawPolyline(pts, true, lineStyle(Role::Simplex, 4.0f, false, true));
    }
}

/// How much of a simplex's faces a view along v shows: the largest |n·v| over its triangles' unit
/// normals (a point or segment: 1, nothing to hide).
double faceVisibility(const PrimitiveShape& s, const Vec3& v) {
    const std::vector<Vec3>& p = s.vertices;
    if (p.size() < 3) return 1.0;
    double best = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = i + 1; j < p.size(); ++j)
            for (std::size_t k = j + 1; k < p.size(); ++k) {
                const Vec3 n = (p[j] - p[i]).cross(p[k] - p[i]);
                if (n.norm() > 0) best = std::max(best, std::abs(n.normalized().dot(v)));
            }
    return best;
}

/// The view: across the line of the closest points (their gap shows as a gap), turned about that
/// line to where both simplices show a face best (a triangle seen edge-on reads as a segment).
Vec3 faceOnViewAcross(const ClosestFeaturesInput& in, const SimplexPairResult& r) {
    const Vec3 fallback(1.0, 0.8, 1.7);
    const Vec3 gap = r.pointB - r.pointA;
    if (!r.valid) return fallback;
    if (r.intersect || !(gap.norm() > 0)) {
        // Touching or crossing: no gap to look across; the direction (of 64 spread over a half
        // sphere, Fibonacci) from which both show a face best.
        Vec3 best = fallback;
        double bestScore = std::min(faceVisibility(in.a, fallback.normalized()), faceVisibility(in.b, fallback.normalized()));
        for (int k = 0; k < 64; ++k) {
            const double z = 1.0 - (k + 0.5) / 64.0, rho = std::sqrt(1.0 - z * z), phi = k * 2.399963229728653;
            const Vec3 v(rho * std::cos(phi), 0.3 + 0.7 * z, rho * std::sin(phi));  // from above the horizon
            const double score = std::min(faceVisibility(in.a, v.normalized()), faceVisibility(in.b, v.normalized()));
            if (score > bestScore + 1e-3) bestScore = score, best = v;
        }
        return best;
    }
    const Vec3 g = gap.normalized();
    const Vec3 u1 = viewAcross(fallback, g).normalized();
    const Vec3 u2 = g.cross(u1);
    Vec3 best = u1;
    double bestScore = -1.0;
    for (int k = 0; k < 24; ++k) {  // every 15°, preferring the default side on ties
        const double angle = M_PI * k / 12.0;
        const Vec3 v = std::cos(angle) * u1 + std::sin(angle) * u2;
        const double score = std::min(faceVisibility(in.a, v), faceVisibility(in.b, v)) - 1e-3 * (k > 12 ? 24 - k : k);
        if (score > bestScore) bestScore = score, best = v;
    }
    return best;
}

Frame featuresFrame(GlContext& gl, const SceneCommon& scene, int scale, const ClosestFeaturesInput& in,
                    const FeaturesRun& run) {
    const SimplexPairResult& r = run.result;
    std::vector<Vec3> drawn = in.a.vertices;
    drawn.insert(drawn.end(), in.b.vertices.begin(), in.b.vertices.end());
    const Vec3 view = faceOnViewAcross(in, r);
    Canvas c(gl, canvasOptions(scene.image.width, scene.image.height, scale));
    c.setCamera(scene.camera ? *scene.camera : viewAbove(drawn, view, Vec3::UnitY(), 0.72, scene.image.width, scene.image.height));
    drawSimplex(c, in.a, Role::ShapeA);
    drawSimplex(c, in.b, Role::ShapeB);
    if (r.valid && r.featureA.dimension() < 3) drawFeature(c, in.a, r.featureA);
    if (r.valid && r.featureB.dimension() < 3) drawFeature(c, in.b, r.featureB);
    const bool labels = scene.hasLayer("labels");
    if (labels) {
        for (const auto& [s, letter] : {std::pair{&in.a, 'a'}, std::pair{&in.b, 'b'}}) {
            Vec3 centre = Vec3::Zero();
            for (const Vec3& p : s->vertices) centre += p;
            centre /= double(s->vertices.size());
            for (std::size_t i = 0; i < s->vertices.size(); ++i)
                drawLabelAway(c, s->vertices[i], centre, std::string(1, letter) + std::to_string(i), labelStyle(Role::Ink, 22.0f),
                              14.0);
        }
    }
    if (r.valid && r.intersect) c.drawPoint(r.pointA, 9.0f, roleColor(Role::Result), true, 2.0f, roleColor(Role::Ink));  // where they meet
    if (r.valid && !r.intersect) {
        c.drawLine(r.pointA, r.pointB, lineStyle(Role::Result, 3.0f, true, true));
        c.drawPoint(r.pointA, 7.0f, roleColor(Role::Result));
        c.drawPoint(r.pointB, 7.0f, roleColor(Role::Result));
        if (labels) {
            TextStyle ts{19.0f, roleColor(Role::Ink), Anchor::Center, true, true};
            ts.offsetPx = Eigen::Vector2d(0, 26);
            ts.place = true;
            c.drawText(0.5 * (r.pointA + r.pointB), "distance " + formatNumber(r.distance), ts);
        }
    }
    // A simplex that is its own closest feature is drawn all in the feature colour: its own
    // colour is not in the picture, so not in the key (the review: a blue "simplex a" not drawn).
    const auto wholly = [&](const PrimitiveShape& s, const auto& feature) {
        return r.valid && feature.dimension() < 3 && std::size_t(feature.dimension() + 1) == s.vertices.size();
    };
    std::vector<KeyItem> key;
    if (!wholly(in.a, r.featureA)) key.push_back({roleColor(Role::ShapeA), "simplex a"});
    if (!wholly(in.b, r.featureB)) key.push_back({roleColor(Role::ShapeB), "simplex b"});
    key.push_back({roleColor(Role::Simplex), "the closest features"});
    key.push_back({roleColor(Role::Result), r.intersect ? "a common point" : "closest points"});
    drawKey(c, 20, 62, key, 17.0f);
    if (scene.hasLayer("numbers")) {
        std::vector<std::string> lines;
        if (r.intersect)
            lines.push_back("they intersect: " + featureName(r.featureA, 'a') + " meets " + featureName(r.featureB, 'b') +
                            " at " + formatPoint(r.pointA) + ";  " + std::to_string(r.pairsTested) + " feature pairs tried");
        else
            lines.push_back("closest features: " + featureName(r.featureA, 'a') + " and " + featureName(r.featureB, 'b') +
                            ", distance " + formatNumber(r.distance) + ";  points " + formatPoint(r.pointA) + " and " +
                            formatPoint(r.pointB) + ";  " + std::to_string(r.pairsTested) + " feature pairs tried");
        std::string next = "nearest pairs:";
        for (std::size_t k = 0; k < run.candidates.size() && k < 4; ++k)
            next += (k ? ";  " : " ") + featureName(run.candidates[k].a, 'a') + " – " + featureName(run.candidates[k].b, 'b') +
                    " " + formatNumber(run.candidates[k].distance);
        lines.push_back(next);
        const double gjkDistance = run.gjk.intersect() ? 0.0 : run.gjk.distance;
        lines.push_back("check against GJK: distance " + formatNumber(gjkDistance) + ", difference " +
                        formatNumber(std::abs(gjkDistance - r.distance)) +
                        (run.gjk.intersect() == r.intersect ? ", same verdict" : ", verdicts differ"));
        drawNumberBlock(c, lines, 52);
    }
    return finishedFrame(c, scene.title, scene.caption, "features", scene.title + ": " + featureName(r.featureA, 'a') + " – " + featureName(r.featureB, 'b'));
}

}  // namespace

DemoOutput runClosestFeatures(const SceneCommon& scene, const ClosestFeaturesInput& in, const RunContext& ctx) {
    const FeaturesRun run = runFeatures(in);
    DemoOutput out;
    out.trace = featuresJson(in, run);
    if (numericOnly(ctx, out)) return out;
    out.frames.push_back(featuresFrame(*ctx.gl, scene, figureScale(scene, ctx), in, run));
    return out;
}

}  // namespace cdlab::demos
