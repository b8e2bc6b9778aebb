#include "demos/app/cli.h"

#include <cstring>
#include <filesystem>
#include <iostream>
#include <vector>

#include "demos/bench/bench.h"
#include "demos/catalog/catalog.h"
#include "demos/harness/scene_runner.h"
#include "demos/query/query.h"
#include "demos/stress/stress.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace cdlab::demos {

namespace {

constexpr const char* kUsage =
    "usage: cdlab <command> [options]\n"
    "  figures   render every demo scene into out/figures/<demo>/<scene>/\n"
    "            [--scene PATTERN] [--list] [--scale N] [--steps] [--out DIR] [--no-render] [--verbose]\n"
    "            [--force] (re-render unchanged scenes) [--profile] (time per scene and stage)\n"
    "  golden    compare every scene with its goldens (what ctest runs)\n"
    "            [--scene PATTERN] [--report DIR] [--update failing|all] [--verbose]\n"
    "            (CDLAB_UPDATE_GOLDEN=1 or =all also updates)\n"
    "  query     JSON Lines queries on stdin, one JSON answer per line on stdout (see README)\n"
    "  bench     time per query against error; BVH and broad phase [--quick] [--only queries,vclip,bvh,broadphase]\n"
    "  stress    numerical-stability families against independent oracles [--seconds N] (see README)\n"
    "  demos     list the demos\n"
    "exit status: 0 ok, 1 test/comparison failure or failed queries, 2 usage or input error,\n"
    "             or an output that cannot be written\n";

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

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
        std::cerr << program << ": " << e.what() << "\n" << kUsage;
        return 2;
    } catch (const InputError& e) {
        std::cerr << e.what() << "\n";
        return 2;
    } catch (const render::GlError& e) {
        std::cerr << program << ": OpenGL: " << e.what() << "\n";
        return 2;
    } catch (const render::ImageError& e) {
        std::cerr << program << ": " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << program << ": " << e.what() << "\n";
        return 2;
    }
}

}  // namespace

int cdlabMain(int argc, char** argv) {
    return guarded("cdlab", [&]() -> int {
        if (argc < 2) throw UsageError("missing command");
        std::string cmd = argv[1];
        if (cmd == "-h" || cmd == "--help" || cmd == "help") {
            std::cout << kUsage;
            return 0;
        }
        if (cmd == "figures") return runFigures(parseRunnerOptions(argc, argv, 2, nullptr));
        if (cmd == "golden") {
            RunnerOptions o = parseRunnerOptions(argc, argv, 2, nullptr);
            if (o.update.empty()) {
                const char* env = std::getenv("CDLAB_UPDATE_GOLDEN");
                if (env && *env && std::strcmp(env, "0") != 0)
                    o.update = std::strcmp(env, "all") == 0 ? "all" : "failing";
            }
            return runGolden(o);
        }
        if (cmd == "query") {
            if (argc > 2) throw UsageError("query takes no arguments: it reads JSON Lines on stdin");
            return runQueries(std::cin, std::cout);
        }
        if (cmd == "bench") return runBench(argc - 1, argv + 1);
        if (cmd == "stress") return runStress(argc - 1, argv + 1);
        if (cmd == "demos") {
            for (const Demo* d : allDemos()) std::cout << d->name() << "\t" << d->description() << "\n";
            return 0;
        }
        throw UsageError("unknown command '" + cmd + "'");
    });
}

int demoMain(const std::string& demo, int argc, char** argv) {
    std::string program = "demo_" + demo;
    return guarded(program.c_str(), [&]() -> int {
        std::vector<std::string> files;
        RunnerOptions o = parseRunnerOptions(argc, argv, 1, &files);
        o.demo = demo;
        if (files.empty()) return runFigures(o);
        return renderSceneFiles(files, o);
    });
}

}  // namespace cdlab::demos
