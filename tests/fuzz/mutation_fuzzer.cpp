#include "tests/fuzz/mutation_fuzzer.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cdlab::fuzz {

namespace {

// Values at the edges of what the parsers and the geometry must handle.
const std::vector<std::string> kNumbers = {"0",        "-0",     "-0.0",
                                           "1",        "-1",     "0.5",
                                           "1e308",    "-1e308", "1e-308",
                                           "4.9e-324", "1e400",  "-1e400",
                                           "1e-12",    "1e12",   "NaN",
                                           "Infinity", "2e9",    "9007199254740993",
                                           "1e+",      "0.1e-3", "123456789012345678901234567890"};
// JSON grammar pieces and the format's keys, so mutations stay near valid inputs.
const std::vector<std::string> kTokens = {"{",
                                          "}",
                                          "[",
                                          "]",
                                          ",",
                                          ":",
                                          "\"",
                                          "null",
                                          "true",
                                          "false",
                                          "[]",
                                          "{}",
                                          "[0,0,0]",
                                          "[1,0,0,0]",
                                          "[0,0,0,0]",
                                          "\"op\":",
                                          "\"a\":",
                                          "\"b\":",
                                          "\"id\":",
                                          "\"method\":",
                                          "\"trace\":true",
                                          "\"radius\":",
                                          "\"vertices\":",
                                          "\"rotation\":",
                                          "\"steps\":true",
                                          "\"layers\":[]",
                                          "\"demo\":",
                                          "\\u0000",
                                          "\\ud800",
                                          "\xff",
                                          "\xc3\x28",
                                          "\n",
                                          "{\"point\":[0,0,0]}",
                                          "{\"sphere\":{\"center\":[0,0,0],\"radius\":0}}"};

}  // namespace

MutationFuzzer::MutationFuzzer(std::vector<std::string> seeds, std::uint64_t rngSeed, std::size_t maxLength)
    : seeds_(std::move(seeds)), rng_(rngSeed), maxLength_(maxLength) {
    if (seeds_.empty()) seeds_.push_back("{}");
}

std::size_t MutationFuzzer::position(const std::string& s) {
    return std::uniform_int_distribution<std::size_t>(0, s.size())(rng_);
}

void MutationFuzzer::mutate(std::string& s) {
    auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); };
    switch (pick(7)) {
        case 0:  // flip one byte to a random value
            if (!s.empty()) s[pick(s.size())] = char(pick(256));
            break;
        case 1:  // insert a grammar token
            s.insert(position(s), kTokens[pick(kTokens.size())]);
            break;
        case 2: {  // erase a range
            if (s.empty()) break;
            const std::size_t at = pick(s.size());
            s.erase(at, 1 + pick(std::min<std::size_t>(16, s.size() - at)));
            break;
        }
        case 3: {  // duplicate a range (nesting, repeated keys)
            if (s.empty()) break;
            const std::size_t at = pick(s.size());
            const std::string piece = s.substr(at, 1 + pick(std::min<std::size_t>(64, s.size() - at)));
            s.insert(position(s), piece);
            break;
        }
        case 4: {  // splice with another seed
            const std::string& other = seeds_[pick(seeds_.size())];
            s = s.substr(0, position(s)) + other.substr(std::min(other.size(), std::size_t(pick(other.size() + 1))));
            break;
        }
        default: {  // replace a number with a boundary value
            std::vector<std::size_t> starts;
            for (std::size_t i = 0; i < s.size(); ++i)
                if ((std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '-') &&
                    (i == 0 || !std::isalnum(static_cast<unsigned char>(s[i - 1]))))
                    starts.push_back(i);
            if (starts.empty()) break;
            const std::size_t at = starts[pick(starts.size())];
            std::size_t end = at + 1;
            while (end < s.size() && (std::isalnum(static_cast<unsigned char>(s[end])) || s[end] == '.' ||
                                      s[end] == '-' || s[end] == '+'))
                ++end;
            s.replace(at, end - at, kNumbers[pick(kNumbers.size())]);
            break;
        }
    }
    if (s.size() > maxLength_) s.resize(maxLength_);
}

std::string MutationFuzzer::next() {
    std::string s = seeds_[std::uniform_int_distribution<std::size_t>(0, seeds_.size() - 1)(rng_)];
    const int count = 1 + int(std::uniform_int_distribution<int>(0, 3)(rng_));
    for (int i = 0; i < count; ++i) mutate(s);
    return s;
}

std::size_t MutationFuzzer::run(const std::function<void(const std::string&)>& target, std::size_t maxExecutions,
                                double seconds) {
    const auto start = std::chrono::steady_clock::now();
    const char* last = std::getenv("CDLAB_FUZZ_LAST");
    std::size_t executions = 0;
    const auto execute = [&](const std::string& input) {
        if (last) std::ofstream(last, std::ios::binary | std::ios::trunc) << input;  // a crash leaves its input
        target(input);
        ++executions;
    };
    for (const std::string& s : seeds_) execute(s);
    while (executions < maxExecutions &&
           (seconds <= 0 || std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds))
        execute(next());
    return executions;
}

std::vector<std::string> readSceneSeeds(const std::string& goldenFolder, const std::string& extraFolder) {
    const auto jsonFiles = [](const std::filesystem::path& folder) {
        std::vector<std::string> paths;
        for (const auto& entry : std::filesystem::directory_iterator(folder))
            if (entry.is_regular_file() && entry.path().extension() == ".json") paths.push_back(entry.path().string());
        std::sort(paths.begin(), paths.end());  // deterministic order
        return paths;
    };
    std::vector<std::string> paths;
    for (const auto& demo : std::filesystem::directory_iterator(goldenFolder))
        if (demo.is_directory())
            for (const std::string& p : jsonFiles(demo.path())) paths.push_back(p);
    std::sort(paths.begin(), paths.end());
    if (!extraFolder.empty())
        for (const std::string& p : jsonFiles(extraFolder)) paths.push_back(p);
    std::vector<std::string> out;
    for (const std::string& p : paths) {
        std::ifstream in(p, std::ios::binary);
        std::ostringstream ss;
        ss << in.rdbuf();
        out.push_back(ss.str());
    }
    return out;
}

std::vector<std::string> readSeedLines(const std::string& file) {
    std::ifstream in(file);
    std::vector<std::string> out;
    std::string line;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) out.push_back(line);
    return out;
}

}  // namespace cdlab::fuzz
