// The harness and the file system under hostile conditions: no run deletes a file it
// did not write, concurrent runs into one folder both succeed, state in out/ that cdlab did not
// write is reported and skipped, a broken golden or scene fails that scene only, and the JSON
// reader bounds what a few bytes can cost. Every cdlab run here is a forked child (its own GL
// context, its exit status and output captured), as on the command line.
#include <doctest/doctest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "app/cli/cli.h"
#include "app/tools/tool_commands.h"
#include "app/harness/gallery.h"
#include "app/harness/scene_runner.h"
#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "render/canvas.h"
#include "render/image.h"
#include "render/pixel_budget.h"
#include "tests/app/harness/temp_files.h"

using namespace cdlab::demos;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

fs::path tempDir(const std::string& name) {
    fs::path p = fs::temp_directory_path() / ("cdlab_harness_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A small scene (256 px, a few frames with steps) so that each run takes a fraction of a second.
void writeScene(const fs::path& file, bool steps = false) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << R"({"demo": "voronoi_triangle", "image": {"width": 256, "height": 256},
      "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]], "queries": [[-0.5, -0.5, 0.2], [1.0, 0.5, 0.5]],
      "views": ["plane"],
      "layers": ["regions", "boundaries", "closest", "queries"], "steps": )"
                        << (steps ? "true" : "false") << "}";
}

struct Child {
    pid_t pid = -1;
    fs::path out, err;
};

struct Result {
    int status = -1;  // exit status, or -1 when killed by a signal
    std::string out, err;
};

// Starts `cdlab args...` (or `demo_<demo> args...` when demo is set) in a child whose stdout and
// stderr go to files; `limitFileSize` > 0 sets RLIMIT_FSIZE there (a full disk, EFBIG for ENOSPC).
Child start(const std::vector<std::string>& args, const fs::path& logs, const std::string& demo = "",
            rlim_t limitFileSize = 0) {
    static int counter = 0;
    Child c;
    c.out = logs / ("out." + std::to_string(counter));
    c.err = logs / ("err." + std::to_string(counter++));
    std::fflush(nullptr);  // else the child's freopen() writes the parent's buffered output again
    c.pid = fork();
    if (c.pid == 0) {
        if (!std::freopen(c.out.c_str(), "w", stdout) || !std::freopen(c.err.c_str(), "w", stderr)) _exit(5);
        // As a shell starts cdlab: doctest's crash handlers (SIGINT, SIGTERM) are not inherited.
        for (const int sig : {SIGINT, SIGTERM, SIGHUP}) signal(sig, SIG_DFL);
        if (limitFileSize > 0) {
            signal(SIGXFSZ, SIG_IGN);
            rlimit limit{limitFileSize, limitFileSize};
            setrlimit(RLIMIT_FSIZE, &limit);
        }
        std::vector<std::string> a = args;
        a.insert(a.begin(), demo.empty() ? "cdlab" : "demo_" + demo);
        std::vector<char*> argv;
        for (auto& s : a) argv.push_back(s.data());
        const int status =
            demo.empty() ? cdlabMain(int(argv.size()), argv.data(), toolCommands()) : demoMain(demo, int(argv.size()), argv.data());
        std::fflush(stdout);
        std::fflush(stderr);
        _exit(status);
    }
    return c;
}

Result finish(const Child& c) {
    int status = 0;
    waitpid(c.pid, &status, 0);
    Result r;
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(c.out);
    r.err = slurp(c.err);
    return r;
}

Result run(const std::vector<std::string>& args, const fs::path& logs, const std::string& demo = "",
           rlim_t limitFileSize = 0) {
    return finish(start(args, logs, demo, limitFileSize));
}

// Every file under `dir` (relative path -> bytes).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = slurp(e.path());
    return files;
}


// A golden folder with one small scene and its goldens; `args` compares them with a report into
// `rep`, `update` also updates failing ones.
struct GoldenSetup {
    fs::path root, golden, rep;
    std::vector<std::string> args, update;
};
GoldenSetup goldenSetup(const std::string& name) {
    GoldenSetup g;
    g.root = tempDir(name);
    g.golden = g.root / "golden";
    g.rep = g.root / "rep";
    writeScene(g.golden / "voronoi_triangle" / "small.json");
    g.args = {"golden", "--golden-dir", g.golden.string(), "--report", g.rep.string()};
    g.update = g.args;
    g.update.insert(g.update.end(), {"--update", "failing"});
    REQUIRE(run(g.update, g.root).status == 0);
    return g;
}

// What parseJson says of `text` (source "src"), or "" when it parses.
std::string parseError(const std::string& text) {
    try {
        parseJson(text, "src");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Every output file decodes (PNG) or parses (JSON); returns how many there are.
int checkComplete(const fs::path& out) {
    int n = 0;
    for (const auto& e : fs::recursive_directory_iterator(out)) {
        if (!e.is_regular_file()) continue;
        ++n;
        CHECK_MESSAGE(!cdlab::test::isTempFile(e.path()), "temp file left: " << e.path());
        const std::string ext = e.path().extension().string();
        if (ext == ".png") CHECK_NOTHROW(cdlab::render::readPng(e.path().string()));
        if (ext == ".json") CHECK_NOTHROW(readJsonFile(e.path().string()));
    }
    return n;
}

}  // namespace

TEST_SUITE("hostile harness") {
    TEST_CASE("a scene named '...json' is refused: nothing in --out or golden/ is deleted or written") {
        // Reproducer: mkdir -p /tmp/x/out && echo precious > /tmp/x/out/user.txt &&
        //   cp golden/gjk/box_box.json '/tmp/x/...json' && demo_gjk --out /tmp/x/out '/tmp/x/...json'
        // The scene name ".." made the output folder <out>/gjk/.. = <out>, and the stale-file cleanup
        // then deleted user.txt. In golden/, `--update` wrote into the demo's folder itself.
        const fs::path root = tempDir("dotdot");
        fs::create_directories(root / "out");
        std::ofstream(root / "out" / "user.txt") << "precious";
        writeScene(root / "...json");
        Result r = run({"--out", (root / "out").string(), (root / "...json").string()}, root, "voronoi_triangle");
        CHECK(r.status == 2);
        CHECK(contains(r.err, (root / "...json").string() + ": "));  // the scene reader or the runner refuses it
        CHECK(snapshot(root / "out") == std::map<std::string, std::string>{{"user.txt", "precious"}});

        writeScene(root / "golden" / "voronoi_triangle" / "...json");
        const auto before = snapshot(root / "golden");
        r = run({"golden", "--golden-dir", (root / "golden").string(), "--update", "all", "--report",
                 (root / "report").string()},
                root);
        CHECK(r.status == 1);
        CHECK(contains(r.out, "FAIL " + (root / "golden" / "voronoi_triangle" / "...json").string() + ": "));
        CHECK(snapshot(root / "golden") == before);
        fs::remove_all(root);
    }

    TEST_CASE("sceneOutputDir refuses every name that could leave its folder") {
        // Reproducer: the scene name is the file stem, and fs::path("...json").stem() is "..".
        const fs::path root = "/tmp/out";
        CHECK(sceneOutputDir(root, "gjk", "box_box") == root / "gjk" / "box_box");
        CHECK(sceneOutputDir(root, "gjk", "v2.1-final") == root / "gjk" / "v2.1-final");
        for (const std::string& bad : std::vector<std::string>{"..", ".", "", ".hidden", "a/b", "../x", "/etc", "a\\b",
                                                               "x y", std::string(256, 'a')}) {
            CHECK_THROWS_AS(sceneOutputDir(root, "gjk", bad), InputError);
            CHECK_THROWS_AS(sceneOutputDir(root, bad, "box_box"), InputError);
        }
        CHECK_FALSE(isPlainName(std::string("a\0b", 3)));
    }

    TEST_CASE("golden --report deletes only the files an earlier report wrote") {
        // Reproducer: mkdir rep && echo precious > rep/user.txt && cdlab golden --report rep
        // (everything passing) -> rep was removed recursively; `--report .` wiped the working folder.
        const GoldenSetup g = goldenSetup("report");
        const fs::path &root = g.root, &golden = g.golden, &rep = g.rep;
        const std::vector<std::string>& args = g.args;
        const std::vector<std::string>& update = g.update;

        fs::create_directories(rep / "userdir" / "empty");
        std::ofstream(rep / "user.txt") << "precious";
        std::ofstream(rep / "userdir" / "keep.txt") << "keep";
        const auto userFiles = snapshot(rep);
        // A passing run into a folder full of the user's files touches none of them.
        CHECK(run(args, root).status == 0);
        CHECK(snapshot(rep) == userFiles);

        // A failing run writes its report beside them ...
        const fs::path png = golden / "voronoi_triangle" / "small" / "plane.png";
        cdlab::render::Image img = cdlab::render::readPng(png.string());
        for (int y = 10; y < 20; ++y)
            for (int x = 10; x < 20; ++x) img.pixel(x, y)[1] ^= 0x80;
        cdlab::render::writePngAtomic(png.string(), img);
        CHECK(run(args, root).status == 1);
        CHECK(fs::exists(rep / "index.html"));
        CHECK(fs::exists(rep / "voronoi_triangle" / "small" / "plane.diff.png"));
        CHECK(fs::exists(rep / "user.txt"));
        // ... and the next run removes exactly that report: files, the folders it made, its list.
        REQUIRE(run(update, root).status == 0);
        CHECK(run(args, root).status == 0);
        CHECK(snapshot(rep) == userFiles);
        CHECK(fs::is_directory(rep / "userdir" / "empty"));
        CHECK_FALSE(fs::exists(rep / "voronoi_triangle"));

        // A list that is not cdlab's (or names a path outside the folder) deletes nothing.
        std::ofstream(root / "victim.txt") << "victim";
        std::ofstream(rep / "cdlab-report.txt") << "# cdlab golden --report: what this report wrote (the next run "
                                                   "deletes it)\nfile user.txt\nfile ../victim.txt\n";
        Result r = run(args, root);
        CHECK(r.status == 0);
        CHECK(contains(r.err, "cdlab-report.txt: line 3: \"file ../victim.txt\" is not"));
        std::ofstream(rep / "cdlab-report.txt") << "user.txt\n";  // not a cdlab list at all
        r = run(args, root);
        CHECK(contains(r.err, "cdlab-report.txt: line 1: not a cdlab report list; nothing in"));
        CHECK(fs::exists(root / "victim.txt"));
        CHECK(fs::exists(rep / "user.txt"));
        fs::remove_all(root);
    }

    TEST_CASE("two figures --force runs into one out/ both succeed and leave only complete files") {
        // Reproducer: two `cdlab figures --force --scene 'gjk/*' --out c` at once, six times: one run
        // failed with "cannot write 'c/gjk/sphere_box/step_02.png': No such file or directory" (the
        // other run's stale-file cleanup had removed its temp file).
        const fs::path root = tempDir("concurrent");
        writeScene(root / "golden" / "voronoi_triangle" / "a.json", true);
        writeScene(root / "golden" / "voronoi_triangle" / "b.json", true);
        const std::vector<std::string> args = {
            "figures", "--force", "--golden-dir", (root / "golden").string(), "--out", (root / "out").string()};
        // The old cleanup failed about one pair in seven here (3 of 20): ten pairs catch it most times.
        for (int i = 0; i < 10; ++i) {
            const Child one = start(args, root), two = start(args, root);
            const Result r1 = finish(one), r2 = finish(two);
            CHECK_MESSAGE(r1.status == 0, r1.err);
            CHECK_MESSAGE(r2.status == 0, r2.err);
        }
        CHECK(checkComplete(root / "out") > 6);
        const FigureManifest m = readFigureManifest(root / "out" / "voronoi_triangle" / "a" / "manifest.json");
        for (const std::string& f : m.files) CHECK(fs::exists(root / "out" / "voronoi_triangle" / "a" / f));
        fs::remove_all(root);
    }

    TEST_CASE("figures on several workers: the files of a serial run, byte for byte") {
        // `cdlab figures` renders scenes on one worker per core, each with its own GL context;
        // --profile keeps one worker (each phase timed alone): the two runs must write the same bytes.
        const fs::path root = tempDir("workers");
        for (const char* name : {"a", "b", "c", "d", "e"})
            writeScene(root / "golden" / "voronoi_triangle" / (std::string(name) + ".json"), name[0] % 2 == 1);
        const auto figures = [&](const std::string& out, bool serial) {
            std::vector<std::string> args = {"figures", "--force", "--golden-dir", (root / "golden").string(),
                                             "--out", (root / out).string()};
            if (serial) args.push_back("--profile");
            return run(args, root);
        };
        const Result serial = figures("serial", true), parallel = figures("parallel", false);
        REQUIRE_MESSAGE(serial.status == 0, serial.err);
        REQUIRE_MESSAGE(parallel.status == 0, parallel.err);
        CHECK(contains(parallel.err, "5 scenes (5 rendered, 0 unchanged)"));
        const auto a = snapshot(root / "serial"), b = snapshot(root / "parallel");
        CHECK(a.size() > 20);
        CHECK(a == b);  // every PNG, GIF, trace and manifest (same binary: same cache keys)
        fs::remove_all(root);
    }

    TEST_CASE("state in out/ that cdlab did not write is reported with its path, skipped or rebuilt") {
        // Reproducer: echo '[1,2]' > out/foo/bar/manifest.json (or '{"frames":5}') and every later
        // `cdlab figures --out out` exited 2 with "[json.exception.type_error.306] cannot use value()".
        const fs::path root = tempDir("foreign");
        writeScene(root / "golden" / "voronoi_triangle" / "a.json");
        const fs::path out = root / "out", scene = out / "voronoi_triangle" / "a";
        fs::create_directories(out / "foo" / "bar");
        fs::create_directories(scene);
        std::ofstream(out / "foo" / "bar" / "manifest.json") << "[1,2]";
        std::ofstream(scene / "manifest.json") << R"({"frames": 5, "files": ["../../../user.txt", "notes.txt"]})";
        std::ofstream(scene / "notes.txt") << "the user's";
        std::ofstream(root / "user.txt") << "precious";
        const std::string foreignManifest = slurp(scene / "manifest.json");
        Result r = run({"figures", "--golden-dir", (root / "golden").string(), "--out", out.string()}, root);
        // A scene folder whose manifest.json is not cdlab's is the user's: refused, nothing written.
        CHECK(r.status == 2);
        CHECK(contains(r.err, "refusing to write into " + scene.string() + ": its manifest.json is not cdlab's (" +
                                  (scene / "manifest.json").string() + ": $: missing required key 'key')"));
        CHECK(slurp(scene / "manifest.json") == foreignManifest);
        CHECK(fs::exists(scene / "notes.txt"));  // never listed by cdlab: never deleted
        CHECK(fs::exists(root / "user.txt"));
        CHECK_FALSE(fs::exists(out / "index.html"));
        // Elsewhere in out/, a manifest that does not read is reported and left out of the gallery.
        fs::remove_all(scene);
        r = run({"figures", "--golden-dir", (root / "golden").string(), "--out", out.string()}, root);
        CHECK(r.status == 0);
        CHECK(contains(r.err, (out / "foo" / "bar" / "manifest.json").string() + ": $: expected an object"));
        CHECK(slurp(out / "foo" / "bar" / "manifest.json") == "[1,2]");  // skipped, untouched
        CHECK(fs::exists(out / "index.html"));
        fs::remove_all(root);
    }

    TEST_CASE("stress: an output folder that cannot be written exits 2") {
        // Reproducer: cdlab stress --out afile/sub (afile a regular file) -> exit 1; docs/cli.md says 2.
        const fs::path root = tempDir("stress");
        std::ofstream(root / "afile") << "a regular file where a folder should be";
        Result r = run({"stress", "--seconds", "0", "--no-figures", "--out", (root / "afile" / "sub").string()}, root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, "cannot create the output folder"));
        fs::create_directories(root / "st" / "stress.json");  // the folder is fine, one file is not
        r = run({"stress", "--seconds", "0", "--no-figures", "--out", (root / "st").string()}, root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, "stress.json"));
        fs::remove_all(root);
    }

    TEST_CASE("a golden that is a directory fails that frame, the run goes on and writes its report") {
        // Reproducer: in a copy of golden/, rm step_01.png && mkdir step_01.png; cdlab golden
        // --golden-dir copy -> "basic_filebuf::underflow error reading the file: Is a directory",
        // no file named, no report, the other scenes never checked.
        const fs::path root = tempDir("golden_dir");
        const fs::path golden = root / "golden";
        writeScene(golden / "voronoi_triangle" / "a.json");
        writeScene(golden / "voronoi_triangle" / "b.json");
        const std::vector<std::string> args = {"golden", "--golden-dir", golden.string(), "--report",
                                               (root / "rep").string()};
        std::vector<std::string> update = args;
        update.insert(update.end(), {"--update", "failing"});
        REQUIRE(run(update, root).status == 0);
        const fs::path png = golden / "voronoi_triangle" / "a" / "plane.png";
        fs::remove(png);
        fs::create_directories(png);
        fs::remove(golden / "voronoi_triangle" / "a" / "trace.json");
        fs::create_directories(golden / "voronoi_triangle" / "a" / "trace.json");
        const Result r = run(args, root);
        CHECK(r.status == 1);
        CHECK(contains(r.out, "FAIL voronoi_triangle/a/plane: cannot read '" + png.string() + "': is a directory"));
        CHECK(contains(r.out, "FAIL voronoi_triangle/a/trace.json: " + (golden / "voronoi_triangle" / "a").string() +
                                  "/trace.json: is a directory"));
        CHECK(contains(r.out, "PASS voronoi_triangle/b/plane"));
        CHECK(fs::exists(root / "rep" / "index.html"));
        // Updating onto a directory cannot write: exit 2, the path named.
        const Result u = run(update, root);
        CHECK(u.status == 2);
        CHECK(contains(u.err, png.string()));
        fs::remove_all(root);
    }

    TEST_CASE("a scene path that is a directory, /dev/zero or an endless pipe is one line, read bounded") {
        // Reproducer: mkdir d.json; demo_gjk d.json -> "byte 1: unexpected end of input";
        // demo_gjk /dev/zero read without limit.
        const fs::path root = tempDir("scene_files");
        fs::create_directories(root / "d.json");
        const auto errorOf = [](const std::string& path) -> std::string {
            try {
                readJsonFile(path);
            } catch (const InputError& e) {
                return e.what();
            }
            return "";
        };
        CHECK(errorOf((root / "d.json").string()) == (root / "d.json").string() + ": is a directory, not a file");
        CHECK(errorOf("/dev/zero") == "/dev/zero: larger than the 16 MiB limit for a JSON file");

        const fs::path fifo = root / "endless.json";
        REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
        const pid_t writer = fork();
        if (writer == 0) {
            std::FILE* f = std::fopen(fifo.c_str(), "w");
            const std::string chunk(1 << 16, ' ');
            while (f && std::fwrite(chunk.data(), 1, chunk.size(), f) == chunk.size()) {}
            _exit(0);  // the reader closed: EPIPE (or SIGPIPE)
        }
        CHECK(errorOf(fifo.string()) == fifo.string() + ": larger than the 16 MiB limit for a JSON file");
        kill(writer, SIGKILL);
        waitpid(writer, nullptr, 0);

        // A file at the limit is fine; one byte more is not (the size is checked before reading).
        std::ofstream(root / "big.json") << "[" << std::string(kMaxJsonFileBytes - 2, ' ') << "]";
        CHECK(errorOf((root / "big.json").string()).empty());
        std::ofstream(root / "big.json", std::ios::app) << " ";
        CHECK(contains(errorOf((root / "big.json").string()), "big.json: larger than the 16 MiB limit"));
        fs::remove_all(root);
    }

    TEST_CASE("figures reports every bad scene, one line each, and writes nothing") {
        // Reproducer: demo_gjk good.json d.json nul.json -> only the first bad file was named.
        const fs::path root = tempDir("bad_scenes");
        writeScene(root / "good.json");
        fs::create_directories(root / "d.json");
        std::ofstream(root / "nul.json") << std::string("{\"demo\": \"voronoi_triangle\"}\0garbage", 36);
        const Result r = run({"--out", (root / "out").string(), (root / "good.json").string(),
                              (root / "d.json").string(), (root / "nul.json").string()},
                             root, "voronoi_triangle");
        CHECK(r.status == 2);
        CHECK(contains(r.err, (root / "d.json").string() + ": is a directory, not a file\n"));
        CHECK(contains(r.err, (root / "nul.json").string() + ": byte 29: NUL byte (U+0000) is not allowed\n"));
        CHECK(contains(r.err, "2 of 3 scenes are invalid; nothing written"));
        CHECK_FALSE(fs::exists(root / "out"));
        fs::remove_all(root);
    }

    TEST_CASE("a scene that fails after validation is named, the others render, exit 2") {
        // Reproducer: a failure while running or writing one scene (an OpenGL error at --scale 4, an
        // unwritable folder) ended the whole run without naming the scene file.
        // Scene a draws more step frames than its contact sheet can hold: found while it runs.
        const fs::path root = tempDir("run_failure");
        fs::create_directories(root / "golden" / "voronoi_triangle");
        std::ofstream scene(root / "golden" / "voronoi_triangle" / "a.json");
        scene << R"({"demo": "voronoi_triangle", "image": {"width": 64, "height": 4096}, "views": ["plane"],
          "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]], "steps": true, "queries": [)";
        for (int i = 0; i < 40; ++i) scene << (i ? ", " : "") << "[" << 0.1 * i << ", " << 0.05 * i << ", 0.2]";
        scene << "]}";
        scene.close();
        writeScene(root / "golden" / "voronoi_triangle" / "b.json");
        Result r = run({"figures", "--golden-dir", (root / "golden").string(), "--out", (root / "out").string()}, root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, (root / "golden" / "voronoi_triangle" / "a.json").string() + ": the contact sheet of"));
        CHECK(contains(r.err, "1 failed"));
        CHECK(fs::exists(root / "out" / "voronoi_triangle" / "b" / "manifest.json"));
        // A file where a scene's folder should be is found before anything is drawn.
        fs::remove(root / "golden" / "voronoi_triangle" / "a.json");
        writeScene(root / "golden" / "voronoi_triangle" / "c.json");
        std::ofstream(root / "out" / "voronoi_triangle" / "c") << "a file where scene c's folder should be";
        r = run({"figures", "--golden-dir", (root / "golden").string(), "--out", (root / "out").string()}, root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, "the output folder " + (root / "out" / "voronoi_triangle" / "c").string() +
                                  " cannot be made: " + (root / "out" / "voronoi_triangle" / "c").string() +
                                  " is there and not a folder"));
        CHECK(contains(r.err, "nothing written"));
        fs::remove_all(root);
    }

    TEST_CASE("a scene whose writing fails half-way keeps its previous complete files") {
        // Reproducer: a full disk while writing a scene's frames left some frames new and some old.
        // Now every file of a scene is staged first and renamed only when all are staged.
        const fs::path root = tempDir("half_written");
        writeScene(root / "golden" / "voronoi_triangle" / "a.json", true);
        const std::vector<std::string> args = {
            "figures", "--force", "--golden-dir", (root / "golden").string(), "--out", (root / "out").string(),
            "--scale", "2"};
        REQUIRE(run(args, root).status == 0);
        const fs::path scene = root / "out" / "voronoi_triangle" / "a";
        const auto before = snapshot(scene);
        REQUIRE(before.size() > 3);
        std::vector<std::string> rerender = args;
        rerender.back() = "1";  // other pixels: every file would change
        // 8 KiB per file: the small trace fits, the first PNGs do not.
        const Result r = run(rerender, root, "", 8 * 1024);
        CHECK(r.status == 2);
        CHECK(contains(r.err, "a.json: cannot write '" + scene.string()));
        CHECK(snapshot(scene) == before);  // byte for byte, and no temp file
        fs::remove_all(root);
    }

    TEST_CASE("nesting is refused while scanning: a 60 MB nested line builds no tree") {
        // Reproducer: a 60 MB line "[[[...]]]" as a query peaked at 2.24 GB before the depth check
        // ran; an unclosed one ended in "internal error: std::bad_alloc".
        const pid_t pid = fork();
        if (pid == 0) {
            rusage before{};
            getrusage(RUSAGE_SELF, &before);
            std::string error;
            const auto refuse = [&error](const std::string& text) {
                try {
                    parseJson(text, "query");
                } catch (const InputError& e) {
                    error += e.what() + std::string("\n");
                }
            };
            refuse(std::string(30'000'000, '[') + std::string(30'000'000, ']'));
            refuse(std::string(60'000'000, '{'));
            rusage after{};
            getrusage(RUSAGE_SELF, &after);
            const long growthKiB = after.ru_maxrss - before.ru_maxrss;  // the 60 MB texts count (~120 MB)
            const bool ok = error ==
                            "query: byte 65: nesting deeper than 64 levels\n"
                            "query: byte 65: nesting deeper than 64 levels\n";
            _exit(!ok ? 3 : growthKiB > 250 * 1024 ? 4 : 0);
        }
        int status = 0;
        waitpid(pid, &status, 0);
        REQUIRE(WIFEXITED(status));
        CHECK(WEXITSTATUS(status) == 0);  // 3: wrong message, 4: peak above 250 MB (was 2.24 GB)

        // Brackets in strings are text, not nesting; an escaped quote does not end the string.
        const std::string inString = "[\"\\\"" + std::string(100, '[') + "\"]";
        CHECK(parseJson(inString, "s")[0].get<std::string>().size() == 101);
    }

    TEST_CASE("a line of millions of empty objects builds no tree") {
        // Reproducer: a 60 MB check line whose trace held 2·10^7 "{}" steps took 27 s and 3.6 GB, then
        // std::bad_alloc ended the run; `query` on a 60 MB line of "[]," took 1.5 GB. The scan before
        // the parser counts containers and values.
        std::string objects = "[";
        for (std::size_t k = 0; k <= kMaxJsonContainers; ++k) objects += "{},";
        CHECK(parseError(objects) == "src: byte " + std::to_string(3 * kMaxJsonContainers - 1) + ": more than " +
                                      std::to_string(kMaxJsonContainers) + " arrays and objects, the limit for one text");
        std::string numbers = "[0";
        for (std::size_t k = 0; k < kMaxJsonValues; ++k) numbers += ",0";
        numbers += "]";
        CHECK(contains(parseError(numbers), "more than " + std::to_string(kMaxJsonValues) + " values, the limit"));
        // Commas and brackets inside strings are text.
        CHECK(parseError("[\"" + std::string(100, ',') + std::string(100, '{') + "\"]").empty());
    }

    TEST_CASE("a NUL byte is refused with its position, not taken for the end of the text") {
        // Reproducer: printf '{"id":1,...}\0garbage\n' | cdlab query answered the part before the NUL;
        // a scene file with a NUL said "unexpected end of input".
        CHECK(parseError(std::string("{\"a\":1}\0garbage", 15)) == "src: byte 8: NUL byte (U+0000) is not allowed");
        CHECK(parseError(std::string("{\"a\":\"x\0y\"}", 11)) == "src: byte 8: NUL byte (U+0000) is not allowed");
        CHECK(parseError(std::string("\0", 1)) == "src: byte 1: NUL byte (U+0000) is not allowed");
        CHECK(parseError("{\"a\":\"x\\u0000y\"}").empty());  // the escaped form is a valid string
    }

}  // TEST_SUITE

namespace {

// A child whose stdout is /dev/full (a full disk) and stdin /dev/null.
Result runToFullDisk(const std::vector<std::string>& args, const fs::path& logs) {
    const fs::path err = logs / "err.full";
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        if (!std::freopen("/dev/null", "r", stdin) || !std::freopen("/dev/full", "w", stdout) ||
            !std::freopen(err.c_str(), "w", stderr))
            _exit(5);
        std::vector<std::string> a = args;
        a.insert(a.begin(), "cdlab");
        std::vector<char*> argv;
        for (auto& x : a) argv.push_back(x.data());
        const int status = cdlabMain(int(argv.size()), argv.data(), toolCommands());
        std::fflush(stderr);
        _exit(status);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, "", slurp(err)};
}

bool anyTempFile(const fs::path& dir) {
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec))
        if (cdlab::test::isTempFile(e.path())) return true;
    return false;
}

// A pid that no process has: a child that has exited and been waited for.
pid_t deadPid() {
    const pid_t pid = fork();
    if (pid == 0) _exit(0);
    waitpid(pid, nullptr, 0);
    return pid;
}

}  // namespace

TEST_SUITE("hostile harness: output folders") {
    TEST_CASE("golden --report . keeps the user's index.html") {
        // Reproducer: cd folder-with-index.html && cdlab golden --report . (a failing run) replaced
        // index.html with the report and listed it in cdlab-report.txt; the next, passing run deleted it.
        const GoldenSetup g = goldenSetup("report_index");
        const fs::path &root = g.root, &golden = g.golden, &rep = g.rep;
        const std::vector<std::string>& args = g.args;
        fs::create_directories(rep);
        std::ofstream(rep / "index.html") << "<html>the user's page</html>";
        const fs::path png = golden / "voronoi_triangle" / "small" / "plane.png";
        const cdlab::render::Image good = cdlab::render::readPng(png.string());
        cdlab::render::Image bad = good;
        for (int y = 10; y < 20; ++y)
            for (int x = 10; x < 20; ++x) bad.pixel(x, y)[1] ^= 0x80;
        cdlab::render::writePngAtomic(png.string(), bad);
        Result r = run(args, root);
        CHECK(r.status == 2);  // the frame fails, and the report page cannot be written
        CHECK(contains(r.out, "FAIL voronoi_triangle/small/plane"));
        CHECK(contains(r.err, "refusing to overwrite " + (rep / "index.html").string() + ": cdlab did not write it"));
        CHECK(slurp(rep / "index.html") == "<html>the user's page</html>");
        CHECK_FALSE(contains(slurp(rep / "cdlab-report.txt"), "index.html"));
        CHECK(fs::exists(rep / "voronoi_triangle" / "small" / "plane.diff.png"));  // the rest of the report
        cdlab::render::writePngAtomic(png.string(), good);
        r = run(args, root);
        CHECK(r.status == 0);
        CHECK(slurp(rep / "index.html") == "<html>the user's page</html>");
        CHECK_FALSE(fs::exists(rep / "voronoi_triangle"));
        fs::remove_all(root);
    }

    TEST_CASE("figures --out keeps the user's index.html") {
        // Reproducer: echo mine > DIR/index.html; cdlab figures --scene voronoi_triangle/regions
        // --out DIR -> index.html replaced by the gallery.
        const fs::path root = tempDir("figures_index");
        writeScene(root / "golden" / "voronoi_triangle" / "a.json");
        const fs::path out = root / "out";
        fs::create_directories(out / "voronoi_triangle");
        std::ofstream(out / "index.html") << "mine";
        const std::vector<std::string> args = {"figures", "--golden-dir", (root / "golden").string(), "--out",
                                               out.string()};
        Result r = run(args, root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, "refusing to overwrite " + (out / "index.html").string() + ": cdlab did not write it"));
        CHECK(contains(r.err, "nothing written"));
        CHECK(snapshot(out) == std::map<std::string, std::string>{{"index.html", "mine"}});
        // A scene page's path holding the user's file: refused before anything is drawn.
        fs::remove(out / "index.html");
        std::ofstream(out / "voronoi_triangle" / "a.html") << "mine too";
        r = run(args, root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, "refusing to overwrite " + (out / "voronoi_triangle" / "a.html").string()));
        CHECK(snapshot(out) == std::map<std::string, std::string>{{"voronoi_triangle/a.html", "mine too"}});
        // cdlab's own pages are rewritten, run after run.
        fs::remove(out / "voronoi_triangle" / "a.html");
        REQUIRE(run(args, root).status == 0);
        CHECK(run(args, root).status == 0);
        CHECK(contains(slurp(out / "index.html"), "<meta name=\"generator\" content=\"cdlab figures\">"));
        fs::remove_all(root);
    }

    TEST_CASE("render --out keeps a folder's own files") {
        // Reproducer: render F --out DIR overwrote a user's DIR/trace.json, DIR/result.png and a web
        // app's DIR/manifest.json (the note about it said "cdlab figures").
        const fs::path root = tempDir("render_own");
        writeScene(root / "scene.json");
        const fs::path out = root / "out";
        const std::vector<std::string> args = {"render", (root / "scene.json").string(), "--out", out.string()};
        for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
                 {"trace.json", "{\"mine\": 1}"}, {"plane.png", "not a png, but mine"}, {"manifest.json", "{\"name\": \"web app\"}"}}) {
            fs::remove_all(out);
            fs::create_directories(out);
            std::ofstream(out / name) << text;
            std::ofstream(out / "notes.txt") << "notes";
            const auto before = snapshot(out);
            const Result r = run(args, root);
            CHECK_MESSAGE(r.status == 2, name);
            CHECK_MESSAGE(contains(r.err, out.string()), r.err);
            CHECK_MESSAGE((contains(r.err, "refusing to overwrite " + (out / name).string()) ||
                           contains(r.err, "refusing to write into " + out.string() + ": its manifest.json is not cdlab's")),
                          r.err);
            CHECK_FALSE(contains(r.err, "cdlab figures"));
            CHECK_MESSAGE(snapshot(out) == before, name);  // nothing written, no temp file
        }
        // Into a folder of other files whose names do not collide: written, and re-rendered later.
        fs::remove_all(out);
        fs::create_directories(out);
        std::ofstream(out / "notes.txt") << "notes";
        REQUIRE(run(args, root).status == 0);
        CHECK(run({"render", (root / "scene.json").string(), "--out", out.string(), "--force"}, root).status == 0);
        CHECK(slurp(out / "notes.txt") == "notes");
        CHECK(fs::exists(out / "plane.png"));
        fs::remove_all(root);
    }

    TEST_CASE("figures --out inside --golden-dir is refused") {
        // Reproducer: cdlab figures --golden-dir G --out G [--scale 2] overwrote the goldens (at 2x)
        // and left html, gif and manifest files in G.
        const fs::path root = tempDir("golden_out");
        const fs::path golden = root / "golden";
        writeScene(golden / "voronoi_triangle" / "a.json");
        REQUIRE(run({"golden", "--golden-dir", golden.string(), "--update", "all", "--report", (root / "rep").string()},
                    root)
                    .status == 0);
        const auto before = snapshot(golden);
        // Also through a symlink below --out: F/voronoi_triangle -> G/voronoi_triangle.
        fs::create_directories(root / "F");
        fs::create_directory_symlink(golden / "voronoi_triangle", root / "F" / "voronoi_triangle");
        for (const fs::path& out : {golden, golden / "sub", golden / "voronoi_triangle" / ".." / "x", root / "F"}) {
            const Result r = run({"figures", "--golden-dir", golden.string(), "--out", out.string(), "--scale", "2"}, root);
            CHECK(r.status == 2);
            CHECK_MESSAGE(contains(r.err, "is inside the golden folder"), r.err);
            CHECK(snapshot(golden) == before);
        }
        // golden --report never writes its report into the golden folder.
        const Result r = run({"golden", "--golden-dir", golden.string(), "--report", (golden / "voronoi_triangle").string()}, root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, "is inside the golden folder"));
        CHECK(snapshot(golden) == before);
        fs::remove_all(root);
    }

    TEST_CASE("golden --report writes and deletes nothing through a symlink") {
        // Reproducer: mkdir R; ln -s G/voronoi_triangle R/voronoi_triangle; cdlab golden --golden-dir G
        // --report R wrote plane.actual/expected/diff.png into G/voronoi_triangle/t1/; with R/out ->
        // another folder, "file out/victim.txt" in R/cdlab-report.txt deleted that folder's victim.txt.
        const GoldenSetup g = goldenSetup("report_symlink");
        const fs::path other = g.root / "other";
        fs::create_directories(other);
        std::ofstream(other / "victim.txt") << "victim";
        fs::create_directories(g.rep);
        fs::create_directory_symlink(other, g.rep / "out");
        std::ofstream(g.rep / "cdlab-report.txt")
            << "# cdlab golden --report: what this report wrote (the next run deletes it)\nfile out/victim.txt\nfolder out\n";
        Result r = run(g.args, g.root);
        CHECK(r.status == 0);
        CHECK(slurp(other / "victim.txt") == "victim");
        // A failing frame's report would go through R/voronoi_triangle -> the golden folder: refused.
        fs::create_directory_symlink(g.golden / "voronoi_triangle", g.rep / "voronoi_triangle");
        const fs::path png = g.golden / "voronoi_triangle" / "small" / "plane.png";
        cdlab::render::Image img = cdlab::render::readPng(png.string());
        for (int y = 10; y < 30; ++y)
            for (int x = 10; x < 30; ++x) img.pixel(x, y)[1] ^= 0x80;
        cdlab::render::writePngAtomic(png.string(), img);
        const auto before = snapshot(g.golden);
        r = run(g.args, g.root);
        CHECK(r.status == 2);
        CHECK_MESSAGE(contains(r.err, "a folder on its path is a symlink"), r.err);
        CHECK(snapshot(g.golden) == before);
        fs::remove_all(g.root);
    }

    TEST_CASE("two scenes into one folder are refused before anything is written") {
        // Reproducer: cdlab render a/x.json b/x.json -> both into out/render/x, "2 rendered", exit 0;
        // figures with a scene filed under another demo's folder did the same.
        const fs::path root = tempDir("same_folder");
        writeScene(root / "a" / "x.json");
        writeScene(root / "b" / "x.json");
        Result r = run({"render", (root / "a" / "x.json").string(), (root / "b" / "x.json").string(), "--out",
                        (root / "out").string()},
                       root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, (root / "b" / "x.json").string() + ": writes the same folder"));
        CHECK(contains(r.err, "nothing written"));
        CHECK_FALSE(fs::exists(root / "out"));
        // A voronoi_triangle scene filed under another folder of the golden set, with the same name.
        writeScene(root / "golden" / "voronoi_triangle" / "x.json");
        writeScene(root / "golden" / "gjk" / "x.json");
        r = run({"figures", "--golden-dir", (root / "golden").string(), "--out", (root / "figs").string()}, root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, "writes the same folder"));
        CHECK_FALSE(fs::exists(root / "figs" / "voronoi_triangle"));
        // A dangling symlink where a scene's folder goes (out/y -> x, not there yet).
        writeScene(root / "c" / "y.json");
        fs::create_directories(root / "out2");
        fs::create_directory_symlink("x", root / "out2" / "y");
        r = run({"render", (root / "a" / "x.json").string(), (root / "c" / "y.json").string(), "--out",
                 (root / "out2").string()},
                root);
        CHECK(r.status == 2);
        CHECK_MESSAGE(contains(r.err, "is a symlink to nothing"), r.err);
        CHECK_FALSE(fs::exists(root / "out2" / "x"));
        fs::remove_all(root);
    }

    TEST_CASE("an interrupted render leaves no temp file, stale ones of dead runs are swept") {
        // Reproducer: cdlab render big_steps.json & sleep 1; kill -INT $! -> 48-65 *.png.tmp.<pid>.<n>
        // files that no later run removed.
        const fs::path root = tempDir("interrupt");
        fs::create_directories(root);
        std::ofstream(root / "big.json") << R"({"demo": "voronoi_triangle", "image": {"width": 1024, "height": 1024},
          "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]],
          "queries": [[-0.5, -0.5, 0.2], [1.0, 0.5, 0.5], [0.2, 0.2, 0.1], [3, 1, 0], [-1, 2, 0.3], [1, -1, 0]],
          "views": ["plane", "3d"], "steps": true})";
        const fs::path out = root / "out";
        int caught = 0;  // kills that came while a temp file was there
        for (int attempt = 0; attempt < 12 && caught < 2; ++attempt) {
            fs::remove_all(out);
            const Child c = start({"render", (root / "big.json").string(), "--out", out.string(), "--force"}, root);
            // Until the first temp file shows (the sanitizer build draws ~10x slower) or the run ends.
            bool seen = false, ended = false;
            int status = 0;
            for (int poll = 0; poll < 600'000 && !seen && !ended; ++poll) {
                seen = anyTempFile(out);
                if (!seen) {
                    ended = waitpid(c.pid, &status, WNOHANG) == c.pid;
                    usleep(250);
                }
            }
            if (!ended) {  // a reaped pid is never signalled
                kill(c.pid, attempt % 2 ? SIGTERM : SIGINT);
                waitpid(c.pid, &status, 0);
            }
            caught += seen && WIFSIGNALED(status);
            CHECK_MESSAGE(!anyTempFile(out), "attempt " << attempt);
        }
        CHECK(caught >= 1);

        // What SIGKILL leaves: swept by the next run into that folder; a live process's file is kept.
        fs::remove_all(out);
        REQUIRE(run({"render", (root / "big.json").string(), "--out", out.string()}, root).status == 0);
        const std::string dead = "plane.png.tmp." + std::to_string(deadPid()) + ".7";
        const std::string live = "plane.png.tmp." + std::to_string(getpid()) + ".7";
        std::ofstream(out / dead) << "x";
        std::ofstream(out / live) << "x";
        std::ofstream(out / "notes.tmp.12.x") << "not a temp name";
        const std::string usersTemp = "data.csv.tmp." + std::to_string(deadPid()) + ".1";  // no file cdlab writes
        std::ofstream(out / usersTemp) << "the user's";
        REQUIRE(run({"render", (root / "big.json").string(), "--out", out.string(), "--force"}, root).status == 0);
        CHECK_FALSE(fs::exists(out / dead));
        CHECK(fs::exists(out / live));
        CHECK(fs::exists(out / "notes.tmp.12.x"));
        CHECK(fs::exists(out / usersTemp));
        fs::remove_all(root);
    }

    TEST_CASE("stdout on a full disk is exit 2") {
        // Reproducer: cdlab check < lines > /dev/full; cdlab render --template gjk > /dev/full;
        // cdlab golden > /dev/full; cdlab demos > /dev/full -> exit 0, everything lost.
        const fs::path root = tempDir("full_disk");
        writeScene(root / "golden" / "voronoi_triangle" / "a.json");
        REQUIRE(run({"golden", "--golden-dir", (root / "golden").string(), "--update", "all", "--report",
                     (root / "rep").string()},
                    root)
                    .status == 0);
        for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
                 {"check"},
                 {"render", "--template", "gjk"},
                 {"golden", "--golden-dir", (root / "golden").string(), "--report", (root / "rep").string()},
                 {"demos"}}) {
            const Result r = runToFullDisk(args, root);
            CHECK_MESSAGE(r.status == 2, args[0]);
            CHECK_MESSAGE(contains(r.err, "cdlab: cannot write to standard output: No space left on device"), r.err);
        }
        fs::remove_all(root);
    }

    TEST_CASE("a run killed between its renames and its manifest leaves a folder the next run takes") {
        // Reproducer: cdlab render gjk/box_box.json --out o1; rm o1/manifest.json (what a kill between
        // the renames and the manifest left); cdlab render ... --out o1 -> "refusing to overwrite
        // o1/trace.json". The provisional manifest, written before the renames, lists every file.
        const fs::path root = tempDir("killed_manifest");
        writeScene(root / "scene.json", true);
        const fs::path out = root / "out";
        const std::vector<std::string> args = {"render", (root / "scene.json").string(), "--out", out.string()};
        REQUIRE(run(args, root).status == 0);
        FigureManifest m = readFigureManifest(out / "manifest.json");
        FigureManifest provisional{"", m.title, m.caption, {}, m.files};
        cdlab::render::writeFileAtomic((out / "manifest.json").string(), figureManifestText(provisional));
        const Result r = run(args, root);
        CHECK_MESSAGE(r.status == 0, r.err);
        CHECK(contains(r.err, "1 rendered"));  // no cache key: drawn again, not taken as finished
        CHECK_FALSE(readFigureManifest(out / "manifest.json").key.empty());
        fs::remove_all(root);
    }

    TEST_CASE("render --out DIR takes a file whose name is no folder name") {
        // Reproducer: cdlab render "é scene.json" --out DIR -> refused for its name, though --out
        // names the folder.
        const fs::path root = tempDir("odd_name");
        writeScene(root / "\xc3\xa9 scene.json");
        Result r = run({"render", (root / "\xc3\xa9 scene.json").string(), "--out", (root / "o").string()}, root);
        CHECK_MESSAGE(r.status == 0, r.err);
        CHECK(fs::exists(root / "o" / "plane.png"));
        // With two files each one's name is its folder's: refused, with the way out named.
        writeScene(root / "plain.json");
        r = run({"render", (root / "\xc3\xa9 scene.json").string(), (root / "plain.json").string(), "--out",
                 (root / "o2").string()},
                root);
        CHECK(r.status == 2);
        CHECK(contains(r.err, "cannot name an output folder: give one with --out DIR"));
        fs::remove_all(root);
    }

    TEST_CASE("a scene's frames are bounded together, whatever its demo declared") {
        // Reproducer: a 64-query voronoi scene at 4096² with steps took 0.93 GB at 1024², 1.87 GB at
        // 2048² and ended in bad_alloc at 4096²; a demo that declares fewer frames than it draws is
        // stopped by the budget every readPixels() counts against.
        using cdlab::render::PixelBudget;
        CHECK_NOTHROW(PixelBudget::spend(1e300));  // no budget in force: nothing counted
        {
            PixelBudget outer(1000);
            CHECK_NOTHROW(PixelBudget::spend(600));
            {
                PixelBudget inner(100);
                CHECK_THROWS_AS(PixelBudget::spend(101), cdlab::render::ImageError);
                CHECK_NOTHROW(PixelBudget::spend(100));
            }
            CHECK_NOTHROW(PixelBudget::spend(400));  // the outer one's 1000, the inner spending not counted
            CHECK_THROWS_WITH_AS(PixelBudget::spend(1), doctest::Contains("the limit for one scene"),
                                 cdlab::render::ImageError);
        }
        CHECK_NOTHROW(PixelBudget::spend(1e300));
        // Every frame read back counts its rendered pixels, supersampling and --scale included: a
        // vclip scene of 37 frames of 2048 x 1536 at --scale 2 drew 466 M pixels (3.3 GB) before.
        std::unique_ptr<cdlab::render::GlContext> gl = createContext(false);
        cdlab::render::CanvasOptions options;
        options.width = 64, options.height = 32, options.supersample = 2, options.scale = 2;
        cdlab::render::Canvas canvas(*gl, options, cdlab::render::Camera::twoD(0, 0, 1));
        PixelBudget budget(2 * (64 * 4) * (32 * 4));
        CHECK_NOTHROW(canvas.readPixels());
        CHECK_NOTHROW(canvas.readPixels());
        CHECK_THROWS_AS(canvas.readPixels(), cdlab::render::ImageError);
    }

    TEST_CASE("a contact sheet stays within the image limits") {
        // Reproducer: a 30 KB caption made a 1008 x 18678 contact sheet, then a GL error blaming
        // the supersampling factor; 40 step frames of 64 x 4096 made cells 4096 tall. Cells are now
        // at most 3 x 384 layout pixels tall, and a sheet past 4096 per side is one error.
        const fs::path root = tempDir("tall_sheet");
        std::ofstream scene(root / "tall.json");
        scene << R"({"demo": "voronoi_triangle", "image": {"width": 64, "height": 4096}, "views": ["plane"],
          "triangle": [[0, 0, 0], [2, 0, 0], [0.5, 1.5, 0]], "steps": true, "queries": [)";
        for (int i = 0; i < 40; ++i) scene << (i ? ", " : "") << "[" << 0.1 * i << ", " << 0.05 * i << ", 0.2]";
        scene << "]}";
        scene.close();
        const Result r = run({"render", (root / "tall.json").string(), "--out", (root / "o").string()}, root);
        CHECK(r.status == 2);
        CHECK_MESSAGE(contains(r.err, "tall.json: the contact sheet of 40 frames would be 208 x 7219 pixels, above the "
                                      "limit of 4096 per side"),
                      r.err);
        CHECK_FALSE(contains(r.err, "OpenGL"));
        CHECK_FALSE(fs::exists(root / "o" / "contact_sheet.png"));
        fs::remove_all(root);
    }

    TEST_CASE("control characters from files are escaped in every line printed") {
        // Reproducer: a scene key "\u001b[8m" (or a file name with a newline) printed raw: a
        // terminal hid the rest of the line; a newline forged a line of its own.
        CHECK(printable("a\nb\x1b[8m\t\r\x7f") == "a\\nb\\x1b[8m\\t\\r\\x7f");
        CHECK(printable("\xc3\xa9t\xc3\xa9 \xe2\x88\x92") == "\xc3\xa9t\xc3\xa9 \xe2\x88\x92");  // UTF-8 kept
        CHECK(printable("\xc2\x9b" "31m") == "\\u009b31m");                        // C1 CSI
        CHECK(printable("\xff\xc3") == "\\xff\\xc3");                              // not UTF-8
        CHECK(printable("\xed\xa0\x80") == "\\xed\\xa0\\x80");                     // a surrogate
        const fs::path root = tempDir("escapes");
        std::ofstream(root / "line\nbreak.json") << R"({"demo": "voronoi_triangle", "triangle": [[0, 0, 0], [2, 0, 0],
          [0.5, 1.5, 0]], "queries": [[1, 1, 1]], "\u001b[8mhidden": 1})";
        const Result r = run({"render", (root / "line\nbreak.json").string(), "--out", (root / "o").string()}, root);
        CHECK(r.status == 2);
        CHECK(r.err.find('\x1b') == std::string::npos);
        CHECK(contains(r.err, "line\\nbreak.json"));
        CHECK(contains(r.err, "\\x1b[8mhidden"));
        fs::remove_all(root);
    }
}
