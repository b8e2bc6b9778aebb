// Sweep and prune vs uniform grid vs octrees vs brute force (see bench_broadphase.h).
//
// Scene: n boxes, half extents uniform in [0.25, 0.75] (mean size 1), centres uniform in a cube of
// side L = (n / 0.05)^(1/3) (0.05 boxes per unit volume: about 0.2 n overlapping pairs), each with
// a constant velocity of up to 0.05 per axis per frame (5% of a box size: coherent), bouncing off
// the walls. Every frame the same boxes go to every method, one after the other.
#include "app/bench/bench_broadphase.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <random>
#include <vector>

#include "core/base/aabb_ops.h"
#include "core/broadphase/octree.h"
#include "core/broadphase/sweep_and_prune.h"
#include "core/broadphase/uniform_grid.h"
#include "app/bench/box_motion.h"
#include "app/bench/bench_measure.h"
#include "demos/draw/plot.h"
#include "app/measure/statistics.h"
#include "render/image.h"

namespace cdlab::demos {

namespace {

/// The O(n^2) baseline: every pair, closed overlap test on the three axes.
std::size_t bruteForce(const std::vector<Aabb>& b, std::vector<BoxPair>& out) {
    out.clear();
    const int n = static_cast<int>(b.size());
    for (int i = 0; i < n; ++i) {
        const Aabb& p = b[i];
        for (int j = i + 1; j < n; ++j) {
            const Aabb& q = b[j];
            if (overlaps(p, q)) out.push_back(BoxPair{i, j});
        }
    }
    return out.size();
}

/// The octrees' pairs as sorted keys, as pairKeys (app/bench/box_motion.h) for BoxPair lists.
std::vector<std::uint64_t> octreePairKeys(const std::vector<std::pair<int, int>>& pairs) {
    std::vector<std::uint64_t> keys;
    keys.reserve(pairs.size());
    for (const auto& [a, b] : pairs) keys.push_back(BoxPair::make(a, b).key());
    std::sort(keys.begin(), keys.end());
    return keys;
}

struct Result {
    int n = 0;
    double pairs = 0, swaps = 0;  // mean per frame
    double sapMs = 0, gridMs = 0, bruteMs = NAN, buildMs = 0;
    double octMs = NAN, looseMs = NAN;    // octree build + overlappingPairs, classic / loose (k = 2)
    double octTests = 0, looseTests = 0;  // mean box-box tests per frame
    double octRoot = 0, looseRoot = 0;    // mean objects stored at the root
    double octDepth = 0, looseDepth = 0;  // mean depth of an object's node
    double slowSwaps = 0, slowSapMs = 0;  // SAP alone with speed 0.05 (100 / n)^(2/3): swaps per box ~constant
    int frames = 0, bruteFrames = 0, octFrames = 0;
    int setChecks = 0;  // frames on which every method's pair set was compared with brute force's
    bool agree = true;
};

// Octrees as used here: split a node holding more than 8 objects, down to depth 10 (cells of
// L / 1024, far below the box size: the leaf size, not the depth cap, stops the recursion).
OctreeOptions octreeOptions(double looseness) {
    OctreeOptions o;
    o.maxDepth = 10;
    o.maxObjectsPerLeaf = 8;
    o.looseness = looseness;
    return o;
}

double meanObjectDepth(const Octree& tree) {
    const OctreeStats st = tree.stats();
    double sum = 0, count = 0;
    for (std::size_t d = 0; d < st.objectsPerDepth.size(); ++d) {
        sum += static_cast<double>(d) * st.objectsPerDepth[d];
        count += st.objectsPerDepth[d];
    }
    return count > 0 ? sum / count : 0.0;
}

/// octFrames: frames (after the warm-up) on which the octrees run; bruteFrames likewise.
// One frame of both octrees, rebuilt from scratch (tight: looseness 1, loose: 2), timed apart.
struct OctreeFrame {
    double octMs = 0.0, looseMs = 0.0;
    std::int64_t octTests = 0, looseTests = 0;
    bool ok = true;  ///< both builds succeeded
};

OctreeFrame octreeFrame(const std::vector<Aabb>& boxes, Octree& octree, Octree& loose,
                        std::vector<std::pair<int, int>>& octPairs, std::vector<std::pair<int, int>>& loosePairs) {
    const OctreeOptions octOptions = octreeOptions(1.0), looseOptions = octreeOptions(2.0);
    OctreeFrame o;
    double t0 = threadMilliseconds();
    octree.build(boxes, octOptions);
    octPairs = octree.overlappingPairs(&o.octTests);
    o.octMs = millisecondsSince(t0);
    t0 = threadMilliseconds();
    loose.build(boxes, looseOptions);
    loosePairs = loose.overlappingPairs(&o.looseTests);
    o.looseMs = millisecondsSince(t0);
    o.ok = octree.status() == OctreeStatus::Ok && loose.status() == OctreeStatus::Ok;
    return o;
}

// The same boxes with velocities scaled so that the endpoint gaps crossed per frame stay constant
// (projected endpoint density grows as n / side = n^(2/3)): SAP's s = O(n) regime.
void measureSlowSap(int n, int frames, int warmup, std::vector<Aabb>& boxes, Result& r) {
    BoxMotion slow(n, 1000 + static_cast<std::uint64_t>(n), kBoxSpeed * std::pow(100.0 / n, 2.0 / 3.0));
    slow.step(boxes);
    SweepAndPrune sapSlow;
    sapSlow.reserve(n, n);
    sapSlow.build(boxes);
    std::vector<double> sapT;
    double swaps = 0;
    for (int f = 0; f < warmup + frames; ++f) {
        slow.step(boxes);
        const double t0 = threadMilliseconds();
        const SapResult s = sapSlow.update(boxes);
        const double t = millisecondsSince(t0);
        if (f < warmup) continue;
        sapT.push_back(t);
        swaps += static_cast<double>(s.swaps);
    }
    r.slowSapMs = median(sapT);
    r.slowSwaps = swaps / frames;
}

Result measure(int n, int frames, int bruteFrames, int octFrames) {
    Result r;
    r.n = n;
    r.frames = frames;
    BoxMotion motion(n, 1000 + static_cast<std::uint64_t>(n), kBoxSpeed);
    std::vector<Aabb> boxes;
    motion.step(boxes);
    SweepAndPrune sap;
    sap.reserve(n, n);
    double t0 = threadMilliseconds();
    sap.build(boxes);
    r.buildMs = millisecondsSince(t0);
    UniformGrid grid;
    UniformGridOptions go;
    go.cellSize = 1.5;  // the largest box size: each box touches at most 8 cells
    Octree octree, loose;
    std::vector<std::pair<int, int>> octPairs, loosePairs;
    std::vector<BoxPair> brute;
    brute.reserve(n);
    std::vector<double> sapT, gridT, bruteT, octT, looseT;
    double pairs = 0, swaps = 0;
    const int warmup = 3;
    for (int f = 0; f < warmup + frames; ++f) {
        motion.step(boxes);
        t0 = threadMilliseconds();
        const SapResult s = sap.update(boxes);
        const double tSap = millisecondsSince(t0);
        t0 = threadMilliseconds();
        const UniformGridResult g = grid.build(boxes, go);
        const double tGrid = millisecondsSince(t0);
        if (s.status != SapStatus::Ok || g.status != GridStatus::Ok || sap.pairs().size() != grid.pairs().size())
            r.agree = false;
        // Octrees, rebuilt from scratch every frame like the grid (the warm-up frames always run).
        const bool octFrame = f - warmup < octFrames;
        if (octFrame) {
            const OctreeFrame o = octreeFrame(boxes, octree, loose, octPairs, loosePairs);
            if (!o.ok || octPairs.size() != sap.pairs().size() || loosePairs.size() != sap.pairs().size())
                r.agree = false;
            if (f >= warmup) {
                octT.push_back(o.octMs);
                looseT.push_back(o.looseMs);
                r.octTests += static_cast<double>(o.octTests);
                r.looseTests += static_cast<double>(o.looseTests);
                r.octRoot += octree.stats().objectsAtRoot;
                r.looseRoot += loose.stats().objectsAtRoot;
                r.octDepth += meanObjectDepth(octree);
                r.looseDepth += meanObjectDepth(loose);
            }
        }
        if (f < warmup) continue;
        sapT.push_back(tSap);
        gridT.push_back(tGrid);
        pairs += static_cast<double>(sap.pairs().size());
        swaps += static_cast<double>(s.swaps);
        if (f - warmup < bruteFrames) {
            t0 = threadMilliseconds();
            const std::size_t k = bruteForce(boxes, brute);
            bruteT.push_back(millisecondsSince(t0));
            if (k != sap.pairs().size()) r.agree = false;
            // The pair sets themselves (not only their sizes) against brute force's, outside the timing.
            const std::vector<std::uint64_t> truth = pairKeys(brute);
            bool same = pairKeys(sap.pairs()) == truth && pairKeys(grid.pairs()) == truth;
            if (octFrame) same = same && octreePairKeys(octPairs) == truth && octreePairKeys(loosePairs) == truth;
            if (!same) r.agree = false;
            if (octFrame) ++r.setChecks;
        }
    }
    r.pairs = pairs / frames;
    r.swaps = swaps / frames;
    r.sapMs = median(sapT);
    r.gridMs = median(gridT);
    r.bruteMs = median(bruteT);
    r.bruteFrames = static_cast<int>(bruteT.size());
    r.octMs = median(octT);
    r.looseMs = median(looseT);
    r.octFrames = static_cast<int>(octT.size());
    if (r.octFrames > 0) {
        for (double* x : {&r.octTests, &r.looseTests, &r.octRoot, &r.looseRoot, &r.octDepth, &r.looseDepth})
            *x /= r.octFrames;
    }
    measureSlowSap(n, frames, warmup, boxes, r);
    return r;
}

/// Log-log slope of the brute-force time between the first and the last n where it was measured.
double bruteSlope(const std::vector<Result>& rs) {
    const Result* last = &rs.front();
    for (const Result& r : rs)
        if (std::isfinite(r.bruteMs)) last = &r;
    return std::log(last->bruteMs / rs.front().bruteMs) / std::log(static_cast<double>(last->n) / rs.front().n);
}

/// Log-log slope of y against n between the first and the last result.
double slope(const std::vector<Result>& rs, double Result::*y) {
    const Result& a = rs.front();
    const Result& b = rs.back();
    return std::log(b.*y / a.*y) / std::log(static_cast<double>(b.n) / a.n);
}

void writeFigures(const std::vector<Result>& results, bool quick, int bruteLimit, const std::string& outDir) {
    std::unique_ptr<render::GlContext> gl;
    try {
        gl = render::GlContext::create();
    } catch (const std::exception& e) {
        std::cerr << "cdlab bench: no broad-phase figures (" << e.what() << ")\n";
        return;
    }
    PlotSeries sap{"SAP update (insertion sort)", 0, true, true, {}, {}};
    PlotSeries grid{"uniform grid, rebuilt", 1, true, true, {}, {}};
    PlotSeries brute{"brute force, all pairs", 2, true, true, {}, {}};
    PlotSeries octree{"octree, classic, rebuilt", 3, true, true, {}, {}};
    PlotSeries loose{"loose octree (k = 2), rebuilt", 5, true, true, {}, {}};
    PlotSeries slowSap{"SAP, slow motion", 4, true, true, {}, {}};
    // Both references in one colour (lines without markers; their labels and slopes tell them apart).
    PlotSeries refN{"O(n) reference", 6, true, false, {}, {}};
    PlotSeries refN2{"O(n^2) reference", 6, true, false, {}, {}};
    for (const Result& r : results) {
        sap.points.emplace_back(r.n, r.sapMs);
        grid.points.emplace_back(r.n, r.gridMs);
        slowSap.points.emplace_back(r.n, r.slowSapMs);
        if (std::isfinite(r.bruteMs)) brute.points.emplace_back(r.n, r.bruteMs);
        if (std::isfinite(r.octMs)) octree.points.emplace_back(r.n, r.octMs);
        if (std::isfinite(r.looseMs)) loose.points.emplace_back(r.n, r.looseMs);
    }
    // Reference slopes anchored at the smallest n: through the grid's time (slope 1) and brute force's (slope 2).
    const Result& r0 = results.front();
    for (const Result& r : results) {
        const double x = static_cast<double>(r.n) / r0.n;
        refN.points.emplace_back(r.n, r0.gridMs * x);
        if (std::isfinite(r0.bruteMs) && r.n <= bruteLimit) refN2.points.emplace_back(r.n, r0.bruteMs * x * x);
    }
    char sub[256];
    std::snprintf(sub, sizeof sub,
                  "Slopes: SAP %.2f (slow %.2f), grid %.2f, octree %.2f, loose %.2f, brute force %.2f (to n = %d).%s",
                  slope(results, &Result::sapMs), slope(results, &Result::slowSapMs), slope(results, &Result::gridMs),
                  slope(results, &Result::octMs), slope(results, &Result::looseMs), bruteSlope(results), bruteLimit,
                  quick ? " Quick run." : "");
    PlotOptions po;
    po.title = "Broad phase: time per frame vs number of boxes (coherent motion)";
    po.subtitle = sub;
    po.xLabel = "boxes n";
    po.yLabel = "ms per frame (median thread CPU, shared 2-core box)";
    po.width = 1024;
    po.height = 768;
    po.legendWidth = 260;
    try {
        render::writePngAtomic(outDir + "/broadphase_time.png",
                               drawLogLogPlot(*gl, po, {sap, slowSap, grid, octree, loose, brute, refN, refN2}));
        // Colours as in the time figure (SAP, slow SAP, grid, octrees); SAP / (n + k) takes brute force's.
        PlotSeries sapWork{"SAP / (n + k + swaps)", 0, true, true, {}, {}};
        PlotSeries sapPer{"SAP / (n + k)", 2, true, true, {}, {}};
        PlotSeries gridPer{"uniform grid / (n + k)", 1, true, true, {}, {}};
        PlotSeries swapsPer{"swaps per box (count)", 6, true, true, {}, {}};
        PlotSeries slowWork{"SAP slow / (n + k)", 4, true, true, {}, {}};
        PlotSeries octPer{"octree / (n + k)", 3, true, true, {}, {}};
        PlotSeries loosePer{"loose octree / (n + k)", 5, true, true, {}, {}};
        for (const Result& r : results) {
            sapWork.points.emplace_back(r.n, 1e6 * r.sapMs / (r.n + r.pairs + r.swaps));
            sapPer.points.emplace_back(r.n, 1e6 * r.sapMs / (r.n + r.pairs));
            gridPer.points.emplace_back(r.n, 1e6 * r.gridMs / (r.n + r.pairs));
            swapsPer.points.emplace_back(r.n, r.swaps / r.n);
            slowWork.points.emplace_back(r.n, 1e6 * r.slowSapMs / (r.n + r.pairs));
            if (std::isfinite(r.octMs)) octPer.points.emplace_back(r.n, 1e6 * r.octMs / (r.n + r.pairs));
            if (std::isfinite(r.looseMs)) loosePer.points.emplace_back(r.n, 1e6 * r.looseMs / (r.n + r.pairs));
        }
        PlotOptions pp = po;
        pp.title = "Broad phase: cost per unit of work, k = overlapping pairs";
        pp.subtitle =
            "SAP / (n + k + s) flat: O(n + s + k); s / n grows ~n^(2/3) at constant density, unless motion slows "
            "(slow)";
        pp.yLabel = "ns per item (swaps per box: count)";
        render::writePngAtomic(
            outDir + "/broadphase_per_item.png",
            drawLogLogPlot(*gl, pp, {sapWork, sapPer, slowWork, gridPer, octPer, loosePer, swapsPer}));
    } catch (const std::exception& e) {
        std::cerr << "cdlab bench: " << e.what() << "\n";
    }
}

}  // namespace

int runBroadphaseBench(bool quick, const std::string& outDir, std::ostream& table) {
    const std::vector<int> sizes = quick ? std::vector<int>{100, 300, 1000, 3000, 10000}
                                         : std::vector<int>{100, 300, 1000, 3000, 10000, 30000, 100000};
    const int bruteLimit = quick ? 10000 : 30000;
    std::vector<Result> results;
    bool agree = true;
    int setChecks = 0;
    for (int n : sizes) {
        std::cerr << "cdlab bench: broad phase n = " << n << "\n";
        const int frames = quick ? (n >= 10000 ? 10 : 30) : (n >= 30000 ? 20 : 60);
        const int bruteFrames = n > bruteLimit ? 0 : n >= 10000 ? 3 : n >= 3000 ? 10 : frames;
        // The classic octree tests every object against all objects stuck on its ancestors' split
        // planes (~n^(5/3) tests per frame): fewer frames at large n keep the full run short.
        const int octFrames = n >= 30000 ? 5 : n >= 10000 ? (quick ? 5 : 10) : frames;
        results.push_back(measure(n, frames, bruteFrames, octFrames));
        agree = agree && results.back().agree;
        setChecks += results.back().setChecks;
    }
    table << "Broad phase, coherent motion (boxes of size 0.5..1.5 moving <= 0.05 per axis per frame, 0.05 boxes per\n"
          << "unit volume): median thread-CPU ms per frame, every method side by side on the same frames.\n"
          << "k = overlapping pairs, swaps = SAP insertion-sort swaps per frame (means). Grid cell 1.5.\n"
          << "octree / loose: Octree (core/broadphase/octree.h) built from scratch every frame, then overlappingPairs; "
             "classic\n"
          << "(looseness 1) and loose (looseness 2), split above 8 objects per node, depth <= 10; fewer frames at\n"
          << "n >= 10k (see the second table).\n"
          << "slow: SAP alone on the same boxes with speeds scaled by (100 / n)^(2/3), so that swaps per box stay\n"
          << "constant (the projected endpoint density grows like n^(2/3) at constant volume density).\n"
          << "Brute force measured up to n = " << bruteLimit << " (beyond: \"-\", ~n^2 / 2 box tests per frame).\n\n";
    char line[320];
    const char* head = "%7s %7s %9s %7s %9s %9s %9s %9s %9s %9s %9s %9s %9s | %7s %9s\n";
    std::snprintf(line, sizeof line, head, "n", "k", "swaps", "swaps/n", "SAP ms", "grid ms", "octree ms", "loose ms",
                  "brute ms", "SAP ns/", "SAP ns/", "grid ns/", "build ms", "slow", "slow SAP");
    table << line;
    std::snprintf(line, sizeof line, head, "", "", "", "", "", "", "", "", "", "(n+k)", "(n+k+s)", "(n+k)", "",
                  "swaps/n", "ms");
    table << line;
    for (const Result& r : results) {
        std::snprintf(line, sizeof line, "%7d %7.0f %9.0f %7.1f %9s %9s %9s %9s %9s %9s %9s %9s %9s | %7.2f %9s\n", r.n,
                      r.pairs, r.swaps, r.swaps / r.n, cell("%.4f", r.sapMs).c_str(), cell("%.4f", r.gridMs).c_str(),
                      cell("%.4f", r.octMs).c_str(), cell("%.4f", r.looseMs).c_str(), cell("%.3f", r.bruteMs).c_str(),
                      cell("%.1f", 1e6 * r.sapMs / (r.n + r.pairs)).c_str(),
                      cell("%.1f", 1e6 * r.sapMs / (r.n + r.pairs + r.swaps)).c_str(),
                      cell("%.1f", 1e6 * r.gridMs / (r.n + r.pairs)).c_str(), cell("%.3f", r.buildMs).c_str(),
                      r.slowSwaps / r.n, cell("%.4f", r.slowSapMs).c_str());
        table << line;
    }
    std::snprintf(
        line, sizeof line,
        "log-log slopes vs n: SAP %.2f, swaps %.2f, grid %.2f, octree %.2f, loose octree %.2f, brute force %.2f;\n"
        "slow motion: SAP %.2f, swaps %.2f\n",
        slope(results, &Result::sapMs), slope(results, &Result::swaps), slope(results, &Result::gridMs),
        slope(results, &Result::octMs), slope(results, &Result::looseMs), bruteSlope(results),
        slope(results, &Result::slowSapMs), slope(results, &Result::slowSwaps));
    table << line;
    // Why the classic octree scales worse: boxes on split planes stay high up and meet everything below.
    table
        << "\nOctrees per frame (means over the measured frames): box-box tests per box, objects stored at the root,\n"
        << "mean depth of an object's node, ns per (n + k).\n";
    const char* octHead = "%7s %7s | %9s %9s %9s %9s | %9s %9s %9s %9s\n";
    std::snprintf(line, sizeof line, octHead, "n", "frames", "tests/n", "at root", "depth", "ns/(n+k)", "tests/n",
                  "at root", "depth", "ns/(n+k)");
    table << line;
    std::snprintf(line, sizeof line, octHead, "", "", "classic", "", "", "", "loose k=2", "", "", "");
    table << line;
    for (const Result& r : results) {
        std::snprintf(line, sizeof line, "%7d %7d | %9.1f %9.0f %9.2f %9s | %9.1f %9.0f %9.2f %9s\n", r.n, r.octFrames,
                      r.octTests / r.n, r.octRoot, r.octDepth, cell("%.1f", 1e6 * r.octMs / (r.n + r.pairs)).c_str(),
                      r.looseTests / r.n, r.looseRoot, r.looseDepth,
                      cell("%.1f", 1e6 * r.looseMs / (r.n + r.pairs)).c_str());
        table << line;
    }
    table << (agree ? "SAP, grid, both octrees and brute force reported the same number of pairs on every frame"
                    : "MISMATCH: the methods disagreed on the pair count or pair set on some frame")
          << "; the pair SETS of all five were compared on " << setChecks << " frames (every brute-force frame).\n";
    writeFigures(results, quick, bruteLimit, outDir);
    return agree ? 0 : 1;
}

}  // namespace cdlab::demos
