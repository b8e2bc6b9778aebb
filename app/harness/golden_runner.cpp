#include "app/harness/scene_runner.h"

#include <fnmatch.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "app/catalog/catalog.h"
#include "app/harness/trace_compare.h"
#include "app/scene/scene_limits.h"
#include "render/compare.h"
#include "render/image.h"
#include "render/legibility.h"
#include "render/pixel_budget.h"

namespace cdlab::demos {

namespace fs = std::filesystem;

namespace {

// ---- The failure report folder ----------------------------------------------------------------
// `--report DIR` may name a folder of the user's (`--report .`), so a run deletes only what an
// earlier run wrote there: the files listed in DIR/cdlab-report.txt, then the folders that list
// says it created (if empty), then the list itself. Nothing else in DIR is ever touched. Paths
// are listed before their files are written, so a run killed half-way is still cleaned up. (A
// text list, not JSON: a report folder inside golden/ must not look like a scene file.)
constexpr const char* kReportList = "cdlab-report.txt";
constexpr const char* kReportHeader = "# cdlab golden --report: what this report wrote (the next run deletes it)";

// A path relative to the report folder whose every component is a plain name.
bool isPlainRelativePath(const std::string& rel) {
    std::size_t start = 0;
    for (;;) {
        const std::size_t slash = rel.find('/', start);
        if (!isPlainName(rel.substr(start, slash == std::string::npos ? std::string::npos : slash - start)))
            return false;
        if (slash == std::string::npos) return true;
        start = slash + 1;
    }
}

class ReportFolder {
public:
    explicit ReportFolder(fs::path root) : root_(std::move(root)) {}

    /// A path below the report folder that goes through a symlink (a folder of the path, or the
    /// file itself): never written or deleted through (hostile_harness_test "golden --report
    /// writes and deletes nothing through a symlink").
    bool throughSymlink(const std::string& rel) const {
        fs::path p = root_;
        std::error_code ec;
        for (const fs::path& part : fs::path(rel)) {
            p /= part;
            if (fs::symlink_status(p, ec).type() == fs::file_type::symlink) return true;
        }
        return false;
    }

    const fs::path& root() const { return root_; }

    /// Deletes what the previous report listed. A list that is not cdlab's (unreadable, another
    /// format, a path that could leave the folder) is reported and nothing is deleted.
    void removePrevious() const {
        const fs::path list = root_ / kReportList;
        std::error_code ec;
        if (fs::symlink_status(list, ec).type() == fs::file_type::not_found) return;
        std::vector<std::string> files, folders;
        const std::string problem = readList(list, files, folders);
        if (!problem.empty()) {
            std::cerr << "cdlab golden: " << printable(list.string()) << ": " << printable(problem) << "; nothing in " << printable(root_.string())
                      << " deleted\n";
            return;
        }
        for (const std::string& rel : files)
            if (!throughSymlink(rel) && fs::symlink_status(root_ / rel, ec).type() == fs::file_type::regular)
                fs::remove(root_ / rel, ec);
        // Deepest first; rmdir() removes only empty folders (and no symlink).
        std::sort(folders.begin(), folders.end(), [](const std::string& a, const std::string& b) {
            return std::count(a.begin(), a.end(), '/') > std::count(b.begin(), b.end(), '/');
        });
        for (const std::string& rel : folders)
            if (!throughSymlink(rel)) ::rmdir((root_ / rel).c_str());
        fs::remove(list, ec);
    }

    /// Lists report files (paths relative to the folder) before they are written, with the
    /// folders that do not exist yet. Throws std::runtime_error when the list cannot be written.
    void plan(const std::vector<std::string>& relativeFiles) {
        for (const std::string& rel : relativeFiles) {
            for (std::size_t slash = rel.find('/'); slash != std::string::npos; slash = rel.find('/', slash + 1)) {
                const std::string folder = rel.substr(0, slash);
                std::error_code ec;
                if (std::find(folders_.begin(), folders_.end(), folder) == folders_.end() &&
                    !fs::exists(root_ / folder, ec))
                    folders_.push_back(folder);
            }
            if (std::find(files_.begin(), files_.end(), rel) != files_.end()) continue;
            // removePrevious() took away every file an earlier report listed: anything still at
            // this path is the user's (hostile_harness_test "golden --report . keeps the user's
            // index.html"), and is never replaced.
            std::error_code ec;
            if (throughSymlink(rel))
                throw std::runtime_error("refusing to write " + printable((root_ / rel).string()) +
                                         ": a folder on its path is a symlink; give --report a folder of its own");
            if (fs::symlink_status(root_ / rel, ec).type() != fs::file_type::not_found)
                throw std::runtime_error("refusing to overwrite " + printable((root_ / rel).string()) +
                                         ": cdlab did not write it (" + kReportList +
                                         " does not list it); give --report a folder of its own");
            files_.push_back(rel);
        }
        std::string text = std::string(kReportHeader) + "\n";
        for (const std::string& f : files_) text += "file " + f + "\n";
        for (const std::string& f : folders_) text += "folder " + f + "\n";
        render::writeFileAtomic((root_ / kReportList).string(), text);
    }

private:
    // "" when the list reads; else what is wrong (with its line number).
    static std::string readList(const fs::path& list, std::vector<std::string>& files,
                                std::vector<std::string>& folders) {
        std::string text, problem;
        if (!render::readFileBounded(list.string(), kMaxJsonFileBytes, "a report list", text, problem)) return problem;
        std::istringstream in(text);
        std::string line;
        if (!std::getline(in, line) || line != kReportHeader) return "line 1: not a cdlab report list";
        for (int n = 2; std::getline(in, line); ++n) {
            const std::size_t space = line.find(' ');
            const std::string kind = line.substr(0, space),
                              rel = space == std::string::npos ? "" : line.substr(space + 1);
            if ((kind != "file" && kind != "folder") || !isPlainRelativePath(rel))
                return "line " + std::to_string(n) + ": " +
                       Json(line).dump(-1, ' ', false, Json::error_handler_t::replace) +
                       " is not \"file <path>\" or \"folder <path>\" with a plain relative path";
            (kind == "file" ? files : folders).push_back(rel);
        }
        return "";
    }

    fs::path root_;
    std::vector<std::string> files_, folders_;
};

// ---- One golden run ---------------------------------------------------------------------------

bool goldenExists(const fs::path& golden) {
    std::error_code ec;
    return fs::symlink_status(golden, ec).type() != fs::file_type::not_found;
}

// What is wrong with a golden: "" when `compare` (which reads it and returns "" or what differs)
// passes, the ReadError it throws, or that the golden is missing.
template <class ReadError, class Compare>
std::string goldenProblem(const fs::path& golden, bool exists, const Compare& compare) {
    if (!exists) return "missing golden " + golden.string();
    try {
        return compare();
    } catch (const ReadError& e) {
        return e.what();
    }
}

// What to run to create a scene's missing goldens: that scene only, not the whole suite.
std::string createHint(const SceneCommon& sc) {
    return " (create it with: ./cdlab golden --scene " + sceneId(sc) + " --update failing)";
}

struct GoldenRun {
    const RunnerOptions& options;
    ReportFolder report;
    std::vector<render::ReportEntry> entries;
    int checked = 0, failed = 0, updated = 0;
    bool writeFailed = false;  // a golden update or a report file could not be written: exit 2

    void fail(const std::string& what) {
        std::cout << "FAIL " << printable(what) << "\n";
        ++failed;
    }
    void sceneFailed(const std::string& what) {  // one failed check for the scene as a whole
        ++checked;
        fail(what);
    }
    void writeError(const std::string& what) {
        std::cerr << "cdlab golden: " << printable(what) << "\n";
        writeFailed = true;
    }
    bool updates(const std::string& problem) const {
        return options.update == "all" || (!problem.empty() && !options.update.empty());
    }
    /// With --update-golden, rewrites golden `id` through `write` when `problem` (or "all") asks for
    /// it; true when it did or tried (nothing more to check then).
    template <class Write>
    bool updateGolden(const std::string& id, const std::string& problem, const Write& write) {
        if (!updates(problem)) return false;
        try {
            write();
            std::cout << "UPDATED " << printable(id + (problem.empty() ? "" : " (was: " + problem + ")")) << "\n";
            ++updated;
        } catch (const std::exception& e) {
            fail(id + ": " + problem);
            writeError(e.what());
        }
        return true;
    }

    // Legibility problems of every frame, for the summary of the worst.
    struct Offender {
        std::string frame;
        render::LegibilityProblem problem;
    };
    std::vector<Offender> offenders{};

    void runScene(const std::string& file, const RunContext& ctx);
    void checkLegibility(const SceneCommon& sc, const Frame& fr);
    void checkFrame(const SceneCommon& sc, const Frame& fr, const fs::path& goldenDir);
    void checkTrace(const SceneCommon& sc, const Json& trace, const fs::path& goldenDir);
    void reportFrame(const SceneCommon& sc, const Frame& fr, const fs::path& goldenPng, bool exists,
                     const std::string& problem);
};

// Any exception from one scene (its file, its run, a golden it reads) fails that scene only.
void GoldenRun::runScene(const std::string& file, const RunContext& ctx) {
    try {
        std::unique_ptr<PreparedScene> scene = loadScene(file);
        const SceneCommon& sc = scene->common();
        const fs::path goldenDir = sceneOutputDir(fs::path(file).parent_path().parent_path(),
                                                  fs::path(file).parent_path().filename().string(), sc.name);
        render::PixelBudget budget(kMaxScenePixels);  // every frame of the scene together
        DemoOutput out = scene->run(ctx);
        for (const Frame& fr : out.frames) {
            checkFrame(sc, fr, goldenDir);
            checkLegibility(sc, fr);
        }
        checkTrace(sc, out.trace, goldenDir);
    } catch (const InputError& e) {
        const std::string what = e.what();
        sceneFailed(what.rfind(file, 0) == 0 ? what : file + ": " + what);
    } catch (const render::GlError& e) {
        sceneFailed(file + ": OpenGL: " + e.what());
    } catch (const std::exception& e) {  // render::ImageError, std::bad_alloc, ...
        sceneFailed(file + ": " + e.what());
    }
}

void GoldenRun::checkFrame(const SceneCommon& sc, const Frame& fr, const fs::path& goldenDir) {
    ++checked;
    const std::string id = sceneId(sc) + "/" + fr.name;
    if (!isPlainName(fr.name)) throw std::logic_error("frame name " + Json(fr.name).dump() + " is not a plain name");
    const fs::path goldenPng = goldenDir / (fr.name + ".png");
    const bool exists = goldenExists(goldenPng);
    render::CompareResult cmp;
    std::string problem = goldenProblem<render::ImageError>(goldenPng, exists, [&] {
        cmp = render::compareImages(fr.image, render::readPng(goldenPng.string()), sc.golden.image);
        return cmp.passed ? std::string() : cmp.summary();
    });
    if (updateGolden(id, problem, [&] { render::writePngAtomic(goldenPng.string(), fr.image); })) return;
    if (problem.empty()) {
        std::cout << "PASS " << printable(id) << ": " << cmp.summary() << "\n";
        return;
    }
    if (!exists) problem += createHint(sc);
    fail(id + ": " + problem);
    reportFrame(sc, fr, goldenPng, exists, problem);
}

// The frame's recorded layout and pixels against render/legibility.h's rules.
void GoldenRun::checkLegibility(const SceneCommon& sc, const Frame& fr) {
    if (fr.image.width == 0) return;
    ++checked;
    const std::string id = sceneId(sc) + "/" + fr.name;
    const std::vector<render::LegibilityProblem> problems =
        render::checkFigure(fr.image);
    for (const render::LegibilityProblem& p : problems) offenders.push_back({id, p});
    if (problems.empty()) return;
    fail(id + ": not slide-legible, " + std::to_string(problems.size()) +
         " problem(s); worst: " + render::describe(problems.front()));
    std::string details = "not slide-legible: " + render::describe(problems.front());
    for (std::size_t i = 1; i < problems.size() && i < 6; ++i) {
        std::cout << "     " << printable(render::describe(problems[i])) << "\n";
        details += "\n" + render::describe(problems[i]);
    }
    entries.push_back({id, "", "", "", details});
}

// actual / expected / diff PNGs of a failed frame into the report folder.
void GoldenRun::reportFrame(const SceneCommon& sc, const Frame& fr, const fs::path& goldenPng, bool exists,
                            const std::string& problem) {
    const std::string id = sceneId(sc) + "/" + fr.name;
    const std::string rel = sc.demo + "/" + sc.name + "/" + fr.name;
    const fs::path rdir = sceneOutputDir(report.root(), sc.demo, sc.name);
    render::ReportEntry entry{id, rel + ".actual.png", "", "", problem};
    try {
        std::optional<render::Image> expected;
        if (exists) {
            try {
                expected = render::readPng(goldenPng.string());
            } catch (const render::ImageError&) {  // already reported as the problem
            }
        }
        report.plan(expected ? std::vector<std::string>{rel + ".actual.png", rel + ".expected.png", rel + ".diff.png"}
                             : std::vector<std::string>{rel + ".actual.png"});
        render::writePngAtomic((rdir / (fr.name + ".actual.png")).string(), fr.image);
        if (expected) {
            render::writePngAtomic((rdir / (fr.name + ".expected.png")).string(), *expected);
            render::writePngAtomic((rdir / (fr.name + ".diff.png")).string(), render::diffImage(fr.image, *expected));
            entry.expectedPng = rel + ".expected.png";
            entry.diffPng = rel + ".diff.png";
        }
    } catch (const std::exception& e) {
        writeError("report: " + std::string(e.what()));
    }
    entries.push_back(entry);
}

// The numeric trace: an algorithm regression fails even when the pixels look alike.
void GoldenRun::checkTrace(const SceneCommon& sc, const Json& trace, const fs::path& goldenDir) {
    ++checked;
    const fs::path goldenTrace = goldenDir / "trace.json";
    const std::string id = sceneId(sc) + "/trace.json";
    const bool exists = goldenExists(goldenTrace);
    TraceComparison tc;
    const std::string problem = goldenProblem<InputError>(goldenTrace, exists, [&] {
        tc = compareTraces(trace, readJsonFile(goldenTrace.string()), sc.golden.traceAbsolute, sc.golden.traceRelative);
        return tc.passed() ? std::string() : tc.summary();
    });
    if (updateGolden(id, problem, [&] { render::writeFileAtomic(goldenTrace.string(), traceText(trace)); })) return;
    if (problem.empty()) {
        std::cout << "PASS " << printable(id) << ": " << printable(tc.summary()) << "\n";
        return;
    }
    fail(id + ": " + problem + (exists ? "" : createHint(sc)));
    std::string details = problem + (exists ? "" : createHint(sc));
    for (std::size_t i = 1; i < tc.mismatches.size(); ++i) {
        std::cout << "     " << printable(tc.mismatches[i].path + ": " + tc.mismatches[i].what) << "\n";
        details += "\n" + tc.mismatches[i].path + ": " + tc.mismatches[i].what;
    }
    entries.push_back({id, "", "", "", details});  // the report lists trace failures too
}

}  // namespace

int runGolden(const RunnerOptions& o) {
    const std::vector<std::string> files = selectScenes(o);
    if (files.empty()) {
        std::cerr << "cdlab golden: no scene matches\n";
        return 2;
    }
    GoldenRun run{
        o,
        ReportFolder(o.reportDir.empty() ? std::string(CDLAB_SOURCE_DIR) + "/build/golden-report" : o.reportDir),
        {}};
    // The report never mixes with the goldens: not the golden folder itself, nor inside a folder
    // of it that holds scenes (a demo's; its PNGs would sit beside the goldens). A folder of its
    // own below it (tests use <golden>/report) is fine.
    {
        const auto resolved = [](const fs::path& p) {
            std::error_code ec;
            const fs::path r = fs::weakly_canonical(fs::absolute(p), ec);
            return ec ? fs::absolute(p).lexically_normal() : r;
        };
        const fs::path golden =
            resolved(o.goldenDir.empty() ? fs::path(CDLAB_SOURCE_DIR) / "golden" : fs::path(o.goldenDir));
        const fs::path report = resolved(run.report.root());
        const auto [g, r] = std::mismatch(golden.begin(), golden.end(), report.begin(), report.end());
        const auto holdsScenes = [](const fs::path& dir) {
            std::error_code ec;
            for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
                if (it->path().extension() == ".json" && it->is_regular_file(ec)) return true;
            return false;
        };
        if (g == golden.end() && (r == report.end() || holdsScenes(golden / *r))) {
            std::cerr << "cdlab golden: the report folder " << printable(run.report.root().string())
                      << " is inside the golden folder " << printable(golden.string())
                      << ": give --report a folder outside it\n";
            return 2;
        }
    }
    run.report.removePrevious();

    std::unique_ptr<render::GlContext> gl = createContext(o.verbose);  // one context for the whole run
    const RunContext ctx{gl.get(), 0, false};
    for (const auto& file : files) run.runScene(file, ctx);

    if (!run.entries.empty()) {
        const std::string page = (run.report.root() / "index.html").string();
        try {
            run.report.plan({"index.html"});
            render::writeHtmlReport(page, run.entries);
            std::cout << "report: " << printable(page) << "\n";
        } catch (const std::exception& e) {
            run.writeError("report: " + std::string(e.what()));
        }
    }
    if (!run.offenders.empty()) {
        std::stable_sort(run.offenders.begin(), run.offenders.end(),
                         [](const auto& a, const auto& b) { return a.problem.severity > b.problem.severity; });
        std::cout << "legibility: " << run.offenders.size() << " problem(s); worst:\n";
        for (std::size_t i = 0; i < run.offenders.size() && i < 12; ++i) {
            std::cout << "  " << printable(run.offenders[i].frame + ": " + render::describe(run.offenders[i].problem)) << "\n";
        }
    }
    std::cout << "golden: " << run.checked - run.failed - run.updated << " passed, " << run.failed << " failed";
    if (run.updated) std::cout << ", " << run.updated << " updated";
    std::cout << "\n";
    if (run.writeFailed) return 2;
    return run.failed ? 1 : 0;
}

}  // namespace cdlab::demos
