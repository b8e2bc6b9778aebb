// The bounded fuzz run of ctest: each entry point gets its seed corpus verbatim and then a few
// seconds of deterministic mutations (tests/fuzz/mutation_fuzzer.h). A broken contract aborts the
// test with the offending input on stderr. Longer runs with coverage guidance: ./cdlab fuzz.
#include <doctest/doctest.h>

#include <cstdlib>

#include "tests/fuzz/fuzz_targets.h"
#include "tests/fuzz/mutation_fuzzer.h"

using namespace cdlab::fuzz;

namespace {

// The default budget is a number of inputs, the same on every machine and in every build (the
// sanitizer build is ~10x slower: a time budget made it test fewer inputs, or none past the seeds).
// CDLAB_FUZZ_SECONDS=N instead runs each target for N seconds (e.g. overnight).
struct Budget {
    std::size_t executions;
    double seconds;
};
Budget budget(std::size_t defaultExecutions) {
    const char* s = std::getenv("CDLAB_FUZZ_SECONDS");
    if (s && std::atof(s) > 0) return {std::size_t(-1), std::atof(s)};
    return {defaultExecutions, 0.0};
}

const std::uint8_t* bytes(const std::string& s) { return reinterpret_cast<const std::uint8_t*>(s.data()); }

}  // namespace

TEST_SUITE("fuzz") {
    TEST_CASE("query answers keep the contract on mutated queries") {
        std::vector<std::string> seeds = readSeedLines(CDLAB_SOURCE_DIR "/tests/fuzz/seeds/queries.jsonl");
        REQUIRE(seeds.size() >= 20);
        MutationFuzzer fuzzer(seeds, 0xC0FFEE);
        const Budget b = budget(100'000);
        const std::size_t runs =
            fuzzer.run([](const std::string& s) { fuzzQuery(bytes(s), s.size()); }, b.executions, b.seconds);
        MESSAGE("query: " << runs << " executions");
        CHECK(runs > seeds.size());
    }

    TEST_CASE("scene loading keeps the contract on mutated scenes") {
        std::vector<std::string> seeds =
            readSceneSeeds(CDLAB_SOURCE_DIR "/golden", CDLAB_SOURCE_DIR "/tests/fuzz/seeds/scenes");
        REQUIRE(seeds.size() >= 10);
        MutationFuzzer fuzzer(seeds, 0xBADC0DE, 16384);
        const Budget b = budget(5'000);
        const std::size_t runs =
            fuzzer.run([](const std::string& s) { fuzzScene(bytes(s), s.size()); }, b.executions, b.seconds);
        MESSAGE("scene: " << runs << " executions");
        CHECK(runs > seeds.size());
    }

    TEST_CASE("drawing mutated scenes at a small size keeps the contract") {
        // The other targets never reach the drawing path; this one draws (96² pixels, one GL context).
        std::vector<std::string> seeds =
            readSceneSeeds(CDLAB_SOURCE_DIR "/golden", CDLAB_SOURCE_DIR "/tests/fuzz/seeds/scenes");
        MutationFuzzer fuzzer(seeds, 0xD2A3, 16384);
        const Budget b = budget(150);
        const std::size_t runs =
            fuzzer.run([](const std::string& s) { fuzzRender(bytes(s), s.size()); }, b.executions, b.seconds);
        MESSAGE("render: " << runs << " executions");
        CHECK(runs > seeds.size());
    }

    TEST_CASE("check verdicts keep the contract on mutated student files") {
        // The seeds: every hostile check line found so far (tests/fuzz/seeds/check.jsonl), then the
        // query corpus, whose lines check must judge too (and pass with cdlab's own answer).
        std::vector<std::string> seeds = readSeedLines(CDLAB_SOURCE_DIR "/tests/fuzz/seeds/check.jsonl");
        REQUIRE(seeds.size() >= 10);
        const std::vector<std::string> queries = readSeedLines(CDLAB_SOURCE_DIR "/tests/fuzz/seeds/queries.jsonl");
        seeds.insert(seeds.end(), queries.begin(), queries.end());
        MutationFuzzer fuzzer(seeds, 0xC4EC4, 16384);
        const Budget b = budget(20'000);
        const std::size_t runs =
            fuzzer.run([](const std::string& s) { fuzzCheck(bytes(s), s.size()); }, b.executions, b.seconds);
        MESSAGE("check: " << runs << " executions");
        CHECK(runs > seeds.size());
    }

    TEST_CASE("the answer contract rejects what it should") {
        CHECK(queryAnswerViolation(R"({"id":1,"intersect":false,"distance":2.5,"normal":[0,0,1]})") == "");
        CHECK(queryAnswerViolation(R"({"id":1,"error":"query: $.a: expected an object"})") == "");
        CHECK(queryAnswerViolation(R"({"id":1,"distance":null})") != "");       // NaN printed as null
        CHECK(queryAnswerViolation(R"({"id":1,"point_a":[0,null,0]})") != "");  // NaN in a vector
        CHECK(queryAnswerViolation(R"({"id":1,"distance":-1})") != "");
        CHECK(queryAnswerViolation(R"({"id":1,"normal":[0,0,2]})") != "");
        CHECK(queryAnswerViolation(R"({"id":1,"error":"internal error: boom"})") != "");
        CHECK(queryAnswerViolation(R"({"distance":1,"id":1})") != "");  // id must come first
        CHECK(queryAnswerViolation("{\"id\":1,") != "");
    }

    TEST_CASE("mutation is deterministic for a seed") {
        MutationFuzzer a({"{\"op\":\"distance\",\"a\":[1,2,3]}"}, 42), b({"{\"op\":\"distance\",\"a\":[1,2,3]}"}, 42);
        for (int i = 0; i < 100; ++i) CHECK(a.next() == b.next());
    }

}  // TEST_SUITE
