#include "demos/harness/scene_runner.h"

#include <fnmatch.h>

#include <chrono>
#include <filesystem>
#include <iostream>

#include "demos/scene/scene.h"

namespace cdlab::demos {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::unique_ptr<render::GlContext> createContext(bool verbose) {
    auto t0 = Clock::now();
    auto gl = render::GlContext::create();
    if (verbose)
        std::cerr << "GL_RENDERER: " << gl->glRenderer() << "\nGL_VERSION: " << gl->glVersion()
                  << "\nEGL platform: " << gl->eglPlatform() << " (context created in " << int(secondsSince(t0) * 1000)
                  << " ms)\n";
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

fs::path sceneOutputDir(const fs::path& root, const std::string& demo, const std::string& name) {
    for (const auto& [what, value] : {std::pair<const char*, const std::string&>{"demo", demo}, {"scene", name}})
        if (!isPlainName(value))
            throw InputError(std::string(what) + " name " +
                             Json(value).dump(-1, ' ', false, Json::error_handler_t::replace) +
                             " cannot name an output folder (allowed: letters, digits, '_', '-', '.'; not '.' first)");
    return root / demo / name;
}

}  // namespace cdlab::demos
