#include "demos/lib/scene_runner.h"

#include <fnmatch.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "demos/lib/demo.h"
#include "demos/lib/trace_compare.h"
#include "render/compare.h"

namespace cdlab::demos {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

std::unique_ptr<render::GlContext> createContext(bool verbose) {
    auto t0 = Clock::now();
    auto gl = render::GlContext::create();
    if (verbose)
        std::cerr << "GL_RENDERER: " << gl->glRenderer() << "\nGL_VERSION: " << gl->glVersion() << "\nEGL platform: "
                  << gl->eglPlatform() << " (context created in " << int(secondsSince(t0) * 1000) << " ms)\n";
    return gl;
}

std::string traceText(const Json& trace) { return trace.dump(1) + "\n"; }

std::vector<std::string> selectScenes(const RunnerOptions& o) {
    std::string golden = o.goldenDir.empty() ? std::string(CDLAB_SOURCE_DIR) + "/golden" : o.goldenDir;
    std::vector<std::string> out;
    for (const std::string& file : findSceneFiles(golden)) {
        fs::path p(file);
        std::string demo = p.parent_path().filename().string();
        std::string id = demo + "/" + p.stem().string();
        if (!o.demo.empty() && demo != o.demo) continue;
        if (!o.pattern.empty() && fnmatch(o.pattern.c_str(), id.c_str(), 0) != 0 &&
            id.find(o.pattern) == std::string::npos)
            continue;
        out.push_back(file);
    }
    return out;
}

int runGolden(const RunnerOptions& o) {
    std::vector<std::string> files = selectScenes(o);
    if (files.empty()) {
        std::cerr << "cdlab golden: no scene matches\n";
        return 2;
    }
    std::string reportDir = o.reportDir.empty() ? std::string(CDLAB_SOURCE_DIR) + "/build/golden-report" : o.reportDir;
    std::error_code ec;
    fs::remove_all(reportDir, ec);

    std::unique_ptr<render::GlContext> gl = createContext(o.verbose);  // one context for the whole run
    RunContext ctx{gl.get(), 0, false};
    std::vector<render::ReportEntry> report;
    int checked = 0, failed = 0, updated = 0;

    auto fail = [&](const std::string& what) {
        std::cout << "FAIL " << what << "\n";
        ++failed;
    };

    for (const auto& file : files) {
        std::unique_ptr<PreparedScene> scene;
        try {
            scene = loadScene(file);
        } catch (const InputError& e) {
            fail(std::string(e.what()));
            continue;
        }
        const SceneCommon& sc = scene->common();
        DemoOutput out = scene->run(ctx);
        fs::path goldenDir = fs::path(file).parent_path() / sc.name;

        for (const Frame& fr : out.frames) {
            ++checked;
            std::string id = sceneId(sc) + "/" + fr.name;
            fs::path goldenPng = goldenDir / (fr.name + ".png");
            bool exists = fs::exists(goldenPng);
            render::CompareResult cmp;
            std::string problem;
            if (exists) {
                try {
                    cmp = render::compareImages(fr.image, render::readPng(goldenPng.string()), sc.golden.image);
                    if (!cmp.passed) problem = cmp.summary();
                } catch (const render::ImageError& e) {
                    problem = e.what();
                }
            } else {
                problem = "missing golden " + goldenPng.string();
            }
            bool write = o.update == "all" || (!problem.empty() && !o.update.empty());
            if (write) {
                render::writePngAtomic(goldenPng.string(), fr.image);
                std::cout << "UPDATED " << id << (problem.empty() ? "" : " (was: " + problem + ")") << "\n";
                ++updated;
                continue;
            }
            if (problem.empty()) {
                std::cout << "PASS " << id << ": " << cmp.summary() << "\n";
                continue;
            }
            if (!exists) problem += " (create it with: ./cdlab test --update-golden)";
            fail(id + ": " + problem);
            fs::path rdir = fs::path(reportDir) / sc.demo / sc.name;
            std::string rel = sc.demo + "/" + sc.name + "/" + fr.name;
            render::writePngAtomic((rdir / (fr.name + ".actual.png")).string(), fr.image);
            render::ReportEntry entry{id, rel + ".actual.png", "", "", problem};
            if (exists) {
                try {
                    render::Image expected = render::readPng(goldenPng.string());
                    render::writePngAtomic((rdir / (fr.name + ".expected.png")).string(), expected);
                    render::writePngAtomic((rdir / (fr.name + ".diff.png")).string(), render::diffImage(fr.image, expected));
                    entry.expectedPng = rel + ".expected.png";
                    entry.diffPng = rel + ".diff.png";
                } catch (const render::ImageError&) {
                }
            }
            report.push_back(entry);
        }

        // The numeric trace: an algorithm regression fails even when the pixels look alike.
        ++checked;
        fs::path goldenTrace = goldenDir / "trace.json";
        std::string id = sceneId(sc) + "/trace.json";
        std::string problem;
        TraceComparison tc;
        if (fs::exists(goldenTrace)) {
            try {
                tc = compareTraces(out.trace, readJsonFile(goldenTrace.string()), sc.golden.traceAbsolute, sc.golden.traceRelative);
                if (!tc.passed()) problem = tc.summary();
            } catch (const InputError& e) {
                problem = e.what();
            }
        } else {
            problem = "missing golden " + goldenTrace.string();
        }
        if (o.update == "all" || (!problem.empty() && !o.update.empty())) {
            render::writeFileAtomic(goldenTrace.string(), traceText(out.trace));
            std::cout << "UPDATED " << id << (problem.empty() ? "" : " (was: " + problem + ")") << "\n";
            ++updated;
        } else if (problem.empty()) {
            std::cout << "PASS " << id << ": " << tc.summary() << "\n";
        } else {
            fail(id + ": " + problem + (fs::exists(goldenTrace) ? "" : " (create it with: ./cdlab test --update-golden)"));
            for (std::size_t i = 1; i < tc.mismatches.size(); ++i)
                std::cout << "     " << tc.mismatches[i].path << ": " << tc.mismatches[i].what << "\n";
        }
    }

    if (!report.empty()) {
        std::string page = (fs::path(reportDir) / "index.html").string();
        render::writeHtmlReport(page, report);
        std::cout << "report: " << page << "\n";
    }
    std::cout << "golden: " << checked - failed - updated << " passed, " << failed << " failed";
    if (updated) std::cout << ", " << updated << " updated";
    std::cout << "\n";
    return failed ? 1 : 0;
}

}  // namespace cdlab::demos
