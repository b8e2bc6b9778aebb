// `cdlab stress` on the command line: options, the run, stress.json and the figures (the suite
// itself: stress.cpp).
#include "app/stress/stress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/bench/bench_measure.h"
#include "app/stress/stress_tolerances.h"
#include "demos/draw/plot.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

namespace {

using stress_tolerances::kDistanceTol;

nlohmann::json reportJson(const StressReport& r, const StressOptions& o) {
    nlohmann::json j;
    j["seconds"] = r.seconds;
    j["seed"] = o.seed;
    j["machine"] = machineDescription();
    j["checks"] = r.totalCases;
    j["failures"] = r.totalFailures;
    j["ok"] = r.ok();
    j["size_definition"] =
        "L: larger circumradius of the two shapes about their vertex centroids (triangle: longest edge); "
        "M: largest |coordinate|; u = 2^-53";
    for (const StressCell& c : r.cells) {
        j["cells"].push_back(
            {{"family", c.family},
             {"check", c.check},
             {"informational", c.informational},
             {"cases", c.cases},
             {"failures", c.failures},
             {"failure_rate", c.cases ? double(c.failures) / c.cases : 0.0},
             {"worst_error", std::isfinite(c.worstError) ? nlohmann::json(c.worstError) : nlohmann::json("inf")},
             {"worst_error_over_tolerance",
              std::isfinite(c.worstRatio) ? nlohmann::json(c.worstRatio) : nlohmann::json("inf")},
             {"tolerance", c.tolerance},
             {"max_iterations", c.maxIterations},
             {"iteration_cap_hits", c.iterationCapHits}});
    }
    return j;
}

/// Error-vs-parameter figures: one per family with iterative checks, one series per check.
/// False when a figure could not be written (reported); no GL context means no figures, not an error.
bool writeFigures(const StressReport& r, const std::string& outDir) {
    std::unique_ptr<render::GlContext> gl;
    try {
        gl = render::GlContext::create();
    } catch (const std::exception& e) {
        std::cerr << "cdlab stress: no figures (" << e.what() << ")\n";
        return true;
    }
    bool written = true;
    // Teaching figure: signed volumes vs Johnson on the sliver family and on scales.
    struct Figure {
        std::string file, family, title;
        std::vector<std::string> checks;
    };
    const std::vector<Figure> figures = {
        {"error_vs_thickness_slivers.png",
         "slivers and needles",
         "GJK distance error on slivers: signed volumes vs Johnson",
         {"gjk_distance", "gjk_distance Johnson"}},
        {"error_vs_scale.png",
         "scale 1e-6..1e6",
         "Error relative to size vs scale (8-vertex polytopes)",
         {"gjk_distance", "gjk_distance Johnson", "epa_depth"}},
        {"error_vs_offset.png",
         "offset 1e3..1e9",
         "Error relative to size vs distance from the origin",
         {"gjk_distance", "gjk_distance Johnson", "epa_depth"}},
        {"error_vs_gap.png",
         "gap 1e-12..1e-3, touching",
         "Error relative to size vs gap (separated and overlapping)",
         {"gjk_distance", "gjk_distance Johnson", "epa_depth", "epa_normal |h(n)-depth|"}},
        {"error_vs_angle_parallel_edges.png",
         "nearly parallel edges",
         "Error vs angle between nearly parallel edges",
         {"gjk_distance", "gjk_distance Johnson", "epa_depth"}},
    };
    const std::vector<std::string> families = [&] {
        std::vector<std::string> v;
        for (const StressCell& c : r.cells)
            if (std::find(v.begin(), v.end(), c.family) == v.end()) v.push_back(c.family);
        return v;
    }();
    for (const Figure& fig : figures) {
        PlotOptions po;
        po.title = fig.title;
        const auto fi = std::find(families.begin(), families.end(), fig.family);
        po.xLabel = fi != families.end() && size_t(fi - families.begin()) < r.familyParameter.size()
                        ? r.familyParameter[fi - families.begin()]
                        : "parameter";
        po.yLabel = "|error| / size (0 drawn at the floor)";
        po.yFloor = 1e-18;
        po.subtitle = "cdlab stress, family \"" + fig.family + "\"; dashed line: the stated tolerance floor";
        std::vector<PlotSeries> series;
        int k = 0;
        for (const std::string& check : fig.checks) {
            for (const StressCell& c : r.cells) {
                if (c.family != fig.family || c.check != check) continue;
                PlotSeries s;
                s.label = check == "gjk_distance"           ? "GJK distance, signed volumes"
                          : check == "gjk_distance Johnson" ? "GJK distance, Johnson"
                          : check == "epa_depth"            ? "EPA depth"
                                                            : "EPA normal |h(n) - depth|";
                s.style = k++;
                for (const auto& [x, y] : c.samples)
                    if (x > 0 && std::isfinite(y)) s.points.emplace_back(x, y);
                series.push_back(s);
            }
        }
        if (series.empty()) continue;
        po.hLines.push_back({kDistanceTol, "1e-12 (distance tolerance)"});
        try {
            render::writePngAtomic(outDir + "/" + fig.file, drawLogLogPlot(*gl, po, series));
        } catch (const render::ImageError& e) {  // names the file
            std::cerr << "cdlab stress: " << e.what() << "\n";
            written = false;
        } catch (const std::exception& e) {
            std::cerr << "cdlab stress: " << fig.file << ": " << e.what() << "\n";
            written = false;
        }
    }
    return written;
}

int usage(int status) {
    std::cerr << "usage: cdlab stress [--seconds N] [--quick] [--seed S] [--out DIR] [--no-figures]\n"
                 "  families of hard inputs checked against independent oracles; writes DIR/stress.json,\n"
                 "  DIR/failures.jsonl (one `cdlab query` line per failure) and error-vs-parameter figures\n"
                 "  (default DIR out/stress, 20 s; --quick: 3 s). Exit 0: all checks within tolerance; 1: failures;\n"
                 "  2: usage error, or DIR cannot be written.\n";
    return status;
}

}  // namespace

int runStress(int argc, char** argv) {
    StressOptions options;
    options.progress = true;
    std::string outDir = "out/stress";
    bool figures = true;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick") {
            options.seconds = 3.0;
        } else if (arg == "--seconds" && i + 1 < argc) {
            char* end = nullptr;
            options.seconds = std::strtod(argv[++i], &end);
            if (*end || !(options.seconds >= 0) || options.seconds > 86400) return usage(2);
        } else if (arg == "--seed" && i + 1 < argc) {
            options.seed = std::strtoull(argv[++i], nullptr, 10);
        } else if (arg == "--out" && i + 1 < argc) {
            outDir = argv[++i];
        } else if (arg == "--no-figures") {
            figures = false;
        } else if (arg == "-h" || arg == "--help") {
            return usage(0);
        } else {
            std::cerr << "cdlab stress: unknown argument " << arg << "\n";
            return usage(2);
        }
    }
    // An output folder that cannot be made is found before the run, not after it (exit 2, as for
    // every output that cannot be written).
    {
        std::error_code ec;
        std::filesystem::create_directories(outDir, ec);
        if (ec) {
            std::cerr << "cdlab stress: cannot create the output folder '" << outDir << "': " << ec.message() << "\n";
            return 2;
        }
    }
    const StressReport report = runStressSuite(options);
    std::cout << stressTable(report);
    std::printf("%d checks in %.1f s, %d failures%s\n", report.totalCases, report.seconds, report.totalFailures,
                report.ok() ? "" : (" (reproducers: " + outDir + "/failures.jsonl)").c_str());
    try {
        render::writeFileAtomic(outDir + "/stress.json", reportJson(report, options).dump(2) + "\n");
        std::string lines;
        for (const std::string& l : report.failureLines) lines += l + "\n";
        render::writeFileAtomic(outDir + "/failures.jsonl", lines);
    } catch (const std::exception& e) {  // "cannot write '<path>': <reason>"
        std::cerr << "cdlab stress: " << e.what() << "\n";
        return 2;
    }
    if (figures && !writeFigures(report, outDir)) return 2;
    std::cerr << "cdlab stress: wrote " << outDir << "/stress.json, failures.jsonl" << (figures ? " and figures" : "")
              << "\n";
    return report.ok() ? 0 : 1;
}

}  // namespace cdlab::demos

