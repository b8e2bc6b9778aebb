#include "app/cli/cli.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/usage_text.h"  // generated from app/cli/usage.txt
#include "app/catalog/catalog.h"
#include "app/harness/scene_runner.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

namespace {

const char* const kUsage = kUsageText;

// The usage line and one command's block of the usage text (its line and the indented lines under
// it), as ./cdlab prints it for `./cdlab <cmd> --help`; empty when the text has no such command.
std::string usageOf(const std::string& cmd) {
    std::istringstream in(kUsageText);
    std::string line, out;
    bool on = false;
    std::getline(in, line);  // the general usage line
    while (std::getline(in, line)) {
        if (line.rfind("  ", 0) == 0 && line.size() > 2 && line[2] != ' ')
            on = line.compare(2, cmd.size() + 1, cmd + " ") == 0;
        else if (!line.empty() && line[0] != ' ') on = false;
        if (on) out += line + "\n";
    }
    return out.empty() ? out : "usage: cdlab " + cmd + " [options]\n" + out;
}

bool wantsHelp(int argc, char** argv, int first) {
    for (int i = first; i < argc; ++i)
        if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return true;
    return false;
}



// Parses runner options from argv[first..]; positional arguments are collected into `files`.
RunnerOptions parseRunnerOptions(int argc, char** argv, int first, std::vector<std::string>* files) {
    RunnerOptions o;
    auto value = [&](int& i) -> std::string {
        if (i + 1 >= argc) throw UsageError(std::string("option ") + argv[i] + " needs a value");
        return argv[++i];
    };
    for (int i = first; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--scene") o.pattern = value(i);
        else if (a == "--list") o.list = true;
        else if (a == "--out") o.outDir = value(i);
        else if (a == "--report") o.reportDir = value(i);
        else if (a == "--golden-dir") o.goldenDir = value(i);
        else if (a == "--steps") o.steps = true;
        else if (a == "--verbose" || a == "-v") o.verbose = true;
        else if (a == "--no-render") o.noRender = true;
        else if (a == "--force") o.force = true;
        else if (a == "--profile") o.profile = true;
        else if (a == "--frame") {  // render: NAME or a glob, several separated by commas
            std::string v = value(i), item;
            std::istringstream list(v);
            while (std::getline(list, item, ','))
                if (!item.empty()) o.frames.push_back(item);
            if (o.frames.empty()) throw UsageError("--frame needs a frame name (or a glob such as 'step_0*')");
        }
        else if (a == "--update") {
            o.update = value(i);
            if (o.update != "failing" && o.update != "all") throw UsageError("--update takes 'failing' or 'all'");
        } else if (a == "--scale") {
            std::string v = value(i);
            if (v != "1" && v != "2" && v != "3" && v != "4") throw UsageError("--scale takes 1, 2, 3 or 4");
            o.scale = std::stoi(v);
        } else if (!a.empty() && a[0] == '-') throw UsageError("unknown option " + a);
        else if (files) files->push_back(a);
        else throw UsageError("unexpected argument " + a);
    }
    return o;
}

template <class F>
int guarded(const char* program, F&& body) {
    try {
        return body();
    } catch (const UsageError& e) {
        std::cerr << program << ": " << printable(e.what()) << "\n" << kUsage;
        return 2;
    } catch (const InputError& e) {
        std::cerr << printable(e.what()) << "\n";
        return 2;
    } catch (const render::GlError& e) {
        std::cerr << program << ": OpenGL: " << printable(e.what()) << "\n";
        return 2;
    } catch (const render::ImageError& e) {
        std::cerr << program << ": " << printable(e.what()) << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << program << ": " << printable(e.what()) << "\n";
        return 2;
    }
}

// `cdlab render FILE.json... [--out DIR] [--frame NAME] [--scale N]` or `--template DEMO`.
int runRender(int argc, char** argv) {
    for (int i = 2; i < argc; ++i)
        if (std::strcmp(argv[i], "--template") == 0) {
            if (i + 1 >= argc) throw UsageError("--template needs a demo name (cdlab demos lists them)");
            if (argc != 4) throw UsageError("--template DEMO takes no other argument");
            std::cout << sceneTemplate(argv[i + 1], RunnerOptions{});
            return 0;
        }
    std::vector<std::string> files;
    bool explicitOut = false;
    for (int i = 2; i < argc; ++i) explicitOut = explicitOut || std::strcmp(argv[i], "--out") == 0;
    RunnerOptions o = parseRunnerOptions(argc, argv, 2, &files);
    if (files.empty()) throw UsageError("render needs a scene file (or --template DEMO for a starter)");
    if (!o.pattern.empty() || o.list || !o.update.empty() || !o.reportDir.empty())
        throw UsageError("render takes scene files, --out, --frame, --scale, --steps, --force, --verbose, --profile");
    if (!explicitOut) o.outDir = "out/render";
    o.perFileOutput = true;
    o.outIsFolder = explicitOut && files.size() == 1;
    return renderSceneFiles(files, o);
}

// What a command printed on stdout must have reached it: a full disk or a closed pipe is exit 2,
// not success (hostile_harness_test "stdout on a full disk is exit 2").
int withStdoutChecked(const char* program, int status) {
    errno = 0;
    std::cout.flush();
    const bool flushFailed = std::fflush(stdout) != 0;
    int err = errno;
    if (!flushFailed && std::cout && !std::ferror(stdout)) return status;
    if (status == 2) return status;  // the command has said what went wrong (query: its own line)
    // A write failed earlier and its errno is gone: one more byte finds the reason (ENOSPC, EPIPE).
    if (!err && ::write(STDOUT_FILENO, "\n", 1) < 0) err = errno;
    std::cerr << program << ": cannot write to standard output" << (err ? std::string(": ") + std::strerror(err) : "")
              << "\n";
    return 2;
}

int cdlabCommand(int argc, char** argv, const ToolCommands& tools);

}  // namespace

int cdlabMain(int argc, char** argv, const ToolCommands& tools) {
    // Commands that write files remove their temp files when interrupted (render/image.h).
    render::removeTempFilesOnSignal();
    return withStdoutChecked("cdlab", cdlabCommand(argc, argv, tools));
}

namespace {

int cdlabCommand(int argc, char** argv, const ToolCommands& tools) {
    return guarded("cdlab", [&]() -> int {
        if (argc < 2) throw UsageError("missing command");
        std::string cmd = argv[1];
        if (cmd == "-h" || cmd == "--help" || cmd == "help") {
            std::cout << kUsage;
            return 0;
        }
        if (wantsHelp(argc, argv, 2)) {  // `cdlab <cmd> --help`: that command's usage, nothing run
            const std::string usage = usageOf(cmd);
            std::cout << (usage.empty() ? std::string(kUsage) : usage);
            return 0;
        }
        if (cmd == "figures") return runFigures(parseRunnerOptions(argc, argv, 2, nullptr));
        if (cmd == "render") return runRender(argc, argv);
        if (cmd == "golden") {
            RunnerOptions o = parseRunnerOptions(argc, argv, 2, nullptr);
            if (o.update.empty()) {
                const char* env = std::getenv("CDLAB_UPDATE_GOLDEN");
                if (env && *env && std::strcmp(env, "0") != 0)
                    o.update = std::strcmp(env, "all") == 0 ? "all" : "failing";
            }
            return runGolden(o);
        }
        if (const auto tool = tools.find(cmd); tool != tools.end()) return tool->second(argc, argv);
        if (cmd == "query" || cmd == "check" || cmd == "bench" || cmd == "stress")  // the tools this program lacks
            throw UsageError("'" + printable(cmd) + "' is not in this program, which renders figures: run ./cdlab " +
                             printable(cmd) + " or build/bin/cdlab " + printable(cmd));
        if (cmd == "demos") {
            for (const Demo* d : allDemos()) std::cout << d->name() << "\t" << d->description() << "\n";
            return 0;
        }
        throw UsageError("unknown command '" + printable(cmd) + "'");
    });
}

}  // namespace

int demoMain(const std::string& demo, int argc, char** argv) {
    std::string program = "demo_" + demo;
    render::removeTempFilesOnSignal();
    return withStdoutChecked(program.c_str(), guarded(program.c_str(), [&]() -> int {
        if (wantsHelp(argc, argv, 1)) {
            std::cout << "usage: " << program << " [scene.json ...] [options]\n"
                      << "  renders the " << demo << " demo's golden scenes (or the scene files given) into out/figures/\n"
                      << "  options (as for figures):\n";
            std::istringstream figures(usageOf("figures"));
            std::string line;
            while (std::getline(figures, line))
                if (line.rfind("            ", 0) == 0) std::cout << line << "\n";
            return 0;
        }
        std::vector<std::string> files;
        RunnerOptions o = parseRunnerOptions(argc, argv, 1, &files);
        o.demo = demo;
        if (files.empty()) return runFigures(o);
        return renderSceneFiles(files, o);
    }));
}

}  // namespace cdlab::demos
