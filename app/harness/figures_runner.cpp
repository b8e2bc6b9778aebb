// `cdlab figures`: render scenes into out/figures/<demo>/<scene>/ with a content-hash cache, an
// optional per-scene profile, and one static gallery page out/figures/index.html.
//
// Cache: each scene folder holds manifest.json with a key = FNV-1a over (scene file bytes, the
// options that change pixels, the cdlab executable's bytes). A scene whose key matches and whose
// files all exist is skipped; --force renders everything. Changing the code changes the
// executable, so every scene re-renders after a rebuild that changed anything.
//
// What a run may delete: only files that the scene folder's previous manifest lists (cdlab wrote
// them) and this run did not write again. Folders come from a checked scene name
// (sceneOutputDir), so no scene can point a run at out/ itself or outside it. Each scene's files
// are staged and renamed together under an flock() on the scene folder, so two runs into one
// out/ both succeed and a failed scene keeps its previous complete files.
#include <fcntl.h>
#include <fnmatch.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>
#include <utility>

#include "app/catalog/catalog.h"
#include "app/harness/background_writer.h"
#include "app/harness/gallery.h"
#include "app/harness/layout_json.h"
#include "app/harness/scene_runner.h"
#include "app/scene/scene_limits.h"
#include "render/canvas.h"
#include "render/image.h"
#include "render/pixel_budget.h"

namespace cdlab::demos {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

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

// From the bytes read once at validation: a scene given as a pipe (`<(cat scene.json)`) is not
// opened twice.
std::string cacheKey(const std::string& sceneBytes, const RunnerOptions& o) {
    std::uint64_t h = fnv1a(sceneBytes, executableHash());
    h = fnv1a("scale=" + std::to_string(o.scale) + ";steps=" + std::to_string(o.steps), h);
    for (const std::string& f : o.frames) h = fnv1a(";frame=" + f, h);
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

bool pathExists(const fs::path& p) {
    std::error_code ec;
    return fs::symlink_status(p, ec).type() != fs::file_type::not_found;
}

// A cached scene: a readable manifest with this key whose files are all there. A manifest that does
// not read is not trusted; the write step reports it (once) and replaces it.
bool cacheValid(const fs::path& dir, const std::string& key) {
    if (!pathExists(dir / "manifest.json")) return false;
    try {
        const FigureManifest m = readFigureManifest(dir / "manifest.json");
        if (m.key != key) return false;
        for (const auto& f : m.files)
            if (!pathExists(dir / f)) return false;
        return true;
    } catch (const InputError&) {
        return false;
    }
}

// An exclusive flock() on a folder while this run changes it; released on destruction. Another
// cdlab run writing the same folder waits. Without a lock (the folder cannot be opened) the
// writes go on and report their own errors.
class FolderLock {
public:
    explicit FolderLock(const fs::path& dir) : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
        if (fd_ >= 0)
            while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {}
    }
    ~FolderLock() {
        if (fd_ >= 0) ::close(fd_);  // closing releases the lock
    }
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

private:
    int fd_;
};

// The files the previous run wrote into `dir` (its manifest's list); none without a manifest. A
// manifest.json that is not cdlab's (another program's, or not JSON) is the user's file: the
// folder is refused, nothing in it is written or deleted (hostile_harness_test "render --out
// keeps a folder's own files").
std::vector<std::string> previouslyWritten(const fs::path& dir) {
    const fs::path file = dir / "manifest.json";
    if (!pathExists(file)) return {};
    try {
        return readFigureManifest(file).files;
    } catch (const InputError& e) {
        throw InputError("refusing to write into " + printable(dir.string()) + ": its manifest.json is not cdlab's (" +
                         printable(e.what()) + "); give --out a folder of its own");
    }
}

// A file this run is about to write into `dir` that is there but no cdlab manifest lists: the
// user's, never replaced (hostile_harness_test "render --out keeps a folder's own files").
void refuseForeign(const fs::path& dir, const std::string& name, const std::vector<std::string>& previous) {
    if (pathExists(dir / name) && std::find(previous.begin(), previous.end(), name) == previous.end())
        throw InputError("refusing to overwrite " + printable((dir / name).string()) +
                         ": cdlab did not write it (no cdlab manifest.json there lists it); give --out a folder of its own");
}

// Files of an earlier run that this run did not write (e.g. fewer steps now). Names come from the
// previous manifest and are plain names (readFigureManifest checks), so this never leaves `dir`.
void removeStale(const fs::path& dir, const std::vector<std::string>& previous,
                 const std::vector<std::string>& written) {
    std::error_code ec;
    for (const std::string& name : previous)
        if (std::find(written.begin(), written.end(), name) == written.end() &&
            fs::symlink_status(dir / name, ec).type() == fs::file_type::regular)
            fs::remove(dir / name, ec);
}

// Names of frames and extra files come from demo code; checked all the same.
std::string plainOutputName(const std::string& name) {
    if (!isPlainName(name) || name == "manifest.json")
        throw std::logic_error("output file name " + Json(name).dump() + " is not a plain file name");
    return name;
}

bool frameSelected(const std::string& name, const std::vector<std::string>& globs) {
    if (globs.empty()) return true;
    return std::any_of(globs.begin(), globs.end(),
                       [&](const std::string& g) { return fnmatch(g.c_str(), name.c_str(), 0) == 0; });
}

// --frame: the frames chosen must exist (the error lists the scene's frame names).
void requireSelectedFrames(const DemoOutput& out, const std::vector<std::string>& globs) {
    if (globs.empty()) return;
    std::string names;
    for (const Frame& fr : out.frames) {
        if (frameSelected(fr.name, globs)) return;
        names += (names.empty() ? "" : ", ") + fr.name;
    }
    std::string asked;
    for (const std::string& g : globs) asked += (asked.empty() ? "" : ", ") + g;
    throw InputError("--frame " + asked + " matches no frame of this scene (frames: " + names + ")");
}

// Writes one scene's output: everything staged first; then a provisional manifest (no cache key)
// listing the previous files and this run's; then the renames; stale files of the previous run
// next, the final manifest last. Whenever a run stops (killed, a full disk), the manifest there
// lists every file cdlab put in the folder, so a later run neither refuses them as the user's nor
// takes them for a finished render (hostile_harness_test "a run killed between its renames and its
// manifest leaves a folder the next run takes").
void writeSceneFolder(const fs::path& dir, const std::string& key, const SceneCommon& sc, const DemoOutput& out,
                      const std::vector<std::string>& frameGlobs) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw std::runtime_error("cannot create folder '" + dir.string() + "': " + ec.message());
    FolderLock lock(dir);
    const std::vector<std::string> previous = previouslyWritten(dir);
    // Every name is checked before the first file is staged: a refused folder gets nothing.
    std::vector<std::string> names = {"trace.json", "manifest.json"};
    for (const Frame& fr : out.frames)
        if (frameSelected(fr.name, frameGlobs)) names.push_back(plainOutputName(fr.name + ".png"));
    if (frameGlobs.empty())
        for (const auto& extra : out.files) names.push_back(plainOutputName(extra.first));
    for (const std::string& name : names)
        if (name != "manifest.json") refuseForeign(dir, name, previous);
    names.insert(names.end(), previous.begin(), previous.end());
    render::removeStaleTempFiles(dir.string(), names);  // of this folder's files only

    render::FileSetWriter files;
    FigureManifest manifest{key, sc.title, sc.caption, {}, {}};
    for (const Frame& fr : out.frames) {
        if (!frameSelected(fr.name, frameGlobs)) continue;
        const std::string name = plainOutputName(fr.name + ".png");
        files.addPng((dir / name).string(), fr.image);
        manifest.files.push_back(name);
        manifest.frames.push_back({fr.name, fr.caption, layoutJson(fr.image)});
    }
    for (const auto& [name, bytes] : out.files) {
        if (!frameGlobs.empty()) break;  // a chosen subset of frames: no sheets, GIFs or plots
        files.addFile((dir / plainOutputName(name)).string(), bytes);
        manifest.files.push_back(name);
    }
    files.addFile((dir / "trace.json").string(), traceText(out.trace));
    manifest.files.push_back("trace.json");
    FigureManifest provisional{"", sc.title, sc.caption, {}, previous};
    for (const std::string& name : manifest.files)
        if (std::find(previous.begin(), previous.end(), name) == previous.end()) provisional.files.push_back(name);
    render::writeFileAtomic((dir / "manifest.json").string(), figureManifestText(provisional));
    files.commit();
    removeStale(dir, previous, manifest.files);
    render::writeFileAtomic((dir / "manifest.json").string(), figureManifestText(manifest));
}

std::string ms(double seconds) { return std::to_string(int(seconds * 1000 + 0.5)) + " ms"; }

struct SceneJob {
    std::string file;
    std::unique_ptr<PreparedScene> scene;
    fs::path dir;     // <out>/<demo>/<scene>
    std::string key;  // cache key
    bool todo = true;
};

// A folder as one absolute path without "..", symlinks resolved as far as they exist: two output
// folders are one when these are equal.
fs::path resolvedFolder(const fs::path& dir) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(fs::absolute(dir), ec);
    return ec ? fs::absolute(dir).lexically_normal() : p;
}

// figures and render never write inside the golden folder (goldens change only through `cdlab
// golden --update`; hostile_harness_test "figures --out inside --golden-dir is refused").
void refuseInsideGolden(const fs::path& dir, const RunnerOptions& o) {
    const fs::path golden =
        resolvedFolder(o.goldenDir.empty() ? fs::path(CDLAB_SOURCE_DIR) / "golden" : fs::path(o.goldenDir));
    const fs::path target = resolvedFolder(dir);
    const auto [g, t] = std::mismatch(golden.begin(), golden.end(), target.begin(), target.end());
    if (g == golden.end())
        throw InputError("output folder '" + printable(dir.string()) + "' is inside the golden folder " +
                         printable(golden.string()) +
                         ": figures and render never write there (goldens change with cdlab golden --update)");
}

// An output folder is a folder (a symlink to one included) or not there at all: a file or a
// dangling symlink in its place is refused before anything is written (hostile_harness_test "two
// scenes into one folder are refused before anything is written").
void requireFolderOrNothing(const fs::path& dir) {
    // The folder and, up to the first that exists, its parents (a file at <out>/<demo> hides the
    // scene's folder behind ENOTDIR).
    for (fs::path p = dir; !p.empty(); p = p.parent_path()) {
        std::error_code ec;
        const fs::file_type own = fs::symlink_status(p, ec).type();
        if (own == fs::file_type::not_found) {
            if (p == p.parent_path()) return;
            continue;
        }
        const fs::file_type target = fs::status(p, ec).type();
        if (target == fs::file_type::directory) return;
        throw InputError("the output folder " + printable(dir.string()) + " cannot be made: " +
                         printable(p.string()) + " is " +
                         (target == fs::file_type::not_found ? "a symlink to nothing"
                          : own == fs::file_type::none   ? "not readable (" + ec.message() + ")"
                                                         : std::string("there and not a folder")));
    }
}

// `cdlab render`: <out>/<file stem>, or --out itself for one file (whatever the file's name).
fs::path renderOutputDir(const std::string& file, const RunnerOptions& o) {
    fs::path dir = o.outDir;
    if (!o.outIsFolder) {
        const std::string stem = fs::path(file).stem().string();
        if (!isPlainName(stem))
            throw InputError("the file name " + Json(stem).dump(-1, ' ', false, Json::error_handler_t::replace) +
                             " cannot name an output folder: give one with --out DIR");
        dir /= stem;
    }
    refuseInsideGolden(dir, o);
    return dir;
}

// A scene's run with its frames' pixels bounded together (kMaxScenePixels), whatever its demo
// declared in its frame budget (render/pixel_budget.h).
DemoOutput runBounded(const PreparedScene& scene, const RunContext& ctx) {
    render::PixelBudget budget(kMaxScenePixels);
    return scene.run(ctx);
}

// The line a scene's failure prints: the error (naming the file once), OpenGL errors marked.
std::string failureLine(const SceneJob& job, const std::exception& e) {
    const std::string what = printable(e.what()), file = printable(job.file);
    if (dynamic_cast<const InputError*>(&e)) return what.rfind(file, 0) == 0 ? what : file + ": " + what;
    if (dynamic_cast<const render::GlError*>(&e)) return file + ": OpenGL: " + what;
    return file + ": " + what;  // render::ImageError, write errors, std::bad_alloc, ...
}

// `cdlab figures` on several cores: one worker thread per core, each with its own GL context (an
// EGL context is current on one thread; programs and glyph atlases live in it), taking the next
// scene from a shared counter and writing that scene's folder itself. Scenes are independent —
// each writes only its own folder, under that folder's lock — so the files are a serial run's.
// The reports come back in scene order. A worker whose context cannot be made stops; the scenes
// go to the others, and when none has a context the first one's error is thrown as the serial
// run's would be.
std::vector<WriteReport> renderOnWorkers(const std::vector<SceneJob>& jobs, const RunnerOptions& o, int workers,
                                         bool tty, Clock::time_point t0) {
    std::vector<WriteReport> reports(jobs.size());
    std::atomic<std::size_t> next{0};
    std::atomic<int> started{0}, finished{0};
    std::mutex printing;
    std::exception_ptr contextError;
    int total = 0;
    for (const SceneJob& job : jobs) total += job.todo;
    const auto work = [&](int index) {
        std::unique_ptr<render::GlContext> gl;
        try {
            gl = createContext(o.verbose && index == 0);
        } catch (const render::GlError&) {
            std::lock_guard<std::mutex> lock(printing);
            if (!contextError) contextError = std::current_exception();
            return;
        }
        ++started;
        const RunContext ctx{gl.get(), o.scale, o.steps};
        for (std::size_t i = next++; i < jobs.size(); i = next++) {
            const SceneJob& job = jobs[i];
            if (!job.todo) continue;
            WriteReport& report = reports[i];
            try {
                const auto ts = Clock::now();
                const DemoOutput out = runBounded(*job.scene, ctx);
                requireSelectedFrames(out, o.frames);
                writeSceneFolder(job.dir, job.key, job.scene->common(), out, o.frames);
                for (const Frame& fr : out.frames) report.frames += frameSelected(fr.name, o.frames);
                if (o.perFileOutput) report.note = printable(job.file) + " -> " + printable(job.dir.string()) + "/";
                if (o.verbose) {
                    std::lock_guard<std::mutex> lock(printing);
                    std::cerr << printable(sceneId(job.scene->common())) << ": " << out.frames.size() << " frames drawn in "
                              << ms(secondsSince(ts)) << "\n";
                }
            } catch (const std::exception& e) {
                report.error = failureLine(job, e);
            }
            const int count = ++finished;
            if (tty && !o.verbose) {
                std::lock_guard<std::mutex> lock(printing);
                std::cerr << "\r[" << count << "/" << total << "] " << printable(sceneId(job.scene->common())) << " ("
                          << int(secondsSince(t0)) << " s)\x1b[K" << std::flush;
            }
        }
    };
    std::vector<std::thread> threads;
    for (int k = 0; k < workers; ++k) threads.emplace_back(work, k);
    for (std::thread& t : threads) t.join();
    if (started == 0 && contextError) std::rethrow_exception(contextError);
    std::vector<WriteReport> ordered;  // every scene to render has been, by one worker or another
    for (std::size_t i = 0; i < jobs.size(); ++i)
        if (jobs[i].todo) ordered.push_back(std::move(reports[i]));
    return ordered;
}

// Render workers for a run: one per core (at most 4: each holds a context and a scene's frames),
// none beyond the scenes to render; 1 when profiling (each phase timed alone) or numeric only.
int workerCount(const RunnerOptions& o, const std::vector<SceneJob>& jobs) {
    if (o.profile || o.noRender) return 1;
    int todo = 0;
    for (const SceneJob& job : jobs) todo += job.todo;
    const int cores = static_cast<int>(std::thread::hardware_concurrency());
    return std::clamp(std::min(cores, todo), 1, 4);
}

// The scenes one after the other on this thread with one GL context, each scene's PNG encoding and
// writes on a second thread while the next one draws (`--profile`: here and now, so each phase is
// timed alone). Failures before a scene's write are printed here and counted in `failed`; the
// writes' reports come back in order.
std::vector<WriteReport> renderOnThisThread(const std::vector<SceneJob>& jobs, const RunnerOptions& o, bool anyTodo,
                                            bool tty, Clock::time_point t0, int& failed) {
    std::unique_ptr<render::GlContext> gl;
    if (anyTodo && !o.noRender) gl = createContext(o.verbose);
    render::RenderStats& stats = render::renderStats();
    stats.profiling = o.profile;
    RunContext ctx{gl.get(), o.scale, o.steps};

    BackgroundWriter writer(!o.profile);  // declared after the jobs: joined before they go
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        const SceneJob& job = jobs[i];
        const SceneCommon& sc = job.scene->common();
        if (tty && !o.verbose && !o.profile)
            std::cerr << "\r[" << i + 1 << "/" << jobs.size() << "] " << printable(sceneId(sc)) << " (" << int(secondsSince(t0))
                      << " s)\x1b[K" << std::flush;
        if (!job.todo) {
            if (o.verbose || o.profile) std::cerr << printable(sceneId(sc)) << ": unchanged (cached)\n";
            continue;
        }
        // A scene that fails at run time (or whose files cannot be written) is reported with its
        // file; its folder keeps the previous complete files and the other scenes still render.
        bool submitted = false;  // from then on the writer's report counts the scene, not this loop
        try {
            double algorithm = 0;
            if (o.profile) {  // the numeric part alone: what the algorithm costs without any drawing
                auto ta = Clock::now();
                job.scene->run(RunContext{});
                algorithm = secondsSince(ta);
            }
            const render::RenderStats before = stats;
            auto ts = Clock::now();
            DemoOutput out = runBounded(*job.scene, ctx);
            const double runSeconds = secondsSince(ts);
            requireSelectedFrames(out, o.frames);

            // The PNG encoding and writes go to the writer thread while this one draws the next
            // scene (when profiling, here and now, so each phase is timed alone).
            auto done = std::make_shared<DemoOutput>(std::move(out));
            auto tw = Clock::now();
            writer.submit([&job, &sc, &o, done] {
                WriteReport report;
                try {
                    writeSceneFolder(job.dir, job.key, sc, *done, o.frames);
                    for (const Frame& fr : done->frames) report.frames += frameSelected(fr.name, o.frames);
                    if (o.perFileOutput) report.note = printable(job.file) + " -> " + printable(job.dir.string()) + "/";
                } catch (const std::exception& e) {  // write errors, std::bad_alloc, ...
                    report.error = printable(job.file) + ": " + printable(e.what());
                }
                return report;
            });
            submitted = true;
            const double writeSeconds = secondsSince(tw);

            if (o.profile) {
                const double build = stats.buildSeconds - before.buildSeconds,
                             draw = stats.drawSeconds - before.drawSeconds,
                             readback = stats.readbackSeconds - before.readbackSeconds;
                std::cerr << printable(sceneId(sc)) << ": " << done->frames.size() << " frames; algorithm " << ms(algorithm)
                          << ", drawing " << ms(runSeconds - readback - (gl ? algorithm : 0)) << " (vertices "
                          << ms(build) << ", GL " << ms(draw) << "), read-back " << ms(readback)
                          << ", PNG encoding + writes " << ms(writeSeconds);
                if (!done->skipped.empty()) {
                    std::cerr << "; skipped:";
                    for (const auto& s : done->skipped) std::cerr << " " << printable(s) << ";";
                }
                std::cerr << "\n";
            } else if (o.verbose) {
                std::cerr << printable(sceneId(sc)) << ": " << done->frames.size() << " frames drawn in " << ms(runSeconds)
                          << "\n";
            }
        } catch (const std::exception& e) {
            std::cerr << (tty ? "\n" : "") << failureLine(job, e) << "\n";
            failed += !submitted;
        }
    }
    return writer.finish();
}

// Reads and checks one scene file; throws InputError naming it.
SceneJob validateScene(const std::string& file, const RunnerOptions& o) {
    SceneJob job;
    job.file = file;
    const std::string bytes = readJsonText(file);
    job.scene = loadSceneText(bytes, file);
    const SceneCommon& sc = job.scene->common();
    if (!o.demo.empty() && sc.demo != o.demo)
        throw InputError(file + ": $.demo: this scene is for demo '" + sc.demo + "', not '" + o.demo + "'");
    if (!o.noRender) checkImageBudget(sc, o.scale, o.steps);  // --scale and --steps multiply what the scene asked for
    try {
        job.dir = o.perFileOutput ? renderOutputDir(file, o) : sceneOutputDir(o.outDir, sc.demo, sc.name);
        refuseInsideGolden(job.dir, o);  // also through a symlinked folder below --out
        requireFolderOrNothing(job.dir);
        // A folder whose manifest.json or trace.json is the user's is refused now, before any
        // scene is drawn; the frames' names are checked again when the folder is written.
        {
            FolderLock lock(job.dir);  // another run writing it has listed its files first
            refuseForeign(job.dir, "trace.json", previouslyWritten(job.dir));
        }
        if (!o.perFileOutput) requireGalleryPage(job.dir.string() + ".html");
    } catch (const InputError& e) {
        throw InputError(printable(file) + ": " + e.what());
    }
    job.key = cacheKey(bytes, o) + (o.noRender ? "-numeric" : "");
    return job;
}

// Every scene is validated before anything is written; every bad one is reported (one line each).
bool validateAll(const std::vector<std::string>& files, const RunnerOptions& o, std::vector<SceneJob>& jobs) {
    int bad = 0;
    for (const auto& f : files) {
        try {
            jobs.push_back(validateScene(f, o));
        } catch (const InputError& e) {
            std::cerr << printable(e.what()) << "\n";
            ++bad;
        } catch (const std::exception& e) {  // e.g. std::bad_alloc while reading a scene
            std::cerr << printable(f) << ": " << printable(e.what()) << "\n";
            ++bad;
        }
    }
    // Two scenes writing one folder would overwrite each other (hostile_harness_test "two scenes
    // into one folder are refused").
    std::map<fs::path, const SceneJob*> folders;
    for (const SceneJob& job : jobs) {
        const auto [at, added] = folders.emplace(resolvedFolder(job.dir), &job);
        if (!added) {
            std::cerr << printable(job.file) << ": writes the same folder " << printable(job.dir.string()) << " as "
                      << printable(at->second->file)
                      << (o.perFileOutput ? " (rename one, or render them one at a time with --out)"
                                          : " (two scenes of one demo with one name)")
                      << "\n";
            ++bad;
        }
    }
    if (bad)
        std::cerr << (o.perFileOutput ? "cdlab render: " : "cdlab figures: ") << bad << " of " << files.size() << " scene" << (files.size() == 1 ? "" : "s")
                  << (bad == 1 ? " is" : " are") << " invalid; nothing written\n";
    return bad == 0;
}

}  // namespace

int runFigures(const RunnerOptions& o) { return renderSceneFiles(selectScenes(o), o); }

int renderSceneFiles(const std::vector<std::string>& files, const RunnerOptions& o) {
    if (o.list) {
        for (const auto& f : files)
            std::cout << printable(fs::path(f).parent_path().filename().string() + "/" + fs::path(f).stem().string()) << "\n";
        return 0;
    }
    if (files.empty()) {
        std::cerr << "cdlab figures: no scene matches\n";
        return 2;
    }
    if (!o.perFileOutput) {  // figures: the gallery pages and the golden folder, before any scene
        try {
            refuseInsideGolden(o.outDir, o);
            requireGalleryPage((fs::path(o.outDir) / "index.html").string());
        } catch (const InputError& e) {
            std::cerr << "cdlab figures: " << printable(e.what()) << "; nothing written\n";
            return 2;
        }
    }
    std::vector<SceneJob> jobs;
    if (!validateAll(files, o, jobs)) return 2;
    {
        std::error_code ec;
        fs::create_directories(o.outDir, ec);
        if (ec) {
            std::cerr << "cdlab figures: cannot create the output folder '" << printable(o.outDir) << "': " << ec.message()
                      << "\n";
            return 2;
        }
    }

    // Which scenes need work: the GL context (70 ms .. 1 s) is created only if one does.
    bool anyTodo = false;
    for (SceneJob& job : jobs) {
        job.todo = o.force || !cacheValid(job.dir, job.key);
        anyTodo = anyTodo || job.todo;
    }
    auto t0 = Clock::now();
    int frames = 0, rendered = 0, failed = 0;
    const bool tty = isatty(fileno(stderr)) && !std::getenv("CI");
    std::vector<WriteReport> reports;
    if (const int workers = anyTodo ? workerCount(o, jobs) : 1; workers > 1) {
        reports = renderOnWorkers(jobs, o, workers, tty, t0);
    } else {
        reports = renderOnThisThread(jobs, o, anyTodo, tty, t0, failed);
    }
    for (const WriteReport& report : reports) {
        if (!report.error.empty()) {
            std::cerr << (tty ? "\n" : "") << report.error << "\n";
            ++failed;
            continue;
        }
        ++rendered;
        frames += report.frames;
        if (!report.note.empty()) std::cerr << (tty ? "\n" : "") << report.note << "\n";
    }
    if (tty && !o.verbose && !o.profile) std::cerr << "\n";
    if (o.perFileOutput) {
        std::cerr << "cdlab render: " << jobs.size() << " scene" << (jobs.size() == 1 ? "" : "s") << " (" << rendered
                  << " rendered, " << jobs.size() - rendered - failed << " unchanged";
        if (failed) std::cerr << ", " << failed << " failed";
        std::cerr << "), " << frames << " frames in " << secondsSince(t0) << " s\n";
        return failed ? 2 : 0;
    }
    int pagesRefused = 0;  // gallery pages of the user's (reported by writeGallery), not scenes
    {
        FolderLock lock(o.outDir);
        pagesRefused = writeGallery(o.outDir);
    }
    std::cerr << "cdlab figures: " << jobs.size() << " scenes (" << rendered << " rendered, "
              << int(jobs.size()) - rendered - failed << " unchanged";
    if (failed) std::cerr << ", " << failed << " failed";
    if (pagesRefused) std::cerr << ", " << pagesRefused << " gallery page" << (pagesRefused == 1 ? "" : "s") << " refused";
    std::cerr << "), " << frames << " frames into " << printable(o.outDir) << " in " << secondsSince(t0)
              << " s; gallery " << printable((fs::path(o.outDir) / "index.html").string()) << "\n";
    return failed || pagesRefused ? 2 : 0;
}

}  // namespace cdlab::demos
