// Accuracy figures for teaching: why GJK's sub-algorithm must be robust.
//
// Each scene runs one small deterministic sweep (fixed seed, a fixed number of pairs per decade of
// the swept parameter; no timings, so the figure and its numbers can be golden) of GJK distance
// queries on pairs of convex polytopes, once with the signed-volumes sub-algorithm (Montanari,
// Petrinic, Barbieri, "Improving the GJK algorithm for faster and more reliable distance
// queries between convex objects", ACM TOG 2017) and once with Johnson's (Gilbert, Johnson,
// Keerthi 1988; van den Bergen §4.3.3), and compares both with an independent long double oracle
// (verification/minkowski_hull_oracle.h: the Minkowski-hull oracle, and the hull-free brute force for small
// separated sets). The error is |d - d*| / L, L = the larger circumradius of the two vertex sets
// (the same measure as `cdlab stress`), so 1e-16 means "as exact as the coordinates allow".
//
// Sweeps ("sweep" key):
//   scale           two 8-vertex polytopes of size s, separated, s = 1e-6 .. 1e6
//   offset          size 1, both placed at distance o from the origin, o = 1 .. 1e9
//   parallel_edges  two thin wedges whose ridges cross at a small angle (1e-9 .. 1e-1 rad), ridges
//                   1e-9 .. 1e-2 apart (separated or overlapping): the case where Johnson's
//                   determinant signs lose their meaning (nearly parallel edges = nearly
//                   degenerate triangles / tetrahedra in A - B)
// Frames: "plot" (median and max error per decade, log-log) or, with "figure": "histogram", the
// decade histogram of every pair's error per method. trace.json holds the plotted numbers.
#include "demos/accuracy/accuracy_demo.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "core/base/tolerances.h"
#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/plot.h"
#include "app/measure/statistics.h"
#include "verification/minkowski_hull_oracle.h"

namespace cdlab::demos {

namespace {

const std::vector<std::string> kLayers = {"plot"};
const std::vector<std::string> kSweeps = {"scale", "offset", "parallel_edges"};

// Errors of exactly 0 are drawn at this floor (a log axis has no 0); 1e-18 is two decades below
// the unit roundoff 1.1e-16, so "exact" and "last-bit" answers stay apart.
constexpr double kErrorFloor = 1e-18;
// The tolerance `cdlab stress` judges GJK distances with (relative to L): drawn as a reference line.
constexpr double kStressTolerance = 1e-12;

// ---- A small portable generator (mt19937_64 is fully specified; the maps below use only IEEE
// arithmetic and libm, unlike std::uniform_real_distribution whose algorithm is unspecified) ----

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1p-53; }
double uniform(std::mt19937_64& rng, double lo, double hi) { return lo + (hi - lo) * uniform01(rng); }

Vec3 randomUnit(std::mt19937_64& rng) {
    const double z = uniform(rng, -1.0, 1.0), phi = uniform(rng, 0.0, 6.283185307179586);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Vec3 perpendicular(const Vec3& u) {
    const Vec3 t = std::abs(u.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
    return u.cross(t).normalized();
}

/// n points on an ellipsoid with radii in [0.3, 1], randomly oriented (all in convex position).
std::vector<Vec3> ellipsoid(std::mt19937_64& rng, int n) {
    const Vec3 radii(uniform(rng, 0.3, 1.0), uniform(rng, 0.3, 1.0), uniform(rng, 0.3, 1.0));
    const Vec3 e0 = randomUnit(rng), e1 = perpendicular(e0), e2 = e0.cross(e1);
    std::vector<Vec3> v;
    for (int i = 0; i < n; ++i) {
        const Vec3 p = radii.cwiseProduct(randomUnit(rng));
        v.push_back(p.x() * e0 + p.y() * e1 + p.z() * e2);
    }
    return v;
}

struct Pair {
    std::vector<Vec3> a, b;
    double param = 0;
};

/// Case `i` of decade `k` (x in [10^k, 10^(k+1))), drawn from (seed, k, i) only.
Pair makePair(const std::string& sweep, std::uint64_t seed, int k, int i) {
    std::mt19937_64 rng(seed * 1000003u + static_cast<std::uint64_t>(k + 100) * 1009u + static_cast<std::uint64_t>(i));
    const double x = std::pow(10.0, k + uniform01(rng));
    Pair p;
    p.param = x;
    if (sweep == "scale") {
        // Radii <= 1 and centres >= 2.05 apart (times s): always separated, distance ~0.05..1 s.
        for (Vec3& v : p.a = ellipsoid(rng, 8)) v *= x;
        const Vec3 shift = uniform(rng, 2.05, 3.0) * randomUnit(rng);
        for (Vec3& v : p.b = ellipsoid(rng, 8)) v = x * (v + shift);
    } else if (sweep == "offset") {
        const Vec3 at = x * randomUnit(rng);
        const Vec3 shift = uniform(rng, 2.05, 3.0) * randomUnit(rng);
        for (Vec3& v : p.a = ellipsoid(rng, 8)) v += at;
        for (Vec3& v : p.b = ellipsoid(rng, 8)) v += at + shift;
    } else {
        // The "nearly parallel edges" family of `cdlab stress`: wedges with ridges of length 2 that
        // cross at angle x, |gap| apart along n; half separated, half overlapping.
        const double gap = std::pow(10.0, uniform(rng, -9.0, -2.0)) * (rng() % 2 ? 1.0 : -1.0);
        const Vec3 e = randomUnit(rng), n = perpendicular(e), m = e.cross(n);
        const Vec3 e2 = Eigen::AngleAxisd(x, n) * e, m2 = e2.cross(n);
        const Vec3 at = uniform(rng, -0.5, 0.5) * e + gap * n;
        p.a = {-e, e, 0.2 * (-n + m), 0.2 * (-n - m)};
        p.b = {at - e2, at + e2, at + 0.2 * (n + m2), at + 0.2 * (n - m2)};
    }
    return p;
}

struct Sample {
    // errorSv / errorJohnson: the plain GJK loop (GjkOptions::refineEdgePairs off), so the
    // sub-algorithms are compared as they are; errorRefined: the default, signed volumes with the
    // edge-pair refinement (core/closest/edge_pair_distance.h).
    double param = 0, errorSv = 0, errorJohnson = 0, errorRefined = 0;
};

struct Decade {
    int k = 0;
    int count = 0;
    double svMedian = 0, svMax = 0, johnsonMedian = 0, johnsonMax = 0, refinedMedian = 0, refinedMax = 0;
    int svOverTolerance = 0, johnsonOverTolerance = 0, refinedOverTolerance = 0;
};

struct Sweep {
    std::vector<Sample> samples;
    std::vector<Decade> decades;
    int oracleFailures = 0;
};

struct Settings {
    std::string sweep = "scale";
    std::string figure = "plot";  // or "histogram"
    int kFrom = -6, kTo = 6;      // decades [10^kFrom, 10^kTo)
    int perDecade = 16;
    std::uint64_t seed = 1;
};

Sweep runSweep(const Settings& s) {
    Sweep out;
    for (int k = s.kFrom; k < s.kTo; ++k) {
        Decade d;
        d.k = k;
        std::vector<double> sv, jo, re;
        for (int i = 0; i < s.perDecade; ++i) {
            const Pair p = makePair(s.sweep, s.seed, k, i);
            const MinkowskiOracle o = minkowskiOracle(p.a, p.b);
            if (!o.ok) {
                ++out.oracleFailures;
                continue;
            }
            // Small separated sets: the hull-free brute force decides (as in `cdlab stress`).
            const double exact = o.inside                             ? 0.0
                                 : p.a.size() <= 6 && p.b.size() <= 6 ? oracleDistanceBruteForce(p.a, p.b)
                                                                      : o.distance;
            const double L = std::max(centroidRadius(p.a), centroidRadius(p.b));
            const PolytopeShape a(p.a), b(p.b);
            Sample smp;
            smp.param = p.param;
            auto error = [&](const GjkOptions& opt) {
                const GjkResult g = gjkDistance(a, b, opt);
                return std::isfinite(g.distance) ? std::abs(g.distance - exact) / L : INFINITY;
            };
            for (const SimplexSolver solver : {SimplexSolver::SignedVolumes, SimplexSolver::Johnson}) {
                GjkOptions opt;
                opt.solver = solver;
                opt.refineEdgePairs = false;
                (solver == SimplexSolver::SignedVolumes ? smp.errorSv : smp.errorJohnson) = error(opt);
            }
            smp.errorRefined = error(GjkOptions{});
            sv.push_back(smp.errorSv);
            jo.push_back(smp.errorJohnson);
            re.push_back(smp.errorRefined);
            d.svOverTolerance += !(smp.errorSv <= kStressTolerance);
            d.johnsonOverTolerance += !(smp.errorJohnson <= kStressTolerance);
            d.refinedOverTolerance += !(smp.errorRefined <= kStressTolerance);
            out.samples.push_back(smp);
        }
        d.count = static_cast<int>(sv.size());
        d.svMedian = median(sv);
        d.johnsonMedian = median(jo);
        d.svMax = sv.empty() ? 0.0 : *std::max_element(sv.begin(), sv.end());
        d.johnsonMax = jo.empty() ? 0.0 : *std::max_element(jo.begin(), jo.end());
        d.refinedMedian = median(re);
        d.refinedMax = re.empty() ? 0.0 : *std::max_element(re.begin(), re.end());
        out.decades.push_back(d);
    }
    return out;
}

/// JSON number, with infinities (a NaN answer) written as null.
Json num(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

std::string xLabelOf(const std::string& sweep) {
    if (sweep == "scale") return "size s of both polytopes (world units)";
    if (sweep == "offset") return "distance from the origin / size";
    return "angle between the two ridges (rad)";
}

class AccuracyScene final : public PreparedScene {
public:
    AccuracyScene(SceneCommon common, Settings settings) : PreparedScene(std::move(common)), s_(settings) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const Sweep sw = runSweep(s_);
        DemoOutput out;
        out.trace = traceJson(sw);
        if (numericOnly(ctx, out)) return out;
        PlotOptions po = scenePlotOptions(common_, figureScale(common_, ctx));
        po.subtitle = common_.caption;
        po.legendWidth = 250;
        po.xFloor = po.yFloor = kErrorFloor;
        Frame f;
        if (s_.figure == "histogram") {
            po.xLabel = "|d - d*| / size, decade bins (0 counted in the first bin)";
            po.yLabel = "fraction of pairs";
            std::vector<double> sv, jo, re;
            for (const Sample& x : sw.samples)
                sv.push_back(x.errorSv), jo.push_back(x.errorJohnson), re.push_back(x.errorRefined);
            int svOver = 0, joOver = 0, reOver = 0;
            for (const Sample& x : sw.samples)
                svOver += !(x.errorSv <= kStressTolerance), joOver += !(x.errorJohnson <= kStressTolerance),
                    reOver += !(x.errorRefined <= kStressTolerance);
            const bool withRefined = s_.sweep == "parallel_edges";
            po.subtitle += "; over 1e-12: Johnson " + std::to_string(joOver) + ", signed volumes " +
                           std::to_string(svOver) +
                           (withRefined ? ", + edge pairs " + std::to_string(reOver) : std::string()) + " of " +
                           std::to_string(sw.samples.size()) + " pairs";
            f.name = "histogram";
            f.caption = common_.title;
            std::vector<std::pair<std::string, std::vector<double>>> groups = {{"signed volumes", sv}, {"Johnson", jo}};
            if (withRefined) groups.push_back({"SV + edge pairs (default)", re});
            f.image = drawDecadeHistogram(*ctx.gl, po, groups);
        } else {
            po.xLabel = xLabelOf(s_.sweep);
            if (s_.sweep != "parallel_edges") po.subtitle += "; " + worstLine(sw);  // that one's caption ranks solvers
            po.yLabel = "|d - d*| / size (0 drawn at 1e-18)";
            po.hLines.push_back({kStressTolerance, "1e-12: cdlab stress tolerance"});
            po.hLines.push_back({kUnitRoundoff, "u = 1.1e-16 (double rounding)"});
            PlotSeries svMed{"signed volumes, median", 0, true, true, {}, {}};
            PlotSeries svMax{"signed volumes, max", 4, true, true, {}, {}};
            PlotSeries joMed{"Johnson, median", 1, true, true, {}, {}};
            PlotSeries joMax{"Johnson, max", 5, true, true, {}, {}};
            for (const Decade& d : sw.decades) {
                if (d.count == 0) continue;
                const double x = std::pow(10.0, d.k + 0.5);  // decade centre on the log axis
                auto y = [](double e) { return std::isfinite(e) ? std::max(e, kErrorFloor) : 1.0; };
                svMed.points.emplace_back(x, y(d.svMedian));
                svMax.points.emplace_back(x, y(d.svMax));
                joMed.points.emplace_back(x, y(d.johnsonMedian));
                joMax.points.emplace_back(x, y(d.johnsonMax));
            }
            std::vector<PlotSeries> series = {joMax, joMed, svMax, svMed};
            if (s_.sweep == "parallel_edges") {
                // The default GJK: the terminal edge pair recomputed in double-double.
                PlotSeries reMax{"SV + edge pairs (default), max", 2, true, true, {}, {}};
                for (const Decade& d : sw.decades) {
                    if (d.count == 0) continue;
                    reMax.points.emplace_back(std::pow(10.0, d.k + 0.5), std::max(d.refinedMax, kErrorFloor));
                }
                series.push_back(reMax);
                // Conditioning of the sliver triangles of A - B: barycentric weights from edges at
                // angle theta carry a relative error ~u / theta, so ~u / theta * L is the floor of
                // any double-precision simplex solve (no solver can do better without more bits).
                PlotSeries cond{"u / angle (sliver floor)", 6, true, false, {}, {}};
                for (int k = s_.kFrom; k <= s_.kTo; ++k)
                    cond.points.emplace_back(std::pow(10.0, k), 0x1p-53 / std::pow(10.0, k));
                series.push_back(cond);
            }
            f.name = "plot";
            f.caption = common_.title;
            f.image = drawLogLogPlot(*ctx.gl, po, series);
        }
        out.frames.push_back(std::move(f));
        return out;
    }

private:
    /// The sweep's measured worst error over both solvers, printed after the caption (the caption's
    /// claim is the scene author's, checked by tests/demos/accuracy/accuracy_claims_test.cpp; this
    /// number is the trace's larger "…_worst").
    static std::string worstLine(const Sweep& sw) {
        double worst = 0;
        for (const Decade& d : sw.decades) worst = std::max({worst, d.svMax, d.johnsonMax});
        return "worst " + formatNumber(worst);
    }

    Json traceJson(const Sweep& sw) const {
        Json t = Json::object();
        t["sweep"] = s_.sweep;
        t["seed"] = s_.seed;
        t["pairs_per_decade"] = s_.perDecade;
        t["x"] = xLabelOf(s_.sweep);
        t["error"] = "|d - d*| / L, d* = long double oracle, L = larger circumradius";
        t["oracle_failures"] = sw.oracleFailures;
        Json decades = Json::array();
        double svWorst = 0, joWorst = 0, reWorst = 0;
        int svOver = 0, joOver = 0, reOver = 0;
        const bool withRefined = s_.sweep == "parallel_edges";
        for (const Decade& d : sw.decades) {
            Json decade = {{"from", std::pow(10.0, d.k)},
                           {"pairs", d.count},
                           {"signed_volumes",
                            {{"median", num(d.svMedian)}, {"max", num(d.svMax)}, {"over_1e-12", d.svOverTolerance}}},
                           {"johnson",
                            {{"median", num(d.johnsonMedian)},
                             {"max", num(d.johnsonMax)},
                             {"over_1e-12", d.johnsonOverTolerance}}}};
            if (withRefined)
                decade["edge_pairs"] = {{"median", num(d.refinedMedian)},
                                        {"max", num(d.refinedMax)},
                                        {"over_1e-12", d.refinedOverTolerance}};
            decades.push_back(decade);
            svWorst = std::max(svWorst, d.svMax);
            joWorst = std::max(joWorst, d.johnsonMax);
            reWorst = std::max(reWorst, d.refinedMax);
            svOver += d.svOverTolerance;
            joOver += d.johnsonOverTolerance;
            reOver += d.refinedOverTolerance;
        }
        if (withRefined) {
            t["edge_pairs_worst"] = num(reWorst);
            t["edge_pairs_over_1e-12"] = reOver;
        }
        t["decades"] = decades;
        t["signed_volumes_worst"] = num(svWorst);
        t["johnson_worst"] = num(joWorst);
        t["signed_volumes_over_1e-12"] = svOver;
        t["johnson_over_1e-12"] = joOver;
        if (s_.figure == "histogram") {
            // Pairs per decade bin of the error (bin k: [10^k, 10^(k+1)), zeros in the floor bin).
            auto bins = [&](double Sample::*error) {
                Json b = Json::object();
                for (const Sample& x : sw.samples) {
                    const double e = x.*error;
                    const std::string key = !std::isfinite(e) ? "nan"
                                            : e <= kErrorFloor
                                                ? "<=1e-18"
                                                : "1e" + std::to_string(static_cast<int>(std::floor(std::log10(e))));
                    b[key] = b.value(key, 0) + 1;
                }
                return b;
            };
            t["histogram"] = {{"signed_volumes", bins(&Sample::errorSv)}, {"johnson", bins(&Sample::errorJohnson)}};
            if (withRefined) t["histogram"]["edge_pairs"] = bins(&Sample::errorRefined);
        }
        return t;
    }

    Settings s_;
};

class AccuracyDemo final : public Demo {
public:
    std::string name() const override { return "accuracy"; }
    std::string description() const override {
        return "GJK distance error vs scale, offset and edge angle: signed volumes vs Johnson against a long double "
               "oracle";
    }
    SceneFormat sceneFormat() const override { return {kLayers, ImageSettings{1024, 768}, {480, 360}, "plots"}; }
    std::unique_ptr<PreparedScene> readScene(ObjectReader& r, SceneCommon common) const override {
        Settings s;
        s.sweep = r.get("sweep").asEnum(kSweeps);
        if (s.sweep == "offset") s.kFrom = 0, s.kTo = 9;
        if (s.sweep == "parallel_edges") s.kFrom = -9, s.kTo = -1;
        if (auto d = r.find("decades")) {
            // [first, last): x runs over [10^first, 10^last).
            if (d->size() != 2) d->fail("expected [first, last] decade exponents");
            s.kFrom = d->at(0).asInt(-12, 11);
            s.kTo = d->at(1).asInt(s.kFrom + 1, 12);
        }
        if (auto n = r.find("pairs_per_decade")) s.perDecade = n->asInt(1, 200);
        if (auto seed = r.find("seed")) s.seed = static_cast<std::uint64_t>(seed->asInt(0, 1 << 30));
        if (auto f = r.find("figure")) s.figure = f->asEnum({"plot", "histogram"});
        r.finish();
        return std::make_unique<AccuracyScene>(std::move(common), s);
    }
};

}  // namespace

const Demo& accuracyDemo() {
    static const AccuracyDemo demo;
    return demo;
}

}  // namespace cdlab::demos
