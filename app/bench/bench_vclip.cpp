// V-Clip vs GJK under frame coherence: see bench_vclip.h.
#include "app/bench/bench_vclip.h"
#include "app/measure/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "core/feature_walk/vclip.h"
#include "core/geometry/polyhedron_presets.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"

namespace cdlab::demos {

namespace {

struct Scenario {
    const char* name;
    ConvexPolyhedron poly;
    double orbit;  // centre distance: always separated (bounding radius < orbit / 2)
};

struct Timing {
    double nsMedian = 0.0;
    double stepsMean = 0.0;
};

// Median over `reps` repetitions of the time per query of one pass over the sequence; `pass`
// runs the whole sequence and returns the number of steps it took.
template <class Pass>
Timing timePasses(int reps, int queries, Pass&& pass) {
    std::vector<double> ns;
    long long steps = 0;
    pass();  // warm-up (caches, branch predictors, warm-start state)
    for (int r = 0; r < reps; ++r) {
        const double t0 = threadSeconds();
        steps = pass();
        const double t1 = threadSeconds();
        ns.push_back((t1 - t0) * 1e9 / queries);
    }
    std::nth_element(ns.begin(), ns.begin() + ns.size() / 2, ns.end());
    return {ns[ns.size() / 2], static_cast<double>(steps) / queries};
}

}  // namespace

int runVclipBench(bool quick, std::ostream& out) {
    const int queries = quick ? 200 : 2000, reps = quick ? 3 : 11;
    const std::vector<Scenario> scenarios = {
        {"cube", presets::box(Vec3(1, 1, 1)), 4.0},
        {"icosahedron", presets::icosahedron(1.0), 2.6},
        {"disk (60-gon prism)", presets::disk(60, 1.0), 2.5},
        {"geodesic sphere (642 v)", presets::geodesicSphere(3, 1.0), 2.5},
    };
    const double degrees[] = {0.0, 1.0, 5.0, 10.0, 25.0};
    int status = 0;
    out << "V-Clip vs GJK, " << queries << " coherent queries per sequence, median of " << reps
        << " repetitions (thread CPU ns per query; steps = V-Clip updates / GJK iterations per query)\n\n"
        << "| shape | deg/call | V-Clip cold ns | steps | V-Clip warm ns | steps | GJK cold ns | iters | GJK warm ns | "
           "iters |\n"
        << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Scenario& sc : scenarios) {
        const VClipPolyhedron vp = buildVClipPolyhedron(sc.poly).polyhedron;
        Transformed<PolytopeShape> ga{PolytopeShape(sc.poly), Transform{}}, gb{PolytopeShape(sc.poly), Transform{}};
        // A turns about one axis, B about another and orbits A: each call moves the relative
        // pose by about `deg` degrees (0: the same pose every call).
        const Vec3 axisA = Vec3(0.3, 1.0, 0.2).normalized(), axisB = Vec3(1.0, -0.4, 0.5).normalized();
        const Vec3 orbitAxis = Vec3(0.1, 0.2, 1.0).normalized();
        const Quat q0 = Quat(0.8, 0.3, -0.4, 0.33).normalized();
        for (double deg : degrees) {
            const double step = deg * M_PI / 180.0;
            std::vector<Transform> pa(queries), pb(queries);
            for (int k = 0; k < queries; ++k) {
                pa[k].rotation = Quat(Eigen::AngleAxisd(0.5 * k * step, axisA));
                pb[k].rotation = Quat(Eigen::AngleAxisd(0.5 * k * step, axisB)) * q0;
                pb[k].position = Quat(Eigen::AngleAxisd(0.5 * k * step, orbitAxis)) * Vec3(sc.orbit, 0.3, 0.2);
            }
            std::vector<double> vclipDistance(queries), gjkDistanceOut(queries);
            const Timing vcold = timePasses(reps, queries, [&] {
                long long s = 0;
                for (int k = 0; k < queries; ++k) {
                    const VClipResult r = vclip(vp, pa[k], vp, pb[k]);
                    s += r.steps;
                }
                return s;
            });
            VClipCache cache;
            const Timing vwarm = timePasses(reps, queries, [&] {
                long long s = 0;
                for (int k = 0; k < queries; ++k) {
                    const VClipResult r = vclip(vp, pa[k], vp, pb[k], &cache);
                    vclipDistance[k] = r.distance;
                    s += r.steps;
                }
                return s;
            });
            const Timing gcold = timePasses(reps, queries, [&] {
                long long s = 0;
                for (int k = 0; k < queries; ++k) {
                    ga.transform = pa[k];
                    gb.transform = pb[k];
                    const GjkResult g = gjkDistance(ga, gb);
                    gjkDistanceOut[k] = g.distance;
                    s += g.iterations;
                }
                return s;
            });
            GjkSimplex previous;
            const Timing gwarm = timePasses(reps, queries, [&] {
                long long s = 0;
                GjkOptions o;
                for (int k = 0; k < queries; ++k) {
                    ga.transform = pa[k];
                    gb.transform = pb[k];
                    o.warmStart = previous.count > 0 ? &previous : nullptr;
                    const GjkResult g = gjkDistance(ga, gb, o);
                    previous = g.simplex;
                    s += g.iterations;
                }
                return s;
            });
            for (int k = 0; k < queries; ++k)
                if (!(std::abs(vclipDistance[k] - gjkDistanceOut[k]) <= 1e-9 * (1.0 + gjkDistanceOut[k]))) {
                    out << "MISMATCH " << sc.name << " deg " << deg << " query " << k << ": vclip " << vclipDistance[k]
                        << " gjk " << gjkDistanceOut[k] << "\n";
                    status = 1;
                    break;
                }
            char line[256];
            std::snprintf(line, sizeof line, "| %s | %g | %.0f | %.2f | %.0f | %.2f | %.0f | %.2f | %.0f | %.2f |\n",
                          sc.name, deg, vcold.nsMedian, vcold.stepsMean, vwarm.nsMedian, vwarm.stepsMean,
                          gcold.nsMedian, gcold.stepsMean, gwarm.nsMedian, gwarm.stepsMean);
            out << line;
        }
    }
    return status;
}

}  // namespace cdlab::demos
