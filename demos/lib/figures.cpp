// `cdlab figures`: render scenes into out/figures/<demo>/<scene>/ with a content-hash cache, an
// optional per-scene profile, and one static gallery page out/figures/index.html.
//
// Cache: each scene folder holds manifest.json with a key = FNV-1a over (scene file bytes, the
// options that change pixels, the cdlab executable's bytes). A scene whose key matches and whose
// files all exist is skipped; --force renders everything. Changing the code changes the
// executable, so every scene re-renders after a rebuild that changed anything.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "demos/lib/demo.h"
#include "demos/lib/gallery.h"
#include "demos/lib/scene_runner.h"
#include "render/canvas.h"
#include "render/image.h"

namespace cdlab::demos {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::uint64_t fnv1a(const std::string& bytes, std::uint64_t h = 1469598103934665603ull) {
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Hash of the running program: any code change re-renders every scene.
std::uint64_t executableHash() {
    static const std::uint64_t h = fnv1a(readBytes("/proc/self/exe"));
    return h;
}

std::string cacheKey(const std::string& sceneFile, const RunnerOptions& o) {
    std::uint64_t h = fnv1a(readBytes(sceneFile), executableHash());
    h = fnv1a("scale=" + std::to_string(o.scale) + ";steps=" + std::to_string(o.steps), h);
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

bool cacheValid(const fs::path& dir, const std::string& key) {
    fs::path manifest = dir / "manifest.json";
    if (!fs::exists(manifest)) return false;
    try {
        Json m = Json::parse(readBytes(manifest));
        if (m.value("key", "") != key) return false;
        for (const auto& f : m.at("files"))
            if (!fs::exists(dir / f.get<std::string>())) return false;
        return true;
    } catch (const std::exception&) {
        return false;  // unreadable manifest: render again
    }
}

// Files of an earlier run that this run did not write (e.g. fewer steps now) are removed after
// the new ones are in place.
void removeStale(const fs::path& dir, const std::vector<std::string>& keep) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        std::string name = entry.path().filename().string();
        if (name == "manifest.json" || std::find(keep.begin(), keep.end(), name) != keep.end()) continue;
        if (entry.is_regular_file()) fs::remove(entry.path(), ec);
    }
}

std::string ms(double seconds) { return std::to_string(int(seconds * 1000 + 0.5)) + " ms"; }

}  // namespace

int runFigures(const RunnerOptions& o) { return renderSceneFiles(selectScenes(o), o); }

int renderSceneFiles(const std::vector<std::string>& files, const RunnerOptions& o) {
    if (o.list) {
        for (const auto& f : files)
            std::cout << fs::path(f).parent_path().filename().string() << "/" << fs::path(f).stem().string() << "\n";
        return 0;
    }
    if (files.empty()) {
        std::cerr << "cdlab figures: no scene matches\n";
        return 2;
    }
    // Validate every scene before rendering anything: a bad file produces no output at all.
    std::vector<std::unique_ptr<PreparedScene>> scenes;
    for (const auto& f : files) {
        scenes.push_back(loadScene(f));
        const std::string& demo = scenes.back()->common().demo;
        if (!o.demo.empty() && demo != o.demo)
            throw InputError(f + ": $.demo: this scene is for demo '" + demo + "', not '" + o.demo + "'");
    }

    // Which scenes need work: the GL context (70 ms .. 1 s) is created only if one does.
    std::vector<std::string> keys;
    std::vector<bool> todo;
    bool anyTodo = false;
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        const SceneCommon& sc = scenes[i]->common();
        keys.push_back(cacheKey(files[i], o) + (o.noRender ? "-numeric" : ""));
        bool cached = !o.force && cacheValid(fs::path(o.outDir) / sc.demo / sc.name, keys.back());
        todo.push_back(!cached);
        anyTodo = anyTodo || !cached;
    }
    std::unique_ptr<render::GlContext> gl;
    if (anyTodo && !o.noRender) gl = createContext(o.verbose);
    render::RenderStats& stats = render::renderStats();
    stats.profiling = o.profile;
    RunContext ctx{gl.get(), o.scale, o.steps};

    auto t0 = Clock::now();
    int frames = 0, rendered = 0;
    const bool tty = isatty(fileno(stderr)) && !std::getenv("CI");
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        const SceneCommon& sc = scenes[i]->common();
        const fs::path dir = fs::path(o.outDir) / sc.demo / sc.name;
        if (tty && !o.verbose && !o.profile)
            std::cerr << "\r[" << i + 1 << "/" << scenes.size() << "] " << sceneId(sc) << " (" << int(secondsSince(t0))
                      << " s)\x1b[K" << std::flush;
        if (!todo[i]) {
            if (o.verbose || o.profile) std::cerr << sceneId(sc) << ": unchanged (cached)\n";
            continue;
        }
        ++rendered;
        double algorithm = 0;
        if (o.profile) {  // the numeric part alone: what the algorithm costs without any drawing
            auto ta = Clock::now();
            scenes[i]->run(RunContext{});
            algorithm = secondsSince(ta);
        }
        const render::RenderStats before = stats;
        auto ts = Clock::now();
        DemoOutput out = scenes[i]->run(ctx);
        const double runSeconds = secondsSince(ts);

        auto tw = Clock::now();
        std::vector<std::string> written;
        Json manifest = {{"key", keys[i]}, {"title", sc.title}, {"caption", sc.caption}, {"frames", Json::array()}};
        for (const Frame& fr : out.frames) {
            render::writePngAtomic((dir / (fr.name + ".png")).string(), fr.image);
            written.push_back(fr.name + ".png");
            manifest["frames"].push_back({{"name", fr.name}, {"caption", fr.caption}});
            ++frames;
        }
        for (const auto& [name, bytes] : out.files) {
            render::writeFileAtomic((dir / name).string(), bytes);
            written.push_back(name);
        }
        render::writeFileAtomic((dir / "trace.json").string(), traceText(out.trace));
        written.push_back("trace.json");
        manifest["files"] = written;
        removeStale(dir, written);
        render::writeFileAtomic((dir / "manifest.json").string(), manifest.dump(1) + "\n");
        const double writeSeconds = secondsSince(tw);

        if (o.profile) {
            const double build = stats.buildSeconds - before.buildSeconds, draw = stats.drawSeconds - before.drawSeconds,
                         readback = stats.readbackSeconds - before.readbackSeconds;
            std::cerr << sceneId(sc) << ": " << out.frames.size() << " frames; algorithm " << ms(algorithm)
                      << ", drawing " << ms(runSeconds - readback - (gl ? algorithm : 0)) << " (vertices " << ms(build)
                      << ", GL " << ms(draw) << "), read-back " << ms(readback) << ", PNG encoding + writes "
                      << ms(writeSeconds);
            if (!out.skipped.empty()) {
                std::cerr << "; skipped:";
                for (const auto& s : out.skipped) std::cerr << " " << s << ";";
            }
            std::cerr << "\n";
        } else if (o.verbose) {
            std::cerr << sceneId(sc) << ": " << out.frames.size() << " frames in " << ms(runSeconds + writeSeconds) << "\n";
        }
    }
    if (tty && !o.verbose && !o.profile) std::cerr << "\n";
    writeGallery(o.outDir);
    std::cerr << "cdlab figures: " << scenes.size() << " scenes (" << rendered << " rendered, " << scenes.size() - rendered
              << " unchanged), " << frames << " frames into " << o.outDir << " in " << secondsSince(t0) << " s; gallery "
              << (fs::path(o.outDir) / "index.html").string() << "\n";
    return 0;
}

}  // namespace cdlab::demos
