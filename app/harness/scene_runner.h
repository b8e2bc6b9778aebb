// Runs many scenes in one process with one GL context: `cdlab figures` (write out/figures/) and
// `cdlab golden` (compare with golden/, write a failure report, optionally update goldens).
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/scene/json_reader.h"
#include "render/gl_context.h"

namespace cdlab::demos {

struct RunnerOptions {
    std::string goldenDir;  // scenes + goldens (default <source>/golden)
    std::string outDir = "out/figures";
    std::string pattern;    // glob on "demo/scene" (empty: all)
    std::string demo;       // only this demo's scenes (empty: all)
    std::string reportDir;  // golden: where failures go (default build/golden-report)
    std::string update;     // golden: "" (never), "failing" (failing or missing), "all"
    int scale = 0;          // > 0 overrides every scene's supersampling
    bool steps = false;     // force per-step frames
    bool verbose = false;   // print GL_RENDERER / GL_VERSION and per-scene timings
    bool list = false;      // list scenes and exit
    bool noRender = false;  // numeric only: no GL context, traces only
    bool force = false;     // figures: re-render scenes whose cache key matches
    bool profile = false;   // figures: per-scene time in algorithm, drawing, read-back, PNG
    // render (any scene file anywhere): output in <outDir>/<file stem>/, or in outDir itself when
    // outIsFolder (one file and an explicit --out); never under golden/; no gallery page.
    bool perFileOutput = false;
    bool outIsFolder = false;
    std::vector<std::string> frames;  // render: write only frames whose name matches one of these globs
};

int runFigures(const RunnerOptions& options);
/// Renders the given scene files (all validated first; with options.demo set, each must belong to it).
int renderSceneFiles(const std::vector<std::string>& files, const RunnerOptions& options);
int runGolden(const RunnerOptions& options);
/// `cdlab render --template DEMO`: a scene file for the demo that renders as it is, to copy and edit
/// (the demo's first golden scene without its golden tolerances). Throws InputError for an unknown demo.
std::string sceneTemplate(const std::string& demo, const RunnerOptions& options);

/// The one GL context of a run (prints GL_RENDERER / GL_VERSION when verbose). Throws render::GlError.
std::unique_ptr<render::GlContext> createContext(bool verbose);
/// Wall-clock seconds since t0 (the runners' progress and timing lines).
double secondsSince(std::chrono::steady_clock::time_point t0);
/// A trace as written to trace.json (stable formatting, so goldens diff well).
std::string traceText(const Json& trace);

/// Scene files selected by goldenDir / demo / pattern (also used by tests and the demo executables).
std::vector<std::string> selectScenes(const RunnerOptions& options);

/// <root>/<demo>/<name>: where a scene's figures, goldens or report files go. Throws InputError
/// ("scene name \"..\" ...") when demo or name is not a plain name, so no output path built from
/// a scene can leave <root>, whatever the scene reader let through.
std::filesystem::path sceneOutputDir(const std::filesystem::path& root, const std::string& demo,
                                     const std::string& name);

}  // namespace cdlab::demos
