// Nothing half-written: `cdlab figures` is killed (SIGKILL, no chance to clean up) at several
// moments of a run; every output file left behind is then either the complete previous version
// or a complete new one — each PNG decodes at its size, each JSON parses. Temp files of the
// killed run may remain (they have their own names); no target file is ever truncated.
#include <doctest/doctest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "app/cli/cli.h"
#include "app/tools/tool_commands.h"
#include "app/scene/json_reader.h"
#include "render/image.h"
#include "tests/app/harness/temp_files.h"

using namespace cdlab::demos;
namespace fs = std::filesystem;

namespace {


pid_t startFigures(const fs::path& out) {
    const pid_t pid = fork();
    if (pid == 0) {
        std::string o = out.string();
        std::vector<std::string> args = {"cdlab",   "figures", "--scene", "voronoi_triangle/regions",
                                         "--force", "--out",   o};
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        // No output from the child: the parent's doctest report stays readable.
        if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr)) _exit(5);
        _exit(cdlabMain(int(argv.size()), argv.data(), toolCommands()));
    }
    return pid;
}

// Every target file under `out`: PNG -> its size, JSON/HTML -> 0. Fails the test on a file that
// does not decode.
std::map<std::string, std::pair<int, int>> checkOutputs(const fs::path& out) {
    std::map<std::string, std::pair<int, int>> files;
    for (const auto& e : fs::recursive_directory_iterator(out)) {
        if (!e.is_regular_file() || cdlab::test::isTempFile(e.path())) continue;
        const std::string path = e.path().string();
        const std::string ext = e.path().extension().string();
        if (ext == ".png") {
            cdlab::render::Image img;
            CHECK_NOTHROW(img = cdlab::render::readPng(path));
            files[path] = {img.width, img.height};
        } else if (ext == ".json") {
            CHECK_NOTHROW(readJsonFile(path));
            files[path] = {0, 0};
        } else {
            CHECK(e.file_size() > 0);
            files[path] = {0, 0};
        }
    }
    return files;
}

}  // namespace

TEST_CASE("killing a figures run never leaves a half-written file") {
    const fs::path out = fs::temp_directory_path() / ("cdlab_kill_test_" + std::to_string(getpid()));
    fs::remove_all(out);

    // A complete run first: the "previous version" of every file.
    const auto t0 = std::chrono::steady_clock::now();
    pid_t pid = startFigures(out);
    REQUIRE(pid > 0);
    int status = 0;
    waitpid(pid, &status, 0);
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) == 0);
    double runSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto before = checkOutputs(out);
    REQUIRE(before.size() > 5);

    // Kill runs at spread-out moments of a run (20% .. 80% of its length). The first run's length
    // is only an estimate on a shared machine (it may have run under a load that later runs do not
    // see): a run that finished before its kill halves the estimate and is tried again.
    int killedMidRun = 0, attempts = 0;
    for (int i = 0; killedMidRun < 4 && attempts < 12; ++attempts) {
        pid = startFigures(out);
        REQUIRE(pid > 0);
        std::this_thread::sleep_for(std::chrono::duration<double>(runSeconds * (0.2 + 0.2 * i)));
        kill(pid, SIGKILL);  // a run that already ended (a zombie until reaped) ignores it
        waitpid(pid, &status, 0);
        if (WIFSIGNALED(status)) {
            ++killedMidRun;
            i = (i + 1) % 4;
        } else {
            runSeconds *= 0.5;
        }
        const auto after = checkOutputs(out);
        CHECK(after == before);  // same files, each complete and of the same size
    }
    CHECK(killedMidRun >= 2);
    fs::remove_all(out);
}
