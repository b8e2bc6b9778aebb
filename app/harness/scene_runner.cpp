#include "app/harness/scene_runner.h"

#include <fnmatch.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "app/catalog/catalog.h"
#include "app/scene/scene.h"

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

std::string sceneTemplate(const std::string& demo, const RunnerOptions& o) {
    RunnerOptions only = o;
    only.demo = demo;
    only.pattern.clear();
    const std::vector<std::string> files = selectScenes(only);
    if (files.empty()) {
        std::string names;
        for (const Demo* d : allDemos()) names += std::string(names.empty() ? "" : ", ") + d->name();
        throw InputError("render --template: unknown demo '" + demo + "' (demos: " + names + ")");
    }
    // The file as written (its layout reads better than a re-dump), less its one-line "golden"
    // entry: the golden comparison's tolerances mean nothing outside golden/. A file laid out
    // otherwise is re-dumped from its parse.
    const std::string text = readJsonText(files.front());
    Json scene = parseJson(text, files.front());
    scene.erase("golden");
    std::istringstream in(text);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
        if (line.find("\"golden\"") == std::string::npos) lines.push_back(line);
    std::string out;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        std::string line = lines[i];
        // The entry before a removed last entry loses its comma.
        if (i + 1 < lines.size() && lines[i + 1].find_first_not_of(" ") < lines[i + 1].size() &&
            lines[i + 1][lines[i + 1].find_first_not_of(" ")] == '}' && !line.empty() && line.back() == ',')
            line.pop_back();
        out += line + "\n";
    }
    const Json reparsed = Json::parse(out, nullptr, false);
    return reparsed == scene ? out : scene.dump(2) + "\n";
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
