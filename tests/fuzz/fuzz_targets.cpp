#include "tests/fuzz/fuzz_targets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string_view>
#include <vector>

#include "app/catalog/catalog.h"
#include "app/check/check.h"
#include "app/query/query.h"
#include "render/gl_context.h"

namespace cdlab::fuzz {

using demos::Json;

void contractViolation(const std::string& what, const std::string& input) {
    std::fprintf(stderr, "fuzz contract violated: %s\ninput (%zu bytes): %.2000s\n", what.c_str(), input.size(),
                 input.c_str());
    std::abort();
}

namespace {

bool isBlank(std::string_view line) { return line.find_first_not_of(" \t\r") == std::string_view::npos; }

}  // namespace

std::string queryAnswerViolation(const std::string& line) {
    if (line.rfind("{\"id\":", 0) != 0) return "answer does not start with {\"id\": " + line;
    Json a;
    try {
        a = Json::parse(line);
    } catch (const Json::exception& e) {
        return std::string("answer is not JSON: ") + e.what() + ": " + line;
    }
    if (!a.is_object()) return "answer is not an object: " + line;
    if (a.contains("error")) {
        const std::string error = a["error"].is_string() ? a["error"].get<std::string>() : "";
        if (error.empty() || error.rfind("internal error", 0) == 0) return "not an input error: " + line;
        return "";
    }
    // NaN and Inf print as null: a success answer must hold finite numbers only.
    const auto finite = [](const Json& v) {
        if (v.is_null()) return false;
        if (v.is_array())
            for (const Json& x : v)
                if (x.is_null() ||
                    (x.is_array() && std::any_of(x.begin(), x.end(), [](const Json& y) { return y.is_null(); })))
                    return false;
        return true;
    };
    for (auto it = a.begin(); it != a.end(); ++it)
        if (it.key() != "id" && it.key() != "trace" && !finite(it.value()))
            return "non-finite value in '" + it.key() + "': " + line;
    for (const char* key : {"distance", "depth"})
        if (a.contains(key) && !(a[key].is_number() && a[key].get<double>() >= 0))
            return std::string(key) + " < 0: " + line;
    if (a.contains("normal") && a["normal"].is_array() && a["normal"].size() == 3) {
        double n2 = 0;
        for (const Json& c : a["normal"]) n2 += c.get<double>() * c.get<double>();
        if (std::abs(n2 - 1) > 1e-9) return "normal is not unit: " + line;
    }
    return "";
}

void fuzzQuery(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    std::istringstream in(input);
    std::ostringstream out;
    try {
        demos::runQueries(in, out);
    } catch (const std::exception& e) {
        contractViolation(std::string("runQueries threw: ") + e.what(), input);
    }
    // One answer line per non-blank input line, in order.
    std::size_t expected = 0;
    {
        std::istringstream lines(input);
        std::string line;
        while (std::getline(lines, line))
            if (!isBlank(line)) ++expected;
    }
    std::istringstream answers(out.str());
    std::string line;
    std::size_t count = 0;
    while (std::getline(answers, line)) {
        ++count;
        if (std::string v = queryAnswerViolation(line); !v.empty()) contractViolation(v, input);
    }
    if (count != expected)
        contractViolation(std::to_string(count) + " answers for " + std::to_string(expected) + " lines", input);
}

void fuzzCheck(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    std::istringstream in(input);
    std::ostringstream out;
    int status = 0;
    try {
        status = demos::runCheck(in, out, demos::CheckOptions{});
    } catch (const std::exception& e) {
        contractViolation(std::string("runCheck threw: ") + e.what(), input);
    }
    std::vector<std::size_t> numbers;  // of the non-blank input lines
    {
        std::istringstream lines(input);
        std::string line;
        for (std::size_t n = 1; std::getline(lines, line); ++n)
            if (!isBlank(line)) numbers.push_back(n);
    }
    const std::string text = out.str();
    for (const char c : text)
        if ((static_cast<unsigned char>(c) < 0x20 && c != '\n') || c == 0x7f)
            contractViolation("a control character in check's output", input);
    std::istringstream verdicts(text);
    std::string line;
    std::size_t count = 0, passed = 0, failed = 0;
    while (std::getline(verdicts, line)) {
        if (count == numbers.size()) {
            if (line != std::to_string(passed) + " passed, " + std::to_string(failed) + " failed")
                contractViolation("summary line is not the verdicts' count: " + line, input);
            if (status != (failed ? 1 : 0)) contractViolation("exit status " + std::to_string(status), input);
            ++count;
            continue;
        }
        if (count > numbers.size()) contractViolation("a line after the summary: " + line, input);
        const std::string head = "line " + std::to_string(numbers[count]);
        if (line.rfind(head, 0) != 0) contractViolation("verdict " + std::to_string(count) + " is not " + head + ": " + line, input);
        const bool pass = line.size() >= 6 && line.compare(line.size() - 6, 6, ": pass") == 0;
        const bool fail = line.find(": FAIL", head.size()) != std::string::npos;
        if (pass == fail) contractViolation("neither one pass nor one FAIL: " + line, input);
        (pass ? passed : failed) += 1;
        ++count;
    }
    if (count != numbers.size() + 1)
        contractViolation(std::to_string(count) + " output lines for " + std::to_string(numbers.size()) + " input lines",
                          input);
    // Self-consistency: cdlab's answer to a valid query, handed back, passes.
    std::istringstream lines(input);
    while (std::getline(lines, line)) {
        if (isBlank(line)) continue;
        std::string why;
        if (!demos::selfCheckPasses(line, &why)) contractViolation("cdlab's own answer fails check: " + why, input);
    }
}

namespace {

// The strict loader's contract: a scene, or an InputError that names the source (then nullptr);
// any other exception is a violation.
std::unique_ptr<demos::PreparedScene> loadFuzzScene(const std::string& input) {
    try {
        return demos::loadSceneText(input, "fuzz.json");
    } catch (const demos::InputError& e) {
        if (std::string_view(e.what()).rfind("fuzz.json: ", 0) != 0)
            contractViolation(std::string("input error does not name the source: ") + e.what(), input);
        return nullptr;
    } catch (const std::exception& e) {
        contractViolation(std::string("scene loading threw a non-input error: ") + e.what(), input);
    }
}

}  // namespace

void fuzzScene(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    std::unique_ptr<demos::PreparedScene> scene = loadFuzzScene(input);
    if (!scene) return;
    try {
        scene->run(demos::RunContext{});  // numeric only: no GL context, nothing drawn
    } catch (const demos::InputError&) {
        // Some checks need the computation (e.g. a degenerate hull); they are input errors too.
    } catch (const std::exception& e) {
        contractViolation(std::string("numeric scene run threw: ") + e.what(), input);
    }
}

namespace {

// One context for every input of a run (creating one costs 70 ms .. 1 s).
render::GlContext& fuzzContext() {
    static std::unique_ptr<render::GlContext> gl = render::GlContext::create();
    return *gl;
}

}  // namespace

void fuzzRender(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    // The strict loader first (its contract is fuzzScene's); only scenes it accepts are drawn.
    if (!loadFuzzScene(input)) return;
    // The same scene at a small size — the bound on the work of one input. Some demos have a fixed
    // or a minimum layout (sweep_and_prune 1024 x 768, vclip 800 x 600): the first size the demo
    // accepts is used.
    demos::Json json = demos::Json::parse(input);
    std::unique_ptr<demos::PreparedScene> scene;
    for (const auto& [w, h] :
         {std::pair{kFuzzImageSide, kFuzzImageSide}, std::pair{480, 360}, std::pair{800, 600}, std::pair{1024, 768}}) {
        json["image"] = {{"width", w}, {"height", h}, {"scale", 1}};
        try {
            scene = demos::prepareScene(json, "fuzz.json");
            break;
        } catch (const demos::InputError&) {}
    }
    if (!scene) return;  // refused at every size: an input error (the strict load above accepted it)
    demos::RunContext ctx;
    ctx.gl = &fuzzContext();
    try {
        const demos::DemoOutput out = scene->run(ctx);
        for (const demos::Frame& f : out.frames)
            if (f.image.width <= 0 || f.image.height <= 0 ||
                f.image.rgba.size() != std::size_t(f.image.width) * std::size_t(f.image.height) * 4)
                contractViolation("frame '" + f.name + "' is not a whole image", input);
    } catch (const demos::InputError& e) {
        if (std::string_view(e.what()).rfind("fuzz.json: ", 0) != 0)
            contractViolation(std::string("run-time input error does not name the source: ") + e.what(), input);
    } catch (const std::exception& e) {
        contractViolation(std::string("drawing the scene threw: ") + e.what(), input);
    }
}

}  // namespace cdlab::fuzz
