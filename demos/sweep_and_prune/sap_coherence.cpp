#include "demos/sweep_and_prune/sap_coherence.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "app/scene/scene_limits.h"
#include "core/broadphase/sweep_and_prune.h"
#include "demos/draw/figure_canvas.h"
#include "demos/draw/figure_style.h"
#include "demos/draw/plot.h"

namespace cdlab::demos {

namespace {

/// A double in [a, b) from mt19937's raw 32-bit output (fixed by the standard, unlike distributions).
double uniform(std::mt19937& g, double a, double b) { return a + (b - a) * (double(g()) / 4294967296.0); }

}  // namespace

CoherenceBoxes coherenceBoxes(int n, double speed, double density, unsigned seed) {
    std::mt19937 g(seed + 7919u * static_cast<unsigned>(n));
    CoherenceBoxes b;
    b.side = std::cbrt(n / density);
    for (int i = 0; i < n; ++i) {
        b.centres.push_back(
            Vec3(uniform(g, 0.5, b.side - 0.5), uniform(g, 0.5, b.side - 0.5), uniform(g, 0.5, b.side - 0.5)));
        Vec3 d;
        do d = Vec3(uniform(g, -1, 1), uniform(g, -1, 1), uniform(g, -1, 1));
        while (!(d.squaredNorm() > 1e-4 && d.squaredNorm() <= 1));  // uniform direction by rejection
        b.velocities.push_back(speed * d.normalized());
    }
    return b;
}

std::vector<Aabb> CoherenceBoxes::at(int f) const {
    const double w = side - 1;  // the range of a centre, [0.5, side - 0.5]
    std::vector<Aabb> boxes;
    boxes.reserve(centres.size());
    for (std::size_t i = 0; i < centres.size(); ++i) {
        Vec3 c;
        for (int k = 0; k < 3; ++k) {
            // A triangle wave of period 2w: the straight path folded back at each wall.
            double m = std::fmod(centres[i][k] - 0.5 + f * velocities[i][k], 2 * w);
            if (m < 0) m += 2 * w;
            c[k] = 0.5 + (m <= w ? m : 2 * w - m);
        }
        boxes.push_back(Aabb{c - Vec3::Constant(0.5), c + Vec3::Constant(0.5)});
    }
    return boxes;
}

double CoherenceRun::swapsPerObject() const {
    double total = 0;
    for (long long s : swaps) total += static_cast<double>(s);
    return swaps.empty() ? 0.0 : total / static_cast<double>(swaps.size()) / n;
}

std::vector<CoherenceRun> runCoherence(const CoherenceSettings& s) {
    std::vector<CoherenceRun> runs;
    for (double speed : s.speeds)
        for (int n : s.counts) {
            const CoherenceBoxes b = coherenceBoxes(n, speed, s.density, s.seed);
            CoherenceRun run;
            run.n = n;
            run.speed = speed;
            run.side = b.side;
            SweepAndPrune sap;
            sap.build(b.at(0));
            run.pairs.push_back(static_cast<int>(sap.pairs().size()));
            for (int f = 1; f <= s.updates; ++f) {
                const SapResult r = sap.update(b.at(f));  // untraced: a trace would hold every swap
                run.swaps.push_back(r.swaps);
                for (int k = 0; k < 3; ++k) run.swapsAxis.push_back(r.swapsPerAxis[k]);
                run.pairs.push_back(static_cast<int>(sap.pairs().size()));
            }
            runs.push_back(std::move(run));
        }
    return runs;
}

namespace {

class CoherenceScene final : public PreparedScene {
public:
    CoherenceScene(SceneCommon common, CoherenceSettings s) : PreparedScene(std::move(common)), s_(std::move(s)) {}

    DemoOutput execute(const RunContext& ctx) const override {
        const std::vector<CoherenceRun> runs = runCoherence(s_);
        DemoOutput out;
        out.trace = traceJson(runs);
        if (numericOnly(ctx, out)) return out;
        PlotOptions po = scenePlotOptions(common_, figureScale(common_, ctx));
        po.legendWidth = 270;
        po.xLabel = "boxes n (unit cubes, density " + formatNumber(s_.density) + " per unit volume)";
        po.yLabel = "insertion-sort swaps per box per update (speed: box sides per update)";
        po.xFloor = 1;
        po.yFloor = 1e-3;
        std::vector<PlotSeries> series;
        // Slow to fast: blue, bluish green, orange, vermillion (not yellow, faint on white).
        static constexpr int kStyles[kMaxCoherenceSpeeds] = {1, 2, 0, 5};
        int style = 0;
        for (double speed : s_.speeds) {
            const double sl = slope(runs, speed);
            PlotSeries p{"speed " + formatNumber(speed) + (std::isnan(sl) ? ": no slope (0 swaps)" : ": slope " + formatNumber(sl)),
                         kStyles[style++], true, true, {}, {}};
            for (const CoherenceRun& r : runs)
                if (r.speed == speed) p.points.emplace_back(r.n, std::max(r.swapsPerObject(), po.yFloor));
            series.push_back(std::move(p));
        }
        // What a full re-sort of the three axes costs per box: 2n endpoints, ~2n log2(2n) comparisons
        // per axis. Where a speed's swaps reach it, coherence has nothing left to save.
        PlotSeries full{"full re-sort: 6 log₂(2n) comparisons", 6, true, false, {}, {}};
        for (int n : s_.counts) full.points.emplace_back(n, 6 * std::log2(2.0 * n));
        series.push_back(std::move(full));
        po.subtitle = common_.caption;
        Frame f;
        f.name = "plot";
        f.caption = common_.title;
        f.image = drawLogLogPlot(*ctx.gl, po, series);
        out.frames.push_back(std::move(f));
        return out;
    }

private:
    CoherenceSettings s_;

    /// The log-log slope of swaps per box between the smallest and the largest n at one speed, to two
    /// decimals (the legend's "slope"); NaN (trace null, legend "no slope") when an end made no swaps.
    static double slope(const std::vector<CoherenceRun>& runs, double speed) {
        const CoherenceRun* lo = nullptr;
        const CoherenceRun* hi = nullptr;
        for (const CoherenceRun& r : runs)
            if (r.speed == speed) {
                if (!lo || r.n < lo->n) lo = &r;
                if (!hi || r.n > hi->n) hi = &r;
            }
        if (!lo || hi->n == lo->n || !(lo->swapsPerObject() > 0) || !(hi->swapsPerObject() > 0)) return NAN;
        return std::round(100 * std::log(hi->swapsPerObject() / lo->swapsPerObject()) / std::log(double(hi->n) / lo->n)) /
               100;
    }

    Json traceJson(const std::vector<CoherenceRun>& runs) const {
        Json t = Json::object();
        t["density"] = s_.density;
        t["seed"] = s_.seed;
        t["updates"] = s_.updates;
        Json rs = Json::array();
        for (const CoherenceRun& r : runs)
            rs.push_back({{"n", r.n},
                          {"speed", r.speed},
                          {"side", r.side},
                          {"swaps", r.swaps},
                          {"swaps_per_axis", r.swapsAxis},
                          {"pairs", r.pairs},
                          {"swaps_per_box", r.swapsPerObject()},
                          {"slope", std::isnan(slope(runs, r.speed)) ? Json(nullptr) : Json(slope(runs, r.speed))},
                          {"full_resort_per_box", 6 * std::log2(2.0 * r.n)}});
        t["runs"] = rs;
        return t;
    }
};

}  // namespace

std::unique_ptr<PreparedScene> readCoherenceScene(ObjectReader& r, SceneCommon common) {
    CoherenceSettings s;
    if (auto c = r.find("counts")) {
        if (c->size() < 2 || c->size() > static_cast<std::size_t>(kMaxCoherenceCounts))
            c->fail("expected 2 to " + std::to_string(kMaxCoherenceCounts) + " box counts");
        s.counts.clear();
        for (const JsonNode& n : c->items()) {
            s.counts.push_back(n.asInt(2, kMaxCoherenceBoxes));
            if (s.counts.size() > 1 && s.counts.back() <= s.counts[s.counts.size() - 2])
                n.fail("box counts must increase (the slope is taken from the first to the last)");
        }
    }
    if (auto v = r.find("speeds")) {
        if (v->size() < 1 || v->size() > static_cast<std::size_t>(kMaxCoherenceSpeeds))
            v->fail("expected 1 to " + std::to_string(kMaxCoherenceSpeeds) + " speeds");
        s.speeds.clear();
        for (const JsonNode& x : v->items()) {
            const double speed = x.asPositive();
            if (speed > 4) x.fail("a speed is at most 4 box sides per update");
            s.speeds.push_back(speed);
        }
    }
    if (auto u = r.find("updates")) s.updates = u->asInt(1, 10);
    if (auto d = r.find("density")) {
        s.density = d->asPositive();
        if (s.density > 0.5 || s.density < 1e-4)
            d->fail("density is between 1e-4 and 0.5 cubes per unit volume (a full container cannot move)");
    }
    if (auto sd = r.find("seed")) s.seed = static_cast<unsigned>(sd->asInt(0, 1 << 30));
    // The swaps, estimated before any work: per update and box about 3 axes × 2 endpoints × speed ×
    // the endpoint density 2n / side (an upper estimate: the golden scene makes a third of it).
    double estimate = 0;
    for (double speed : s.speeds)
        for (int n : s.counts) estimate += s.updates * 3.0 * 2 * n * speed * (2.0 * n / std::cbrt(n / s.density));
    requireAtMost(r.node(), estimate, kMaxCoherenceSwapEstimate, "the estimated insertion-sort swaps",
                  "each is one step of the sort: lower counts, speeds or updates");
    r.finish();
    return std::make_unique<CoherenceScene>(std::move(common), std::move(s));
}

}  // namespace cdlab::demos
