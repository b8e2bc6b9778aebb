#include "app/tools/tool_commands.h"

#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

#include "app/bench/bench.h"
#include "app/check/check.h"
#include "app/query/query.h"
#include "app/stress/stress.h"

namespace cdlab::demos {

namespace {

// `cdlab check [--tolerance T] [--figures DIR]`: verdicts for the JSON Lines on stdin.
int checkCommand(int argc, char** argv) {
    CheckOptions co;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--tolerance" && i + 1 < argc) {
            char* end = nullptr;
            const char* text = argv[++i];
            co.tolerance = std::strtod(text, &end);
            // Finite and in (0, kMaxCheckTolerance]: "inf", "nan" and 1e300 are refused, never a pass-all.
            if (!end || end == text || *end || !(co.tolerance > 0) || !(co.tolerance <= kMaxCheckTolerance)) {
                std::ostringstream most;
                most << kMaxCheckTolerance;
                throw UsageError("--tolerance takes a number above 0 and at most " + most.str() +
                                 " (relative to the shapes' size), got " + std::string(text));
            }
        } else if (a == "--figures" && i + 1 < argc) {
            co.figuresDir = argv[++i];
        } else throw UsageError("check: unknown argument " + a + " (it reads JSON Lines on stdin)");
    }
    return runCheck(std::cin, std::cout, co);
}

}  // namespace

ToolCommands toolCommands() {
    return {
        {"query",
         [](int argc, char**) {
             if (argc > 2) throw UsageError("query takes no arguments: it reads JSON Lines on stdin");
             return runQueries(std::cin, std::cout);
         }},
        {"check", checkCommand},
        {"bench", [](int argc, char** argv) { return runBench(argc - 1, argv + 1); }},
        {"stress", [](int argc, char** argv) { return runStress(argc - 1, argv + 1); }},
    };
}

}  // namespace cdlab::demos
