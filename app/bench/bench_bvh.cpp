// BVH build / query / refit benchmark (see bench_bvh.h).
#include "app/bench/bench_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>
#include <vector>

#include "core/bvh/bvh.h"
#include "core/bvh/mesh_collision.h"
#include "core/geometry/triangle_mesh.h"
#include "demos/draw/plot.h"
#include "app/measure/statistics.h"
#include "render/image.h"

namespace cdlab::demos {

namespace {

/// Median over `reps` runs of f() (seconds per run).
template <class F>
double timeRuns(int reps, F&& f) {
    std::vector<double> t;
    for (int r = 0; r < reps; ++r) {
        const double t0 = threadSeconds();
        f();
        t.push_back(threadSeconds() - t0);
    }
    return median(t);
}

/// Seconds per call of f(i): calls are batched so one repetition lasts >= minSeconds; median
/// over `reps` repetitions.
template <class F>
double timePerCall(int reps, double minSeconds, F&& f) {
    int batch = 1;
    for (;;) {
        const double t0 = threadSeconds();
        for (int i = 0; i < batch; ++i) f(i);
        if (threadSeconds() - t0 >= minSeconds || batch >= (1 << 20)) break;
        batch *= 4;
    }
    return timeRuns(reps,
                    [&] {
                        for (int i = 0; i < batch; ++i) f(i);
                    }) /
           batch;
}

/// Torus with about `target` triangles: majorSegments = 2 minorSegments.
TriangleMesh benchTorus(int target) {
    const int minor = std::max(3, static_cast<int>(std::lround(std::sqrt(target / 4.0))));
    const int major = std::max(3, static_cast<int>(std::lround(target / (2.0 * minor))));
    return torusMesh(1.0, 0.3, major, minor);
}

/// The bench tables' short label of a build method.
const char* shortLabel(BvhBuildMethod m) {
    switch (m) {
        case BvhBuildMethod::TopDownMedian: return "median";
        case BvhBuildMethod::TopDownSah: return "SAH";
        case BvhBuildMethod::BottomUp: return "bottom-up";
    }
    return "?";
}

struct Series {
    std::string label;
    std::vector<std::pair<double, double>> points;
};

void addPoint(std::vector<Series>& all, const std::string& label, double x, double y) {
    for (Series& s : all)
        if (s.label == label) {
            s.points.emplace_back(x, y);
            return;
        }
    all.push_back(Series{label, {{x, y}}});
}

std::vector<PlotSeries> toPlot(const std::vector<Series>& all) {
    std::vector<PlotSeries> out;
    for (const Series& s : all) {
        PlotSeries p;
        p.label = s.label;
        p.style = static_cast<int>(out.size());
        p.line = s.points.size() > 1;
        p.points = s.points;
        out.push_back(p);
    }
    return out;
}

std::string fmtNum(const char* f, double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, x);
    return buf;
}

std::string padRight(std::string s, size_t width) {
    if (s.size() < width) s.append(width - s.size(), ' ');
    return s;
}

std::vector<std::pair<int, int>> sortedPairs(const MeshCollisionResult& r) {
    std::vector<std::pair<int, int>> out;
    for (const TrianglePair& p : r.pairs) out.emplace_back(p.a, p.b);
    std::sort(out.begin(), out.end());
    return out;
}

// What the BVH bench collects: plot series, table rows, and a status (1 when a tree's pairs
// differ from the others' or from brute force).
struct BvhBenchOutput {
    std::vector<Series> buildSeries, meshSeries, raySeries, refitSeries;
    std::ostringstream buildTable, queryTable, refitTable;
    int status = 0;
};

// A tree with its table label.
struct NamedTree {
    std::string label;
    const Bvh* tree;
};

const BvhBuildMethod kMethods[] = {BvhBuildMethod::TopDownMedian, BvhBuildMethod::TopDownSah, BvhBuildMethod::BottomUp};
const BvKind kKinds[] = {BvKind::Aabb, BvKind::Obb};

// Build time of every method and bounding volume (bottom-up only up to bottomUpMax triangles);
// the median and SAH trees (AABB, OBB) are kept for the queries.
void benchBuilds(const TriangleMesh& mesh, int reps, int bottomUpMax, std::vector<Bvh>& medianTrees,
                 std::vector<Bvh>& sahTrees, BvhBenchOutput& out) {
    std::vector<Series>& buildSeries = out.buildSeries;
    std::ostringstream& buildTable = out.buildTable;
    const int n = mesh.triangleCount();
    for (BvKind kind : kKinds)
        for (BvhBuildMethod method : kMethods) {
            if (method == BvhBuildMethod::BottomUp && n > bottomUpMax) continue;
            BvhBuildOptions o;
            o.bvKind = kind;
            o.method = method;
            Bvh tree;
            const double s =
                timeRuns(method == BvhBuildMethod::BottomUp && n > 2000 ? 3 : reps, [&] { tree = buildBvh(mesh, o); });
            const std::string label = std::string(shortLabel(method)) + " " + nameOf(kind);
            buildTable << "build      " << fmtNum("%9.0f", n) << "  " << padRight(label, 16) << fmtNum("%9.3f", 1e3 * s)
                       << fmtNum("%11.0f", static_cast<double>(tree.nodes.size()))
                       << fmtNum("%8.0f", static_cast<double>(tree.height())) << "\n";
            addPoint(buildSeries, label, n, 1e3 * s);
            if (method == BvhBuildMethod::TopDownMedian) medianTrees.push_back(std::move(tree));
            else if (method == BvhBuildMethod::TopDownSah) sahTrees.push_back(std::move(tree));
        }
}

// Mesh vs mesh in the cutting pose (every tree must give the same pairs) and the linked pose (no
// pair); returns the cutting pose's pairs.
std::vector<std::pair<int, int>> benchMeshQueries(const TriangleMesh& mesh, const std::vector<NamedTree>& trees,
                                                  const Transform& contact, const Transform& gap, bool quick,
                                                  BvhBenchOutput& out) {
    std::vector<Series>& meshSeries = out.meshSeries;
    std::ostringstream& queryTable = out.queryTable;
    int& status = out.status;
    const int n = mesh.triangleCount();
    std::vector<std::pair<int, int>> reference;
    for (const NamedTree& t : trees) {
        for (int p = 0; p < 2; ++p) {
            const Transform& pb = p == 0 ? contact : gap;
            const MeshCollisionResult r = collideMeshes(mesh, *t.tree, Transform{}, mesh, *t.tree, pb);
            if (p == 0) {
                const auto pairs = sortedPairs(r);
                if (reference.empty()) reference = pairs;
                if (pairs != reference || pairs.empty()) {
                    std::cerr << "cdlab bench: BVH pairs differ between trees (" << t.label << ")\n";
                    status = 1;
                }
            } else if (r.hit) {
                std::cerr << "cdlab bench: BVH pairs in the separated pose (" << t.label << ")\n";
                status = 1;
            }
            const double s = timePerCall(5, quick ? 0.01 : 0.05, [&](int) {
                return collideMeshes(mesh, *t.tree, Transform{}, mesh, *t.tree, pb).pairs.size();
            });
            const std::string label = std::string(p == 0 ? "cutting: " : "linked 0.4 apart: ") + t.label;
            queryTable << (p == 0 ? "mesh-mesh  " : "linked     ") << fmtNum("%9.0f", n) << "  "
                       << padRight(t.label, 16) << fmtNum("%10.1f", 1e6 * s)
                       << fmtNum("%11.0f", static_cast<double>(r.stats.bvTests))
                       << fmtNum("%11.0f", static_cast<double>(r.stats.triangleTests))
                       << fmtNum("%7.0f", static_cast<double>(r.pairs.size())) << "\n";
            addPoint(meshSeries, label, n, 1e6 * s);
        }
    }
    return reference;
}

// The O(n²) reference (1M triangle tests at the smallest size).
void benchBruteForce(const TriangleMesh& mesh, const Transform& contact,
                     const std::vector<std::pair<int, int>>& reference, BvhBenchOutput& out) {
    std::vector<Series>& meshSeries = out.meshSeries;
    std::ostringstream& queryTable = out.queryTable;
    int& status = out.status;
    const int n = mesh.triangleCount();
    // The O(n²) reference at the smallest size only (1M triangle tests).
    MeshCollisionResult brute;
    const double s = timeRuns(3, [&] { brute = collideMeshesBruteForce(mesh, Transform{}, mesh, contact); });
    if (sortedPairs(brute) != reference) {
        std::cerr << "cdlab bench: BVH pairs differ from brute force\n";
        status = 1;
    }
    queryTable << "mesh-mesh  " << fmtNum("%9.0f", n) << "  brute force     " << fmtNum("%10.1f", 1e6 * s)
               << fmtNum("%11.0f", 0.0) << fmtNum("%11.0f", static_cast<double>(brute.stats.triangleTests))
               << fmtNum("%7.0f", static_cast<double>(brute.pairs.size())) << "\n";
    addPoint(meshSeries, "brute force O(n²)", n, 1e6 * s);
}

// Rays from a sphere of radius 3 towards random points near the torus, all hits reported.
void benchRays(const TriangleMesh& mesh, const std::vector<NamedTree>& trees, bool quick, BvhBenchOutput& out) {
    std::vector<Series>& raySeries = out.raySeries;
    std::ostringstream& queryTable = out.queryTable;
    const int n = mesh.triangleCount();
    std::mt19937_64 rng(12345);
    std::normal_distribution<double> g;
    std::vector<Ray> rays;
    for (int i = 0; i < 256; ++i) {
        const Vec3 o = 3.0 * Vec3(g(rng), g(rng), g(rng)).normalized();
        const Vec3 target3 = Vec3(g(rng), g(rng), 0.3 * g(rng));
        rays.push_back(Ray{o, target3 - o});
    }
    for (const NamedTree& t : trees) {
        if (t.label.rfind("SAH", 0) == 0) continue;
        long long bv = 0, tri = 0, hits = 0;
        for (const Ray& ray : rays) {
            const BvhQueryResult r = queryBvhRay(*t.tree, mesh, Transform{}, ray);
            bv += r.stats.bvTests;
            tri += r.stats.triangleTests;
            hits += static_cast<long long>(r.hits.size());
        }
        const double s = timePerCall(5, quick ? 0.01 : 0.05, [&](int i) {
            return queryBvhRay(*t.tree, mesh, Transform{}, rays[i % rays.size()]).hits.size();
        });
        queryTable << "ray        " << fmtNum("%9.0f", n) << "  " << padRight(t.label, 16) << fmtNum("%10.2f", 1e6 * s)
                   << fmtNum("%11.1f", static_cast<double>(bv) / rays.size())
                   << fmtNum("%11.1f", static_cast<double>(tri) / rays.size())
                   << fmtNum("%7.2f", static_cast<double>(hits) / rays.size()) << "\n";
        addPoint(raySeries, t.label, n, 1e6 * s);
    }
}

// Refit vs rebuild after a deformation.
void benchRefit(const TriangleMesh& mesh, const std::vector<Bvh>& medianTrees, int reps, BvhBenchOutput& out) {
    std::vector<Series>& refitSeries = out.refitSeries;
    std::ostringstream& refitTable = out.refitTable;
    const int n = mesh.triangleCount();
    TriangleMesh bent = mesh;
    for (Vec3& v : bent.vertices) v += 0.1 * Vec3(std::sin(3 * v.y()), std::cos(2 * v.x()), std::sin(4 * v.x()));
    for (int k = 0; k < 2; ++k) {
        Bvh tree = medianTrees[k];
        const double refit = timeRuns(reps, [&] { refitBvh(tree, bent); });
        BvhBuildOptions o;
        o.bvKind = kKinds[k];
        const double rebuild = timeRuns(reps, [&] { buildBvh(bent, o); });
        const std::string label = std::string("median ") + nameOf(kKinds[k]);
        refitTable << "wave 0.1   " << fmtNum("%9.0f", n) << "  " << padRight(label, 16)
                   << fmtNum("%10.3f", 1e3 * refit) << fmtNum("%12.3f", 1e3 * rebuild)
                   << fmtNum("%12.1f", rebuild / refit) << "\n";
        addPoint(refitSeries, "refit " + label, n, 1e3 * refit);
        addPoint(refitSeries, "rebuild " + label, n, 1e3 * rebuild);
    }
}

void writeBvhFigures(const std::string& outDir, const BvhBenchOutput& out) {
    const std::vector<Series>& buildSeries = out.buildSeries;
    const std::vector<Series>& meshSeries = out.meshSeries;
    const std::vector<Series>& raySeries = out.raySeries;
    const std::vector<Series>& refitSeries = out.refitSeries;
    std::unique_ptr<render::GlContext> gl;
    try {
        gl = render::GlContext::create();
    } catch (const std::exception& e) {
        std::cerr << "cdlab bench: no BVH figures (" << e.what() << ")\n";
        return;
    }
    const std::string sub = "torus meshes; thread CPU time, median of repetitions; shared 2-core machine";
    auto plot = [&](const std::string& file, const std::string& title, const std::string& yLabel,
                    const std::vector<Series>& s) {
        PlotOptions po;
        po.title = title;
        po.subtitle = sub;
        po.xLabel = "triangles per mesh";
        po.yLabel = yLabel;
        po.yFloor = 1e-6;
        po.legendWidth = 340;
        try {
            render::writePngAtomic(outDir + "/" + file, drawLogLogPlot(*gl, po, toPlot(s)));
        } catch (const std::exception& e) {
            std::cerr << "cdlab bench: " << file << ": " << e.what() << "\n";
        }
    };
    plot("bvh_build.png", "BVH build time vs triangle count", "build time, ms", buildSeries);
    plot("bvh_query_mesh.png", "BVH mesh vs mesh: all intersecting triangle pairs, time vs triangle count",
         "time per query, µs", meshSeries);
    plot("bvh_query_ray.png", "BVH ray query (all hits): time vs triangle count", "time per ray, µs", raySeries);
    plot("bvh_refit.png", "BVH refit vs rebuild after a deformation", "time, ms", refitSeries);
}

}  // namespace

int runBvhBench(bool quick, const std::string& outDir, std::ostream& table) {
    std::vector<int> sizes{1000, 10000, 100000};
    if (!quick) sizes.push_back(1000000);
    const int bottomUpMax = quick ? 2000 : 10000;  // quadratic: 10k takes seconds per build

    // Poses: B is a copy of the torus linked through A's hole, cutting A's tube (contact curves
    // of O(sqrt n) triangles), and linked without contact (core circles 1 apart everywhere, tubes
    // 0.4 apart: the traversal goes deep without a pair).
    Transform contact;
    contact.rotation = Quat(Eigen::AngleAxisd(0.1, Vec3(0.3, 0.5, 0.8).normalized())) *
                       Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
    contact.position = Vec3(1.45, 0.02, 0.03);
    Transform gap;
    gap.rotation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
    gap.position = Vec3(1.0, 0.0, 0.0);

    BvhBenchOutput out;
    out.buildTable << "build      triangles  tree              ms      nodes  height\n";
    out.queryTable << "query      triangles  tree              us/query   BV tests  tri tests  pairs\n";
    out.refitTable << "deform     triangles  tree              refit ms  rebuild ms  rebuild/refit\n";

    for (const int target : sizes) {
        const TriangleMesh mesh = benchTorus(target);
        const int n = mesh.triangleCount();
        std::cerr << "cdlab bench: BVH " << n << " triangles\n";
        // Quick mode: one run per build above 10k triangles (a median of 1).
        const int reps = n <= 10000 ? 5 : (quick ? 1 : 3);
        std::vector<Bvh> medianTrees, sahTrees;
        benchBuilds(mesh, reps, bottomUpMax, medianTrees, sahTrees, out);
        const std::vector<NamedTree> trees{{"median AABB", &medianTrees[0]},
                                           {"median OBB", &medianTrees[1]},
                                           {"SAH AABB", &sahTrees[0]},
                                           {"SAH OBB", &sahTrees[1]}};
        const std::vector<std::pair<int, int>> reference = benchMeshQueries(mesh, trees, contact, gap, quick, out);
        if (n <= 1100) benchBruteForce(mesh, contact, reference, out);
        benchRays(mesh, trees, quick, out);
        benchRefit(mesh, medianTrees, reps, out);
    }

    table << "BVH bench: torus meshes (R = 1, r = 0.3), leaf size 1; thread CPU time, median of repetitions,\n"
          << "all rows side by side in one run on a shared 2-core machine. Bottom-up (O(n²) agglomerative)\n"
          << "only up to " << bottomUpMax << " triangles. mesh-mesh: the torus against a copy through its hole,\n"
          << "cutting its tube; linked: the copy linked through the hole, tubes 0.4 apart (no contact).\n"
          << "ray: 256 rays, all hits (columns: BV tests, triangle tests and hits per ray).\n\n"
          << out.buildTable.str() << "\n"
          << out.queryTable.str() << "\n"
          << out.refitTable.str();
    writeBvhFigures(outDir, out);
    return out.status;
}

}  // namespace cdlab::demos
