// Lin–Canny vs V-Clip vs warm GJK (see bench_lin_canny.h).
#include "app/bench/bench_lin_canny.h"

#include <cmath>
#include <iostream>
#include <string>

#include "core/feature_walk/lin_canny.h"
#include "core/feature_walk/vclip.h"
#include "core/geometry/polyhedron_presets.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "verification/minkowski_hull_oracle.h"

namespace cdlab::demos {

namespace {

struct Frame {
    Transform a, b;
    double oracle = 0;
};

std::vector<Vec3> worldPoints(const ConvexPolyhedron& p, const Transform& t) {
    std::vector<Vec3> out;
    for (const Vec3& v : p.positions()) out.push_back(t.apply(v));
    return out;
}

/// A coherent sequence: rotations of `level` degrees per call, B orbiting at radius 2.6.
std::vector<Frame> motion(const ConvexPolyhedron& shape, double level, int count, std::uint64_t seed, bool oracle) {
    std::mt19937_64 rng(seed);
    const Vec3 ua = randomUnit(rng), ub = randomUnit(rng), uo = randomUnit(rng);
    const Vec3 r0 = uo.unitOrthogonal() * 2.6;
    const Quat qa0 = randomRotation(rng), qb0 = randomRotation(rng);
    const double step = level * M_PI / 180.0;
    std::vector<Frame> frames(count);
    for (int i = 0; i < count; ++i) {
        Frame& f = frames[i];
        f.a.rotation = Quat(Eigen::AngleAxisd(step * i, ua)) * qa0;
        f.b.rotation = Quat(Eigen::AngleAxisd(step * i, ub)) * qb0;
        f.b.position = Eigen::AngleAxisd(0.5 * step * i, uo) * r0;
        if (oracle) f.oracle = minkowskiOracle(worldPoints(shape, f.a), worldPoints(shape, f.b)).distance;
    }
    return frames;
}

/// Exact distance of axis-aligned boxes with half extents ha, hb and centre offset d.
double boxGap(const Vec3& ha, const Vec3& hb, const Vec3& d) {
    double s = 0;
    for (int i = 0; i < 3; ++i) s += std::pow(std::max(0.0, std::abs(d[i]) - ha[i] - hb[i]), 2);
    return std::sqrt(s);
}

struct Trial {
    int a = 0, b = 0;  // indices into the box list
    Transform pa, pb;
    VClipFeature seedA, seedB;
    double exact = 0;
};

// Coherent motion: Lin–Canny, V-Clip and warm-started GJK on the same frames of a spinning pair,
// for a cube, an icosahedron and a 60-gon disk at 0..25 degrees per call.
void benchCoherent(const Settings& settings, std::vector<Row>& rows) {
    const bool quick = settings.quick;
    struct Shape {
        const char* name;
        ConvexPolyhedron mesh;
    };
    const std::vector<Shape> shapes = {{"cube", presets::box(Vec3(0.5, 0.5, 0.5))},
                                       {"icosahedron", presets::icosahedron(1.0)},
                                       {"60-gon disk", presets::disk(60, 1.0, 0.05)}};
    const double levels[] = {0.0, 1.0, 5.0, 10.0, 25.0};
    for (const Shape& s : shapes) {
        const VClipPolyhedron poly = buildVClipPolyhedron(s.mesh).polyhedron;
        const PolytopeShape support(s.mesh);
        // The disk's Minkowski oracle hull has 122^2 points: fewer frames there.
        const int count = quick ? 200 : (s.mesh.vertexCount() > 64 ? 400 : 2000);
        for (double level : levels) {
            if (settings.progress)
                std::cerr << "cdlab bench: lin_canny coherent " << s.name << ", " << level << " deg/call\n";
            const std::vector<Frame> frames = motion(s.mesh, level, count, 77 + static_cast<int>(level), true);
            const std::string input = std::string(s.name) + ", " + fmt("%.0f", level) + " deg/call";
            auto error = [&](int i, const Answer& a) { return relativeError(a.value, frames[i].oracle, 1.0); };
            LinCannyCache lc;
            rows.push_back(measure(
                settings, "feature_walk_coherent", input, "lin_canny", count,
                [&](int i) {
                    if (i == 0) lc = {};
                    const LinCannyResult r = linCanny(poly, frames[i].a, poly, frames[i].b, &lc);
                    return Answer{r.distance, r.steps};
                },
                error));
            VClipCache vc;
            rows.push_back(measure(
                settings, "feature_walk_coherent", input, "vclip", count,
                [&](int i) {
                    if (i == 0) vc = {};
                    const VClipResult r = vclip(poly, frames[i].a, poly, frames[i].b, &vc);
                    return Answer{r.distance, r.steps};
                },
                error));
            GjkSimplex simplex;
            rows.push_back(measure(
                settings, "feature_walk_coherent", input, "gjk warm", count,
                [&](int i) {
                    GjkOptions o;
                    if (i > 0) o.warmStart = &simplex;
                    const GjkResult r = gjkDistance(Transformed<PolytopeShape>{support, frames[i].a},
                                                    Transformed<PolytopeShape>{support, frames[i].b}, o);
                    simplex = r.simplex;
                    return Answer{r.distance, r.iterations};
                },
                error));
        }
    }
}

// Degenerate families: boxes on a 1/4 grid, axis-aligned (90-degree turns), every pair of seed
// features; the exact gap from the box offsets.
struct DegenerateSet {
    std::vector<Vec3> halves;
    std::vector<VClipPolyhedron> boxes;
    std::vector<Trial> trials;
};

DegenerateSet degenerateSet(int trials) {
    DegenerateSet out;
    out.halves = {Vec3(0.5, 0.5, 0.5), Vec3(0.25, 0.5, 0.75), Vec3(0.5, 0.25, 0.25)};
    std::vector<VClipPolyhedron>& boxes = out.boxes;
    const std::vector<Vec3>& halves = out.halves;
    for (const Vec3& h : halves) boxes.push_back(buildVClipPolyhedron(presets::box(h)).polyhedron);
    out.trials.resize(trials);
    std::vector<Trial>& set = out.trials;
    std::mt19937_64 rng(2026);
    auto grid = [&](int lo, int hi) {
        return 0.25 * static_cast<double>(lo + static_cast<int>(rng() % (hi - lo + 1)));
    };
    // 90-degree rotations about the axes keep the boxes axis-aligned (the half extents permute).
    const Quat turns[] = {Quat::Identity(), Quat(Eigen::AngleAxisd(M_PI, Vec3::UnitZ())),
                          Quat(Eigen::AngleAxisd(M_PI, Vec3::UnitX())), Quat(Eigen::AngleAxisd(M_PI, Vec3::UnitY()))};
    for (Trial& t : set) {
        t.a = static_cast<int>(rng() % boxes.size());
        t.b = static_cast<int>(rng() % boxes.size());
        t.pa.position = Vec3(grid(-8, 8), grid(-8, 8), grid(-8, 8));
        t.pa.rotation = turns[rng() % 4];
        t.pb.position = t.pa.position + Vec3(grid(-8, 8), grid(-8, 8), grid(-8, 8));
        t.pb.rotation = turns[rng() % 4];
        const ConvexPolyhedron& ma = boxes[t.a].mesh();
        const ConvexPolyhedron& mb = boxes[t.b].mesh();
        const int ka = static_cast<int>(rng() % 3), kb = static_cast<int>(rng() % 3);
        const int na[] = {ma.vertexCount(), ma.edgeCount(), ma.faceCount()},
                  nb[] = {mb.vertexCount(), mb.edgeCount(), mb.faceCount()};
        t.seedA = {static_cast<VClipFeatureType>(ka + 1), static_cast<int>(rng() % na[ka])};
        t.seedB = {static_cast<VClipFeatureType>(kb + 1), static_cast<int>(rng() % nb[kb])};
        t.exact = boxGap(halves[t.a], halves[t.b], t.pb.position - t.pa.position);
    }
    return out;
}

// One walk on every trial of the degenerate set: 0 ok, 1 cycle or step limit, 2 wrong distance,
// 3 wrong verdict (touching or penetrating called separated, or the reverse).
void benchDegenerate(const Settings& settings, std::vector<Row>& rows, std::vector<DegenerateCount>* counts) {
    const int trials = settings.quick ? 10000 : 100000;
    const DegenerateSet data = degenerateSet(trials);
    const std::vector<VClipPolyhedron>& boxes = data.boxes;
    const std::vector<Trial>& set = data.trials;
    const double tol = 1e-9;
    for (int m = 0; m < 2; ++m) {
        const char* method = m == 0 ? "lin_canny" : "vclip";
        if (settings.progress) std::cerr << "cdlab bench: " << method << " degenerate families\n";
        std::vector<int> outcome(trials);  // 0 ok, 1 cycle, 2 wrong distance, 3 wrong verdict
        Row row = measure(
            settings, "feature_walk_degenerate", "boxes on a 1/4 grid", method, trials,
            [&](int i) {
                const Trial& t = set[i];
                int code = 0;
                double d = 0;
                int steps = 0;
                if (m == 0) {
                    LinCannyCache c{t.seedA, t.seedB};
                    const LinCannyResult r = linCanny(boxes[t.a], t.pa, boxes[t.b], t.pb, &c);
                    d = r.distance;
                    steps = r.steps;
                    if (r.status == LinCannyStatus::CycleDetected || r.status == LinCannyStatus::StepLimit) code = 1;
                    else if (r.status == LinCannyStatus::Separated)
                        code = (t.exact <= tol || std::abs(d - t.exact) > tol) ? 2 : 0;
                    else code = t.exact > tol ? 3 : 0;
                } else {
                    VClipCache c{t.seedA, t.seedB};
                    // V-Clip never enters F-F: it replaces B's face by a vertex itself.
                    const VClipResult r = vclip(boxes[t.a], t.pa, boxes[t.b], t.pb, &c);
                    d = r.distance;
                    steps = r.steps;
                    if (r.status == VClipStatus::CycleDetected || r.status == VClipStatus::StepLimit) code = 1;
                    else if (r.status == VClipStatus::Separated)
                        code = (t.exact <= tol || std::abs(d - t.exact) > tol) ? 2 : 0;
                    else code = t.exact > tol ? 3 : 0;
                }
                outcome[i] = code;
                return Answer{static_cast<double>(code), steps};
            },
            [&](int, const Answer& a) { return a.value != 0 ? 1.0 : 0.0; }, true);
        rows.push_back(row);
        if (counts) {
            DegenerateCount c;
            c.method = method;
            c.trials = trials;
            for (int o : outcome) {
                c.cycles += o == 1;
                c.wrongDistance += o == 2;
                c.wrongVerdict += o == 3;
            }
            counts->push_back(c);
        }
    }
}

}  // namespace

std::vector<Row> benchLinCanny(const Settings& settings, std::vector<DegenerateCount>* counts) {
    std::vector<Row> rows;
    benchCoherent(settings, rows);
    benchDegenerate(settings, rows, counts);
    return rows;
}

}  // namespace cdlab::demos
