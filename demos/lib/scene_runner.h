// Runs many scenes in one process with one GL context: `cdlab figures` (write out/figures/) and
// `cdlab golden` (compare with golden/, write a failure report, optionally update goldens).
#pragma once

#include <string>
#include <vector>

namespace cdlab::demos {

struct RunnerOptions {
    std::string goldenDir;             // scenes + goldens (default <source>/golden)
    std::string outDir = "out/figures";
    std::string pattern;               // glob on "demo/scene" (empty: all)
    std::string demo;                  // only this demo's scenes (empty: all)
    std::string reportDir;             // golden: where failures go (default build/golden-report)
    std::string update;                // golden: "" (never), "failing" (failing or missing), "all"
    int scale = 0;                     // > 0 overrides every scene's supersampling
    bool steps = false;                // force per-step frames
    bool verbose = false;              // print GL_RENDERER / GL_VERSION and per-scene timings
    bool list = false;                 // list scenes and exit
    bool noRender = false;             // numeric only: no GL context, traces only
};

int runFigures(const RunnerOptions& options);
/// Renders the given scene files (all validated first; with options.demo set, each must belong to it).
int renderSceneFiles(const std::vector<std::string>& files, const RunnerOptions& options);
int runGolden(const RunnerOptions& options);

/// Scene files selected by goldenDir / demo / pattern (also used by tests and the demo executables).
std::vector<std::string> selectScenes(const RunnerOptions& options);

}  // namespace cdlab::demos
