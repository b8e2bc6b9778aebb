// `cdlab bench`: run time against error for the core queries, on fixed-seed inputs, each answer
// checked against an independent oracle (verification/minkowski_hull_oracle.h).
//
// Timing and error definitions: app/bench/bench_measure.h.
#include "app/bench/bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/base/primitives.h"
#include "core/closest/closest_point.h"
#include "core/geometry/convex_hull.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/epa.h"
#include "core/gjk_epa/gjk.h"
#include "core/gjk_epa/margins.h"
#include "core/gjk_epa/mpr.h"
#include "core/overlap/sat_tests.h"
#include "app/bench/bench_broadphase.h"
#include "app/bench/bench_tree.h"
#include "app/bench/bench_world.h"
#include "app/bench/bench_contact.h"
#include "app/bench/bench_curved.h"
#include "app/bench/bench_inputs.h"
#include "app/bench/bench_bvh.h"
#include "app/bench/bench_lin_canny.h"
#include "app/bench/bench_measure.h"
#include "app/bench/bench_vclip.h"
#include "app/bench/peers/bench_peers.h"
#include "demos/draw/plot.h"
#include "verification/minkowski_hull_oracle.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

namespace {

using Clock = std::chrono::steady_clock;

struct SpherePair {
    Transformed<SphereShape> a, b;
    double distance = 0;  // analytic: |c_b - c_a| - r_a - r_b (negative: depth)
};

std::vector<SpherePair> spherePairs(int count, double offset, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> radius(0.3, 1.0);
    std::vector<SpherePair> pairs;
    for (int i = 0; i < count; ++i) {
        SpherePair p;
        p.a.shape.radius = radius(rng);
        p.b.shape.radius = radius(rng);
        p.b.transform.position = offset * randomUnit(rng);
        p.distance = p.b.transform.position.norm() - p.a.shape.radius - p.b.shape.radius;
        pairs.push_back(p);
    }
    return pairs;
}

// ---- Output -------------------------------------------------------------------------------------

void printTable(const std::vector<Row>& rows, std::ostream& out, bool markdown) {
    char line[512];
    if (markdown) {
        out << "| query | input | method | ns median | ns min | ns max | err median | err p99 | err max | >1e-6 | "
               ">1e-2 | iters | time / cdlab |\n"
               "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    } else {
        std::snprintf(line, sizeof line, "%-14s %-22s %-24s %9s %9s %9s %9s %9s %9s %7s %7s %6s %7s\n", "query",
                      "input", "method", "ns med", "ns min", "ns max", "err med", "err p99", "err max", ">1e-6",
                      ">1e-2", "iters", "/cdlab");
        out << line;
    }
    for (const Row& r : rows) {
        const char* f = markdown
                            ? "| %s | %s | %s | %.1f | %.1f | %.1f | %.2g | %.2g | %.2g | %.3g | %.3g | %.2f | %s |\n"
                            : "%-14s %-22s %-24s %9.1f %9.1f %9.1f %9.2g %9.2g %9.2g %7.3g %7.3g %6.2f %7s\n";
        const std::string ratio = r.ratio > 0 ? fmt("%.2f", r.ratio) : "";
        std::snprintf(line, sizeof line, f, r.query.c_str(), r.input.c_str(), r.method.c_str(), r.nsMedian, r.nsMin,
                      r.nsMax, r.error.median, r.error.p99, r.error.max, r.error.above1e6, r.error.above1e2,
                      r.iterations, ratio.c_str());
        out << line;
    }
}

nlohmann::json toJson(const std::vector<Row>& rows, const std::string& machine, bool quick) {
    nlohmann::json j;
    j["machine"] = machine;
    j["mode"] = quick ? "quick" : "full";
    j["error_definition"] = "relative |x - x*| / |x*| (touching: |x| / size); boolean queries: 1 per wrong answer";
    j["rows"] = nlohmann::json::array();  // present (empty) when --only ran no query section
    for (const Row& r : rows) {
        j["rows"].push_back({{"query", r.query},
                             {"input", r.input},
                             {"method", r.method},
                             {"queries", r.queries},
                             {"reps", r.reps},
                             {"ns_median", r.nsMedian},
                             {"ns_min", r.nsMin},
                             {"ns_max", r.nsMax},
                             {"error_median", r.error.median},
                             {"error_p99", r.error.p99},
                             {"error_max", r.error.max},
                             {"fraction_above_1e-6", r.error.above1e6},
                             {"fraction_above_1e-2", r.error.above1e2},
                             {"iterations_mean", r.iterations},
                             {"boolean", r.boolean},
                             {"min_time_ratio_to_cdlab", r.ratio}});
    }
    return j;
}

/// Method without its tolerance ("SV tol 1e-06" -> "SV"): one Pareto series per method.
std::string methodBase(const std::string& method, std::string* tolerance) {
    const size_t at = method.find(" tol ");
    if (at == std::string::npos) return method;
    std::string rest = method.substr(at + 5);
    const size_t comma = rest.find(',');
    if (tolerance) *tolerance = rest.substr(0, comma);
    return method.substr(0, at) + (comma == std::string::npos ? "" : rest.substr(comma));
}

/// Error shown for a row: p99 of the relative error; boolean queries: the fraction wrong.
double rowError(const Row& r) {
    if (!r.boolean) return r.error.p99;
    double wrong = 0;
    for (double e : r.errors) wrong += e;
    return r.errors.empty() ? 0.0 : wrong / r.errors.size();
}

/// out/bench/pareto_<query>.png (time vs error, one series per method, tolerance sweeps as
/// lines) and hist_<query>.png (error histograms of the default-setting rows).
void writeBenchFigures(const std::vector<Row>& rows, const std::string& outDir) {
    std::unique_ptr<render::GlContext> gl;
    try {
        gl = render::GlContext::create();
    } catch (const std::exception& e) {
        std::cerr << "cdlab bench: no figures (" << e.what() << ")\n";
        return;
    }
    std::vector<std::string> queries;
    for (const Row& r : rows)
        if (std::find(queries.begin(), queries.end(), r.query) == queries.end()) queries.push_back(r.query);
    for (const std::string& q : queries) {
        std::vector<PlotSeries> series;
        std::map<std::string, size_t> index;
        bool boolean = false;
        for (const Row& r : rows) {
            if (r.query != q || r.queries == 0) continue;
            boolean = r.boolean;
            std::string tol;
            const std::string base = methodBase(r.method, &tol);
            const std::string& key = base;  // tolerance sweeps join their method's series
            auto it = index.find(key);
            if (it == index.end()) {
                it = index.emplace(key, series.size()).first;
                PlotSeries s;
                s.label = key;
                s.style = static_cast<int>(series.size());
                series.push_back(s);
            }
            PlotSeries& s = series[it->second];
            s.points.emplace_back(std::max(rowError(r), 1e-17), r.nsMedian);
            s.pointLabels.push_back(tol.empty() || tol == "1e-13" ? "" : "tol " + tol);  // the sweep's points
        }
        PlotOptions po;
        po.title = "cdlab bench: " + q + " — run time vs error";
        po.xLabel = boolean ? "fraction of wrong answers (10⁻¹⁷: none)" : "error p99, relative (10⁻¹⁷: exact)";
        po.yLabel = "time per query, ns (median)";
        po.subtitle =
            "one marker per input set and setting; down and left is better; same inputs and support functions for "
            "every method";
        po.xFloor = 1e-17;
        po.yFloor = 1;
        try {
            render::writePngAtomic(outDir + "/pareto_" + q + ".png", drawLogLogPlot(*gl, po, series));
        } catch (const std::exception& e) {
            std::cerr << "cdlab bench: pareto_" << q << ": " << e.what() << "\n";
        }
        if (boolean) continue;
        // Histograms: the default settings (tolerance 1e-13 or none) of each method, all inputs pooled.
        std::map<std::string, std::vector<double>> pooled;
        std::vector<std::string> order;
        for (const Row& r : rows) {
            if (r.query != q) continue;
            std::string tol;
            const std::string base = methodBase(r.method, &tol);
            if (!tol.empty() && tol != "1e-13") continue;
            if (!pooled.count(base)) order.push_back(base);
            auto& v = pooled[base];
            v.insert(v.end(), r.errors.begin(), r.errors.end());
        }
        std::vector<std::pair<std::string, std::vector<double>>> hist;
        for (const std::string& m : order)
            hist.emplace_back(m + " (" + std::to_string(pooled[m].size()) + ")", pooled[m]);
        PlotOptions ho;
        ho.title = "cdlab bench: " + q + " — error histogram";
        ho.xLabel = "relative error against the oracle (first bin: ≤ 10⁻¹⁷, including exact)";
        ho.yLabel = "fraction of queries";
        ho.subtitle = "default settings (tolerance 1e-13), every input set pooled; in parentheses: queries";
        ho.xFloor = 1e-17;
        try {
            render::writePngAtomic(outDir + "/hist_" + q + ".png", drawDecadeHistogram(*gl, ho, hist));
        } catch (const std::exception& e) {
            std::cerr << "cdlab bench: hist_" << q << ": " << e.what() << "\n";
        }
    }
}

// Peers (libccd, Bullet) on the same pairs, each row's time relative to cdlab's row `reference`.
void peerRows(const Settings& settings, std::vector<Row>& rows, const std::string& query, const std::string& input,
              const std::vector<const PolyPair*>& set, size_t reference,
              const std::function<double(int, const Answer&)>& error, bool boolean) {
#ifdef CDLAB_BENCH_PEERS
    std::vector<PeerPair> peerPairs;
    for (const PolyPair* p : set) peerPairs.push_back({&p->va, &p->vb, &p->a, &p->b});
    appendPeerRows(settings, rows, query, input, makePeerRunners(peerPairs, query), static_cast<int>(set.size()),
                   reference, error, boolean);
#else
    (void)settings, (void)rows, (void)query, (void)input, (void)set, (void)reference, (void)error, (void)boolean;
#endif
}

// Closest point on triangle / tetrahedron against the long-double oracle.
void benchClosestPoint(const Settings& settings, std::vector<Row>& rows) {
    const bool quick = settings.quick;
    std::cerr << "cdlab bench: closest point\n";
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto rp = [&] { return Vec3(u(rng), u(rng), u(rng)); };
    const int n = quick ? 2000 : 10000;
    std::vector<Vec3> points;
    std::vector<Triangle> tris;
    std::vector<Tetrahedron> tets;
    std::vector<double> triOracle, tetOracle;
    for (int i = 0; i < n; ++i) {
        points.push_back(2.0 * rp());
        tris.push_back({rp(), rp(), rp()});
        tets.push_back({rp(), rp(), rp(), rp()});
        triOracle.push_back(oracleDistanceToTriangle(points[i], tris[i]));
        tetOracle.push_back(oracleDistanceToTetrahedron(points[i], tets[i]));
    }
    rows.push_back(measure(
        settings, "closest_point", "triangle, random", "Ericson 5.1.5", n,
        [&](int i) {
            return Answer{std::sqrt(closestPointOnTriangle(points[i], tris[i]).distanceSquared), 0};
        },
        [&](int i, const Answer& a) { return relativeError(a.value, triOracle[i], 1.0); }));
    rows.push_back(measure(
        settings, "closest_point", "tetrahedron, random", "regions", n,
        [&](int i) {
            return Answer{std::sqrt(closestPointOnTetrahedron(points[i], tets[i]).distanceSquared), 0};
        },
        [&](int i, const Answer& a) { return relativeError(a.value, tetOracle[i], 1.0); }));
}

// GJK distance / intersect and GJK+EPA depth on random polytopes of nv vertices (count pairs per
// set), with the tolerance sweep, warm starts and the peers on the same pairs.
void benchPolytopes(const Settings& settings, int nv, int count, std::vector<Row>& rows) {
    std::cerr << "cdlab bench: polytopes with " << nv << " vertices (" << count << " pairs per set)\n";
    const std::string tag = "poly" + std::to_string(nv);
    const auto sep = polyPairs(nv, count, 2.2, 1000 + nv);
    const auto pen = polyPairs(nv, count, 0.4, 2000 + nv);
    auto distanceRow = [&](const std::vector<PolyPair>& set, const std::string& input, const std::string& method,
                           GjkOptions options) {
        return measure(
            settings, "gjk_distance", input, method, static_cast<int>(set.size()),
            [&, options](int i) {
                const GjkResult r = gjkDistance(set[i].a, set[i].b, options);
                return Answer{r.distance, r.iterations};
            },
            [&](int i, const Answer& a) { return relativeError(a.value, set[i].oracle.distance, 1.0); });
    };
    std::vector<const PolyPair*> sepPointers;
    for (const auto& p : sep) sepPointers.push_back(&p);
    GjkOptions sv;
    GjkOptions johnson;
    johnson.solver = SimplexSolver::Johnson;
    const size_t distanceReference = rows.size();
    rows.push_back(distanceRow(sep, tag + " separated", "SV tol 1e-13", sv));
    rows.push_back(distanceRow(sep, tag + " separated", "Johnson tol 1e-13", johnson));
    peerRows(
        settings, rows, "gjk_distance", tag + " separated", sepPointers, distanceReference,
        [&](int i, const Answer& a) { return relativeError(a.value, sepPointers[i]->oracle.distance, 1.0); }, false);
    if (nv == 16 || nv == 64) {
        for (double tol : {1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14}) {
            GjkOptions o;
            o.relativeTolerance = tol;
            rows.push_back(distanceRow(sep, tag + " separated", "SV tol " + fmt("%.0e", tol), o));
        }
        // Warm start: the same pairs moved by 1e-3 of their size, seeded with the simplex of
        // the previous position (as a frame-coherent caller would).
        const auto moved = polyPairs(nv, count, 2.2, 1000 + nv, 1e-3);
        std::vector<GjkSimplex> previous;
        for (const PolyPair& p : sep) previous.push_back(gjkDistance(p.a, p.b).simplex);
        rows.push_back(distanceRow(moved, tag + " moved 1e-3", "SV cold", sv));
        rows.push_back(measure(
            settings, "gjk_distance", tag + " moved 1e-3", "SV warm", count,
            [&](int i) {
                GjkOptions o;
                o.warmStart = &previous[i];
                const GjkResult r = gjkDistance(moved[i].a, moved[i].b, o);
                return Answer{r.distance, r.iterations};
            },
            [&](int i, const Answer& a) { return relativeError(a.value, moved[i].oracle.distance, 1.0); }));
    }
    // Boolean intersection over both sets (separated and overlapping).
    std::vector<const PolyPair*> both;
    for (const auto& p : sep) both.push_back(&p);
    for (const auto& p : pen) both.push_back(&p);
    auto wrongBoolean = [&](int i, const Answer& a) { return (a.value != 0.0) != both[i]->oracle.inside ? 1.0 : 0.0; };
    // Timed as a caller wanting yes / no calls it (no result filled, as the peers' booleans); the
    // support counts come from an untimed pass that asks for the result.
    std::vector<int> supports;
    for (const PolyPair* p : both) {
        GjkResult r;
        gjkIntersect(p->a, p->b, {}, nullptr, &r);
        supports.push_back(r.iterations);
    }
    const size_t intersectReference = rows.size();
    rows.push_back(measure(
        settings, "gjk_intersect", tag + " sep+pen", "SV", static_cast<int>(both.size()),
        [&](int i) { return Answer{gjkIntersect(both[i]->a, both[i]->b) ? 1.0 : 0.0, supports[i]}; }, wrongBoolean,
        true));
    // MPR from the vertex centroids, computed before timing as libccd's MPR gets them (its center
    // callbacks), with GJK's full loop where it cannot prove an answer.
    std::vector<std::pair<Vec3, Vec3>> interiors;
    for (const PolyPair* p : both) interiors.emplace_back(vertexCentroid(p->va), vertexCentroid(p->vb));
    rows.push_back(measure(
        settings, "gjk_intersect", tag + " sep+pen", "MPR", static_cast<int>(both.size()),
        [&](int i) {
            MprResult r;
            const bool hit = mprIntersect(both[i]->a, interiors[i].first, both[i]->b, interiors[i].second, &r);
            return Answer{hit ? 1.0 : 0.0, r.supports};
        },
        wrongBoolean, true));
    peerRows(settings, rows, "gjk_intersect", tag + " sep+pen", both, intersectReference, wrongBoolean, true);
    // Penetration depth (GJK + EPA) on the overlapping pairs.
    std::vector<const PolyPair*> inside;
    for (const auto& p : pen)
        if (p.oracle.ok && p.oracle.inside) inside.push_back(&p);
    auto depthError = [&](int i, const Answer& a) { return relativeError(a.value, inside[i]->oracle.depth, 1.0); };
    const size_t depthReference = rows.size();
    for (double tol : {1e-13, 1e-6, 1e-3}) {
        EpaOptions o;
        o.relativeTolerance = tol;
        rows.push_back(measure(
            settings, "epa_depth", tag + " penetrating", "GJK+EPA tol " + fmt("%.0e", tol),
            static_cast<int>(inside.size()),
            [&, o](int i) {
                const EpaResult r = penetration(inside[i]->a, inside[i]->b, o);
                return Answer{r.depth, r.iterations};
            },
            depthError));
    }
    peerRows(settings, rows, "epa_depth", tag + " penetrating", inside, depthReference, depthError, false);
}

// Boxes: GJK on separated and touching boxes, EPA, boolean GJK and the 15-axis SAT.
void benchBoxes(const Settings& settings, std::vector<Row>& rows) {
    const bool quick = settings.quick;
    const int nPairs = quick ? 200 : 1000;
    std::cerr << "cdlab bench: boxes\n";
    const auto sep = boxPairs(nPairs, 3.0, false, 31);
    const auto pen = boxPairs(nPairs, 0.5, false, 32);
    const auto touch = boxPairs(nPairs, 0.0, true, 33);
    for (const auto* set : {&sep, &touch}) {
        const bool touching = set == &touch;
        rows.push_back(measure(
            settings, "gjk_distance", touching ? "AABB face touching" : "OBB separated", "SV tol 1e-13", nPairs,
            [&](int i) {
                const GjkResult r = gjkDistance((*set)[i].a, (*set)[i].b);
                return Answer{r.distance, r.iterations};
            },
            [&, touching](int i, const Answer& a) {
                // Touching: the exact distance is 0 (the oracle gives 0 up to its rounding);
                // the error is relative to the size (~1), not to 0.
                return touching ? std::abs(a.value) : relativeError(a.value, (*set)[i].oracle.distance, 1.0);
            }));
    }
    std::vector<const OrientedBoxPair*> inside, all;
    for (const auto& p : pen)
        if (p.oracle.ok && p.oracle.inside) inside.push_back(&p);
    for (const auto& p : sep) all.push_back(&p);
    for (const auto& p : pen) all.push_back(&p);
    rows.push_back(measure(
        settings, "epa_depth", "OBB penetrating", "GJK+EPA tol 1e-13", static_cast<int>(inside.size()),
        [&](int i) {
            const EpaResult r = penetration(inside[i]->a, inside[i]->b);
            return Answer{r.depth, r.iterations};
        },
        [&](int i, const Answer& a) { return relativeError(a.value, inside[i]->oracle.depth, 1.0); }));
    rows.push_back(measure(
        settings, "epa_depth", "AABB face touching", "GJK+EPA tol 1e-13", nPairs,
        [&](int i) {
            const EpaResult r = penetration(touch[i].a, touch[i].b);
            return Answer{r.depth, r.iterations};
        },
        [&](int, const Answer& a) { return std::abs(a.value); }));  // exact answer 0; size ~1
    rows.push_back(measure(
        settings, "gjk_intersect", "OBB sep+pen", "SV", static_cast<int>(all.size()),
        [&](int i) {
            GjkResult r;
            const bool hit = gjkIntersect(all[i]->a, all[i]->b, {}, nullptr, &r);
            return Answer{hit ? 1.0 : 0.0, r.iterations};
        },
        [&](int i, const Answer& a) { return (a.value != 0.0) != all[i]->oracle.inside ? 1.0 : 0.0; }, true));
    rows.push_back(measure(
        settings, "sat_obb_obb", "OBB sep+pen", "15 axes", static_cast<int>(all.size()),
        [&](int i) {
            return Answer{testObbObb(all[i]->obbA, all[i]->obbB).hit ? 1.0 : 0.0, 0};
        },
        [&](int i, const Answer& a) { return (a.value != 0.0) != all[i]->oracle.inside ? 1.0 : 0.0; }, true));
}

// Shapes with a margin (spheres, capsules): the core ⊕ radius form first (core/gjk_epa/margins.h,
// what `cdlab query` does: GJK / EPA on the points or segments, the radii in closed form), then the
// full support for contrast (GJK converges linearly on the round part, EPA needs ever more faces),
// at each of `epaTolerances`; each full-support row's ratio against its cores row. Pairs: .a, .b and
// the oracle's signed .distance (negative: the depth).
template <class Pairs>
void marginRows(const Settings& settings, std::vector<Row>& rows, const std::string& shapes, const Pairs& sep,
                const Pairs& pen, const std::vector<double>& epaTolerances) {
    const auto distanceError = [&](int i, const Answer& a) { return relativeError(a.value, sep[i].distance, 1.0); };
    const auto depthError = [&](int i, const Answer& a) { return relativeError(a.value, -pen[i].distance, 1.0); };
    const int nSep = static_cast<int>(sep.size()), nPen = static_cast<int>(pen.size());
    const size_t distanceReference = rows.size();
    rows.push_back(measure(
        settings, "gjk_distance", shapes + " separated", "SV on cores + radii", nSep,
        [&](int i) {
            const GjkResult r = gjkDistanceWithMargins(sep[i].a, sep[i].b);
            return Answer{r.distance, r.iterations};
        },
        distanceError));
    rows.push_back(measure(
        settings, "gjk_distance", shapes + " separated", "SV tol 1e-13, full support", nSep,
        [&](int i) {
            const GjkResult r = gjkDistance(sep[i].a, sep[i].b);
            return Answer{r.distance, r.iterations};
        },
        distanceError));
    rows.back().ratio = rows.back().nsMin / rows[distanceReference].nsMin;
    const size_t depthReference = rows.size();
    rows.push_back(measure(
        settings, "epa_depth", shapes + " penetrating", "GJK+EPA on cores + radii", nPen,
        [&](int i) {
            const EpaResult r = penetrationWithMargins(pen[i].a, pen[i].b);
            return Answer{r.depth, r.iterations};
        },
        depthError));
    for (double tol : epaTolerances) {
        EpaOptions o;
        o.relativeTolerance = tol;
        rows.push_back(measure(
            settings, "epa_depth", shapes + " penetrating", "GJK+EPA tol " + fmt("%.0e", tol) + ", full support", nPen,
            [&, o](int i) {
                const EpaResult r = penetration(pen[i].a, pen[i].b, o);
                return Answer{r.depth, r.iterations};
            },
            depthError));
        rows.back().ratio = rows.back().nsMin / rows[depthReference].nsMin;
    }
}

// Capsules (oracle: long double segment-segment distance minus the radii).
void benchCapsules(const Settings& settings, std::vector<Row>& rows) {
    const bool quick = settings.quick;
    const int nPairs = quick ? 200 : 1000;
    std::cerr << "cdlab bench: capsules\n";
    struct CapsulePair {
        Transformed<CapsuleShape> a, b;
        double distance = 0;  // signed: negative = depth
    };
    auto capsulePairs = [&](double offset, std::uint64_t seed) {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> half(0.2, 1.0), radius(0.1, 0.5);
        std::vector<CapsulePair> pairs;
        for (int i = 0; i < nPairs; ++i) {
            CapsulePair p;
            p.a.shape = CapsuleShape::alongY(half(rng), radius(rng));
            p.b.shape = CapsuleShape::alongY(half(rng), radius(rng));
            p.a.transform.rotation = randomRotation(rng);
            p.b.transform.rotation = randomRotation(rng);
            p.b.transform.position = offset * randomUnit(rng);
            const double seg =
                oracleSegmentDistance(p.a.transform.apply(p.a.shape.a), p.a.transform.apply(p.a.shape.b),
                                      p.b.transform.apply(p.b.shape.a), p.b.transform.apply(p.b.shape.b));
            p.distance = seg - p.a.shape.radius - p.b.shape.radius;
            pairs.push_back(p);
        }
        return pairs;
    };
    const auto sep = capsulePairs(3.0, 51);
    auto pen = capsulePairs(0.3, 52);
    std::erase_if(pen, [](const CapsulePair& p) { return !(p.distance < 0); });
    marginRows(settings, rows, "capsules", sep, pen, {1e-8});
}

// Float vs double: cdlab has no float variant of GJK (core is double only), so this row
// measures what storing the geometry in float does: vertices rounded to float, GJK in double,
// error against the oracle of the double input.
void benchFloatInput(const Settings& settings, std::vector<Row>& rows) {
    const bool quick = settings.quick;
    const int nPairs = quick ? 200 : 1000;
    std::cerr << "cdlab bench: float-rounded input\n";
    const auto sep = polyPairs(16, nPairs, 2.2, 1016);
    std::vector<PolytopeShape> fa, fb;
    auto toFloat = [](std::vector<Vec3> v) {
        for (Vec3& x : v) x = x.cast<float>().cast<double>();
        return v;
    };
    for (const PolyPair& p : sep) {
        fa.push_back(polytopeOf(toFloat(p.va)));
        fb.push_back(polytopeOf(toFloat(p.vb)));
    }
    rows.push_back(measure(
        settings, "gjk_distance", "poly16 separated", "SV, input rounded to float", nPairs,
        [&](int i) {
            const GjkResult r = gjkDistance(fa[i], fb[i]);
            return Answer{r.distance, r.iterations};
        },
        [&](int i, const Answer& a) { return relativeError(a.value, sep[i].oracle.distance, 1.0); }));
}

// Spheres (analytic oracle).
void benchSpheres(const Settings& settings, std::vector<Row>& rows) {
    const bool quick = settings.quick;
    const int nPairs = quick ? 200 : 1000;
    std::cerr << "cdlab bench: spheres\n";
    const auto sep = spherePairs(nPairs, 2.5, 41);
    const auto pen = spherePairs(nPairs, 0.5, 42);
    marginRows(settings, rows, "spheres", sep, pen, {1e-4, 1e-8});
}

/// The query rows (section "queries"): closest point, GJK distance / intersect, GJK+EPA, SAT on
/// polytopes, boxes, capsules, float-rounded input, spheres and cylinders, appended to rows.
void runQueryRows(const Settings& settings, std::vector<Row>& rows) {
    benchClosestPoint(settings, rows);
    const int nPairs = settings.quick ? 200 : 1000;
    const int nLarge = settings.quick ? 60 : 300;  // 64 / 100 vertices: the oracle hull has n^2 points
    for (int nv : {8, 16, 64, 100}) benchPolytopes(settings, nv, nv >= 64 ? nLarge : nPairs, rows);
    benchBoxes(settings, rows);
    benchCapsules(settings, rows);
    benchFloatInput(settings, rows);
    benchSpheres(settings, rows);
    benchCylinders(settings, rows);
}

/// The sections of `cdlab bench`, in the order they run (--only picks some).
constexpr const char* kSections[] = {"queries", "contact", "vclip", "bvh", "broadphase", "world"};

int usage() {
    std::cerr << "usage: cdlab bench [--quick] [--out DIR] [--only SECTION[,SECTION...]]\n"
                 "  time per query (median / min / max over repetitions) and error against independent\n"
                 "  oracles for closest point, GJK intersect / distance, GJK+EPA, SAT OBB-OBB.\n"
                 "  Sections (default: all): queries (those rows), contact (box-box, box-plane and hull-hull\n"
                 "  manifolds beside Bullet's box-box detector, convex-plane algorithm and hull clipping),\n"
                 "  vclip (Lin-Canny and V-Clip vs warm GJK),\n"
                 "  bvh (BVH build / query / refit), broadphase (SAP, uniform grid, octrees, brute force, dynamic tree).\n"
                 "  Writes DIR/bench.json and DIR/bench.md (default DIR: out/bench).\n";
    return 2;
}

/// Parses the --only list ("bvh,broadphase") into `only`; false (after one error line) on an
/// empty or unknown name.
bool parseSections(const std::string& list, std::vector<std::string>& only) {
    std::string all;
    for (const char* s : kSections) all += std::string(all.empty() ? "" : ", ") + s;
    std::size_t from = 0;
    while (true) {
        const std::size_t comma = list.find(',', from);
        const std::string name = list.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
        if (std::find(std::begin(kSections), std::end(kSections), name) == std::end(kSections)) {
            std::cerr << "cdlab bench: unknown section '" << name << "' in --only (sections: " << all << ")\n";
            return false;
        }
        if (std::find(only.begin(), only.end(), name) == only.end()) only.push_back(name);
        if (comma == std::string::npos) return true;
        from = comma + 1;
    }
}

}  // namespace

int runBench(int argc, char** argv) {
    Settings settings;
    std::string outDir = "out/bench";
    std::vector<std::string> only;  // empty: every section
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick") {
            settings.quick = true;
        } else if (arg == "--out" && i + 1 < argc) {
            outDir = argv[++i];
        } else if (arg == "--only" && i + 1 < argc) {
            if (!parseSections(argv[++i], only)) return 2;
        } else if (arg == "-h" || arg == "--help") {
            usage();
            return 0;
        } else {
            std::cerr << "cdlab bench: unknown argument " << arg << "\n";
            return usage();
        }
    }
    const bool quick = settings.quick;
    settings.targetQueries = quick ? 20000 : 100000;
    auto runs = [&](const char* section) {
        return only.empty() || std::find(only.begin(), only.end(), section) != only.end();
    };
    std::string onlyList;  // "bvh,broadphase" as given to --only (empty: all sections)
    for (const std::string& s : only) onlyList += (onlyList.empty() ? "" : ",") + s;
    std::vector<Row> rows;
    const auto start = Clock::now();
    try {
        std::filesystem::create_directories(outDir);  // the sections write their figures as they go
    } catch (const std::exception& e) {
        std::cerr << "cdlab bench: " << e.what() << "\n";
        return 1;
    }

    if (runs("queries")) runQueryRows(settings, rows);
    if (runs("contact")) benchContacts(settings, rows);

    // ---- feature walks: Lin–Canny beside V-Clip and warm GJK over coherence levels ---------------
    std::ostringstream vclipTable;
    if (runs("vclip")) {
        std::cerr << "cdlab bench: Lin–Canny vs V-Clip vs warm GJK\n";
        std::vector<Row> walk = benchLinCanny(settings);
        rows.insert(rows.end(), walk.begin(), walk.end());
        // V-Clip vs GJK, cold and warm, per shape and rotation per call (its own table: CPU time).
        std::cerr << "cdlab bench: V-Clip vs GJK (coherence)\n";
        runVclipBench(quick, vclipTable);
    }
    // A section whose pair sets disagree with brute force makes the run fail (exit 1) after
    // everything is written: the tables say where ("MISMATCH").
    bool pairMismatch = false;
    std::ostringstream bvhTable;  // BVH build / query / refit, figures bvh_*.png
    if (runs("bvh")) {
        std::cerr << "cdlab bench: BVH build / query / refit\n";
        pairMismatch |= runBvhBench(quick, outDir, bvhTable) != 0;
    }
    std::ostringstream broadphaseTable;  // SAP vs grid vs octrees vs brute force, broadphase_*.png
    if (runs("broadphase")) {
        std::cerr << "cdlab bench: broad phase (sweep and prune, grid, octrees, brute force)\n";
        pairMismatch |= runBroadphaseBench(quick, outDir, broadphaseTable) != 0;
        broadphaseTable << "\n";
        pairMismatch |= runTreeBench(quick, broadphaseTable) != 0;
    }

    std::ostringstream worldTable;  // the many-body world beside Bullet's
    if (runs("world") && runWorldBench(quick, worldTable) != 0) return 1;

    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const std::string machine = machineDescription();
    if (!rows.empty()) printTable(rows, std::cout, false);
    if (runs("vclip")) std::cout << "\n" << vclipTable.str();
    if (runs("bvh")) std::cout << "\n" << bvhTable.str();
    if (runs("broadphase")) std::cout << "\n" << broadphaseTable.str();
    if (runs("world")) std::cout << "\n" << worldTable.str();
    std::cout << "machine: " << machine << "; " << fmt("%.1f", seconds) << " s\n";

    std::ostringstream md;
    md << "# cdlab bench" << (quick ? " (--quick)" : "") << (only.empty() ? "" : " (--only " + onlyList + ")") << "\n\n"
       << "Machine: " << machine << ". Release build (-O3, -ffp-contract=off), one thread.\n\n";
    if (!rows.empty()) {
        md << "Time per query: median (min, max) over repetitions of the whole input set, each repetition\n"
           << ">= " << settings.targetQueries / 1000
           << "k queries in total per row. Error: relative, |x - x*| / |x*| against an\n"
           << "independent oracle (hull of the Minkowski difference {a_i - b_j} by core/geometry/convex_hull.h, "
              "distances to its\n"
           << "faces by brute force in long double; spheres analytic; closest points by long double brute force);\n"
           << "touching sets: |x| / size; boolean queries (intersect, SAT): fraction of wrong answers.\n"
           << "time / cdlab: a peer's min time over cdlab's min time (default settings) on the same input.\n"
           << "Inputs: fixed seeds; random polytopes = n points on random ellipsoids (radii 0.3..1), separated\n"
           << "(centres 2.2 apart), penetrating (0.4 apart), moved (same pairs moved by 1e-3: warm start).\n\n";
        printTable(rows, md, true);
    }
    if (runs("vclip")) md << "\n## V-Clip vs GJK over coherence levels\n\n```\n" << vclipTable.str() << "```\n";
    if (runs("bvh")) md << "\n## BVH build, query and refit\n\n```\n" << bvhTable.str() << "```\n";
    if (runs("broadphase"))
        md << "\n## Broad phase: sweep and prune vs uniform grid vs octrees vs brute force\n\n```\n"
           << broadphaseTable.str() << "```\n";
    if (runs("world")) md << "\n## Many-body world beside Bullet\n\n```\n" << worldTable.str() << "```\n";
    md << "\nRun time " << fmt("%.1f", seconds) << " s.\n";
    try {
        nlohmann::json json = toJson(rows, machine, quick);
        if (!only.empty()) json["sections"] = only;  // a partial run says which sections it holds
        render::writeFileAtomic(outDir + "/bench.json", json.dump(2) + "\n");
        render::writeFileAtomic(outDir + "/bench.md", md.str());
    } catch (const std::exception& e) {
        std::cerr << "cdlab bench: " << e.what() << "\n";
        return 1;
    }
    if (!rows.empty()) writeBenchFigures(rows, outDir);
    std::cerr << "cdlab bench: wrote " << outDir << "/bench.json, bench.md"
              << (rows.empty() ? "" : ", pareto_*.png and hist_*.png") << "\n";
    if (pairMismatch) {
        std::cerr << "cdlab bench: a broad or mid phase reported other pairs than brute force (see MISMATCH above)\n";
        return 1;
    }
    return 0;
}

}  // namespace cdlab::demos
