// A small deterministic mutation fuzzer for the bounded fuzz run inside ctest, where libFuzzer
// (clang only) is not available. It mutates a seed corpus with libFuzzer's cheap byte mutations
// (flip, insert, erase, duplicate, splice; Serebryany, "Continuous fuzzing with libFuzzer and
// AddressSanitizer", SecDev 2016) plus JSON-aware ones: numbers replaced by boundary values and
// grammar tokens inserted. Deterministic for a given seed, so a failing run replays exactly.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace cdlab::fuzz {

class MutationFuzzer {
public:
    MutationFuzzer(std::vector<std::string> seeds, std::uint64_t rngSeed, std::size_t maxLength = 4096);

    /// The next input: a seed with 1..4 mutations applied.
    std::string next();

    /// Runs `target` on every seed verbatim, then on mutated inputs until `maxExecutions` inputs ran
    /// (or, when `seconds` > 0, that much time passed first). Returns the number of executions.
    /// The budget is a count, not a time, so a run tests the same inputs on any machine and in any
    /// build (a sanitizer build is ~10x slower). With CDLAB_FUZZ_LAST=path in the environment each
    /// input is written to that file before it runs: a crash leaves its reproducer there.
    std::size_t run(const std::function<void(const std::string&)>& target, std::size_t maxExecutions,
                    double seconds = 0);

private:
    void mutate(std::string& s);
    std::size_t position(const std::string& s);  // in [0, s.size()]

    std::vector<std::string> seeds_;
    std::mt19937_64 rng_;
    std::size_t maxLength_;
};

/// The scene seed corpus, read whole: every golden/<demo>/<scene>.json, then every *.json in
/// `extraFolder` (tests/fuzz/seeds/scenes: the reproducers of bugs found so far), each sorted.
std::vector<std::string> readSceneSeeds(const std::string& goldenFolder, const std::string& extraFolder = "");
/// Non-blank lines of a file (a JSON Lines seed corpus).
std::vector<std::string> readSeedLines(const std::string& file);

}  // namespace cdlab::fuzz
