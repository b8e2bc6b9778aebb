// Size limits on every source file of the tree (docs/architecture.md, "Sizes"): a .h or .cpp under core/,
// render/, app/, demos/ or verification/ has at most 800 lines, and a function body at most 120
// lines (its opening brace's line to its closing brace's line, both counted; lambdas and nested
// blocks count toward the function around them).
//
// The scanner blanks comments, string literals (raw ones too), character literals and preprocessor
// lines, drops #else / #elif branches, then matches brackets: a '{' outside any function opens a
// function body when what stands before it is a parameter list ')' (after qualifiers, a trailing
// return type, noexcept(...), a constructor's member initializers or a requires clause); a class,
// namespace, enum or initializer '= {...}' is a scope, not a function.
#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace size_limits {

constexpr int kFileLines = 800;
constexpr int kFunctionLines = 120;

bool isWord(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool isSpace(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// Words before a '(' that make it no parameter list.
bool isControlWord(const std::string& w) {
    static const std::set<std::string> kControl = {"if",     "for",    "while",   "switch",   "catch",    "return",
                                                   "sizeof", "alignof", "decltype", "noexcept", "requires", "static_assert"};
    return kControl.count(w) > 0;
}

// The lines of a file: its newlines, plus one for a last line without a newline.
int lineCount(const std::string& src) {
    const int n = int(std::count(src.begin(), src.end(), '\n'));
    return n + (src.empty() || src.back() == '\n' ? 0 : 1);
}

// Blanks [a, b) of out, keeping its newlines so that line numbers stay.
void blank(std::string& out, long a, long b) {
    for (long k = a; k < std::min(b, long(out.size())); ++k)
        if (out[k] != '\n') out[k] = ' ';
}

// The directive's name on a line that starts (after blanks) with '#', or "".
std::string directive(const std::string& line) {
    std::size_t i = line.find_first_not_of(" \t\r");
    if (i == std::string::npos || line[i] != '#') return "";
    i = line.find_first_not_of(" \t", i + 1);
    if (i == std::string::npos) return "";
    std::size_t j = i;
    while (j < line.size() && isWord(line[j])) ++j;
    return line.substr(i, j - i);
}

// The end of a string or character literal that opens at i with quote q (one past its closing quote).
long literalEnd(const std::string& src, long i, char q) {
    const long n = long(src.size());
    long j = i + 1;
    while (j < n && src[j] != q) {
        if (src[j] == '\\')
            ++j;
        else if (src[j] == '\n')
            break;
        ++j;
    }
    return j + 1;
}

// The length of a raw string's prefix (R, LR, uR, UR, u8R) ending just before the quote at i, or 0.
long rawPrefix(const std::string& src, long i) {
    if (i < 1 || src[i - 1] != 'R') return 0;
    long len = 1;
    if (i >= 3 && src.compare(i - 3, 2, "u8") == 0)
        len = 3;
    else if (i >= 2 && (src[i - 2] == 'u' || src[i - 2] == 'U' || src[i - 2] == 'L'))
        len = 2;
    return i - len == 0 || !isWord(src[i - len - 1]) ? len : 0;
}

// The source with comments, literals and preprocessor lines blanked and #else / #elif branches dropped.
std::string clean(const std::string& src) {
    std::string out = src;
    const long n = long(src.size());
    bool atLineStart = true;
    for (long i = 0; i < n;) {
        const char c = src[i];
        if (c == '\n') {
            atLineStart = true;
            ++i;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\r') {
            ++i;
            continue;
        }
        if (atLineStart && c == '#') {  // a directive, with its continuation lines
            long j = i;
            while (j < n && !(src[j] == '\n' && src[j - 1] != '\\')) ++j;
            blank(out, i, j);
            i = j;
            continue;
        }
        atLineStart = false;
        if (src.compare(i, 2, "//") == 0) {
            const std::size_t j = src.find('\n', i);
            const long end = j == std::string::npos ? n : long(j);
            blank(out, i, end);
            i = end;
        } else if (src.compare(i, 2, "/*") == 0) {
            const std::size_t j = src.find("*/", i + 2);
            const long end = j == std::string::npos ? n : long(j) + 2;
            blank(out, i, end);
            i = end;
        } else if (c == '"' && rawPrefix(src, i) > 0) {
            const std::size_t p = src.find('(', i);
            long end = n;
            if (p != std::string::npos) {
                const std::string delim = src.substr(i + 1, p - i - 1);
                const std::size_t e = src.find(")" + delim + "\"", p);
                if (e != std::string::npos) end = long(e + delim.size() + 2);
            }
            blank(out, i, end);
            i = end;
        } else if (c == '"') {
            const long end = literalEnd(src, i, '"');
            blank(out, i, end);
            i = end;
        } else if (c == '\'') {
            long k = i - 1;  // a digit separator (1'000) is no literal
            while (k >= 0 && (isWord(src[k]) || src[k] == '\'' || src[k] == '.')) --k;
            if (k + 1 < i && isDigit(src[k + 1])) {
                ++i;
                continue;
            }
            const long end = literalEnd(src, i, '\'');
            blank(out, i, end);
            i = end;
        } else {
            ++i;
        }
    }
    // Keep each #if's first branch only: the lines of #else / #elif branches are blanked.
    std::vector<bool> skipping;
    for (std::size_t rawAt = 0; rawAt <= src.size();) {
        std::size_t rawEnd = src.find('\n', rawAt);
        if (rawEnd == std::string::npos) rawEnd = src.size();
        const std::string d = directive(src.substr(rawAt, rawEnd - rawAt));
        if (d == "if" || d == "ifdef" || d == "ifndef")
            skipping.push_back(false);
        else if ((d == "else" || d == "elif") && !skipping.empty())
            skipping.back() = true;
        else if (d == "endif" && !skipping.empty())
            skipping.pop_back();
        else if (std::find(skipping.begin(), skipping.end(), true) != skipping.end())
            blank(out, long(rawAt), long(rawEnd));
        rawAt = rawEnd + 1;
    }
    return out;
}

struct FunctionBody {
    std::string name;
    int firstLine;  // the opening brace's line
    int lastLine;   // the closing brace's line
    int length() const { return lastLine - firstLine + 1; }
};

// Finds function bodies in cleaned source by matching brackets.
class Scanner {
public:
    explicit Scanner(std::string text) : t_(std::move(text)) {}

    std::vector<FunctionBody> scan() {
        struct Open {
            char c;
            long pos;
            char kind;  // 'f' function body, 'b' a block inside one, 's' scope, 'i' ( or [ outside functions
            int line;
            std::string name;
        };
        std::vector<Open> stack;
        std::vector<FunctionBody> out;
        int line = 1;
        for (long i = 0; i < long(t_.size()); ++i) {
            const char c = t_[i];
            if (c == '\n') {
                ++line;
            } else if (c == '(' || c == '[' || c == '{') {
                char kind = 'i';
                std::string name;
                if (c == '{') {
                    const bool inFunction = std::any_of(stack.begin(), stack.end(),
                                                        [](const Open& o) { return o.kind == 'f' || o.kind == 'b'; });
                    if (inFunction) {
                        kind = 'b';
                    } else if (auto f = classify(i)) {
                        kind = 'f';
                        name = *f;
                    } else {
                        kind = 's';
                    }
                }
                stack.push_back({c, i, kind, line, name});
            } else if ((c == ')' || c == ']' || c == '}') && !stack.empty()) {
                const Open o = stack.back();
                stack.pop_back();
                match_[i] = o.pos;
                if (o.kind == 'f') out.push_back({o.name, o.line, line});
            }
        }
        unclosed_ = int(stack.size());
        return out;
    }
    int unclosed() const { return unclosed_; }

private:
    std::string t_;
    std::unordered_map<long, long> match_;  // a closing bracket's position -> its opening one's
    int unclosed_ = 0;

    std::optional<long> opener(long closer) const {
        const auto it = match_.find(closer);
        return it == match_.end() ? std::nullopt : std::optional<long>(it->second);
    }
    long skipWsBack(long i) const {
        while (i >= 0 && isSpace(t_[i])) --i;
        return i;
    }
    // i is the last character of an identifier: the identifier and its start.
    std::pair<std::string, long> wordBack(long i) const {
        long j = i;
        while (j >= 0 && isWord(t_[j])) --j;
        return {t_.substr(j + 1, i - j), j + 1};
    }
    // From the '>' closing a template argument list at k, the position of its '<' (or -1).
    long templateOpen(long k) const {
        int depth = 0;
        for (; k >= 0; --k) {
            if (t_[k] == '>') ++depth;
            if (t_[k] == '<' && --depth == 0) break;
        }
        return k;
    }

    // From the last significant character before a '{': skips qualifiers, a trailing return type and
    // noexcept(...), and returns where the parameter list's ')' should be (or -1).
    long backOverQualifiers(long i) const {
        static const std::set<std::string> kQualifiers = {"const", "noexcept", "override", "final", "mutable", "volatile",
                                                          "constexpr", "consteval", "&", "&&", "try"};
        while (i >= 0) {
            i = skipWsBack(i);
            if (i < 0) return -1;
            const char c = t_[i];
            if (isWord(c)) {
                const auto [w, s] = wordBack(i);
                if (kQualifiers.count(w)) {
                    i = s - 1;
                    continue;
                }
                if (auto j = skipTrailingType(i)) {
                    i = *j;
                    continue;
                }
                return i;
            }
            if (c == '&') {
                --i;
                continue;
            }
            if (c == ')') {
                if (auto o = opener(i)) {
                    const long k = skipWsBack(*o - 1);
                    if (k >= 0 && isWord(t_[k])) {
                        const auto [w, s] = wordBack(k);
                        if (w == "noexcept" || w == "throw") {
                            i = s - 1;
                            continue;
                        }
                    }
                }
                return i;
            }
            if (c == '>' || c == '*') {
                if (auto j = skipTrailingType(i)) {
                    i = *j;
                    continue;
                }
            }
            return i;
        }
        return -1;
    }

    // When the text ending at i is "-> Type": the position before the "->".
    std::optional<long> skipTrailingType(long i) const {
        int depth = 0;
        for (long j = i; j >= 1; --j) {
            const char c = t_[j];
            if (c == '>' && t_[j - 1] == '-' && depth == 0) return j - 2;
            if (c == '>') {
                ++depth;
            } else if (c == '<') {
                if (--depth < 0) return std::nullopt;
            } else if (std::string_view(";{}()=,").find(c) != std::string_view::npos) {
                if (depth == 0 || c == ';' || c == '{' || c == '}') return std::nullopt;
            }
        }
        return std::nullopt;
    }

    // i is the '}' or ')' ending a constructor's member initializers: walks back over
    // "name(args), name{args}" to the ':' and returns the position before it.
    std::optional<long> initListBack(long i) const {
        while (true) {
            const auto o = opener(i);
            if (!o) return std::nullopt;
            long k = skipWsBack(*o - 1);
            if (k >= 0 && t_[k] == '>') k = skipWsBack(templateOpen(k) - 1);  // Base<T>{...}
            if (k < 0 || !isWord(t_[k])) return std::nullopt;
            while (true) {  // a qualified name
                k = skipWsBack(wordBack(k).second - 1);
                if (k >= 1 && t_[k] == ':' && t_[k - 1] == ':') {
                    k = skipWsBack(k - 2);
                    continue;
                }
                break;
            }
            if (k >= 0 && t_[k] == ',') {
                k = skipWsBack(k - 1);
                if (k >= 0 && (t_[k] == ')' || t_[k] == '}')) {
                    i = k;
                    continue;
                }
                return std::nullopt;
            }
            if (k >= 2 && t_.compare(k - 2, 3, "...") == 0) return std::nullopt;
            if (k >= 0 && t_[k] == ':' && (k == 0 || t_[k - 1] != ':')) return k - 1;
            return std::nullopt;
        }
    }

    // The name before the parameter list that closes at closeParen, qualified (A::f), or nullopt.
    std::optional<std::string> functionName(long closeParen) const {
        const auto o = opener(closeParen);
        if (!o) return std::nullopt;
        const long k = skipWsBack(*o - 1);
        if (k < 0) return std::nullopt;
        if (t_[k] == ']') {  // a lambda, unless operator[]
            const long k2 = skipWsBack(k - 1);
            if (k2 >= 0 && t_[k2] == '[') {
                const auto [w, s] = wordBack(skipWsBack(k2 - 1));
                if (w == "operator") return qualify(s, "operator[]");
            }
            return "<lambda>";
        }
        if (t_[k] == ')') {  // operator()(...)
            if (auto o2 = opener(k)) {
                const auto [w, s] = wordBack(skipWsBack(*o2 - 1));
                if (w == "operator") return qualify(s, "operator()");
            }
            return std::nullopt;
        }
        if (t_[k] == '>') {  // a template specialisation's name<...>(
            long j = k;
            for (int depth = 0; j >= 0; --j) {
                if (t_[j] == '>') ++depth;
                else if (t_[j] == '<' && --depth == 0) break;
                else if (t_[j] == ';' || t_[j] == '{' || t_[j] == '}') break;
            }
            const long kk = skipWsBack(j - 1);
            if (kk >= 0 && isWord(t_[kk])) {
                const auto [w, s] = wordBack(kk);
                return qualify(s, w + "<>");
            }
        }
        if (isWord(t_[k])) {
            const auto [w, s] = wordBack(k);
            if (isControlWord(w)) return std::nullopt;
            if (s > 0 && t_[s - 1] == '~') return qualify(s - 1, "~" + w);
            return qualify(s, w);
        }
        static const std::regex kOperator(R"(operator\s*([^\w\s(]+)\s*$)");
        const long from = std::max(0L, k - 40);
        const std::string tail = t_.substr(from, k + 1 - from);
        if (std::smatch m; std::regex_search(tail, m, kOperator)) return "operator" + m[1].str();
        return std::nullopt;
    }

    std::string qualify(long s, const std::string& name) const {
        std::string out = name;
        long k = skipWsBack(s - 1);
        while (k >= 1 && t_[k] == ':' && t_[k - 1] == ':') {
            k = skipWsBack(k - 2);
            if (k >= 0 && t_[k] == '>') k = skipWsBack(templateOpen(k) - 1);  // Foo<T>::
            if (k < 0 || !isWord(t_[k])) break;
            const auto [w, s2] = wordBack(k);
            out = w + "::" + out;
            k = skipWsBack(s2 - 1);
        }
        return out;
    }

    std::optional<std::string> wordBeforeParen(long closeParen) const {
        const auto o = opener(closeParen);
        if (!o) return std::nullopt;
        const long k = skipWsBack(*o - 1);
        if (k < 0 || !isWord(t_[k])) return std::nullopt;
        return wordBack(k).first;
    }
    bool isControl(long closeParen) const {
        const auto w = wordBeforeParen(closeParen);
        return w && isControlWord(*w);
    }

    // The function's name when the '{' at pos opens a function body, else nullopt.
    std::optional<std::string> classify(long pos) const {
        const long k = skipWsBack(pos - 1);
        if (k < 0) return std::nullopt;
        const char c = t_[k];
        if (c == '=') return std::nullopt;
        if (c == '}') {  // a body after a trailing "requires requires(...) { ... }" clause
            const auto o = opener(k);
            const long k2 = o ? skipWsBack(*o - 1) : -1;
            if (k2 >= 0 && t_[k2] == ')' && wordBeforeParen(k2) == "requires") {
                long k3 = skipWsBack(*opener(k2) - 1);
                k3 = skipWsBack(wordBack(k3).second - 1);
                if (k3 >= 0 && wordBack(k3).first == "requires") k3 = wordBack(k3).second - 1;
                const long j = backOverQualifiers(k3);
                if (j >= 0 && t_[j] == ')') return functionName(j).value_or("<anon>");
            }
        }
        if (c == '}' || c == ')') {  // a constructor whose member initializers end with name{..} or name(..)
            if (auto j = initListBack(k)) {
                const long j2 = backOverQualifiers(*j);
                if (j2 >= 0 && t_[j2] == ')') return functionName(j2).value_or("<ctor>");
            }
        }
        const long j = backOverQualifiers(k);
        if (j < 0 || t_[j] != ')') return std::nullopt;
        if (isControl(j)) return std::nullopt;  // e.g. a requires(...) { ... } expression
        return functionName(j).value_or("<anon>");  // a macro's TEST(...) { is a body too
    }
};

std::vector<FunctionBody> functionBodies(const std::string& src) { return Scanner(clean(src)).scan(); }

// What exceeds the limits in one file, each problem as "file:line: ...".
// functions, when given, counts the function bodies found.
std::vector<std::string> sizeProblems(const std::string& file, const std::string& src, int fileLines = kFileLines,
                                      int functionLines = kFunctionLines, int* functions = nullptr) {
    std::vector<std::string> problems;
    if (const int n = lineCount(src); n > fileLines)
        problems.push_back(file + ":1: " + std::to_string(n) + " lines, over " + std::to_string(fileLines));
    Scanner scanner(clean(src));
    const std::vector<FunctionBody> bodies = scanner.scan();
    if (functions) *functions += int(bodies.size());
    for (const FunctionBody& f : bodies)
        if (f.length() > functionLines)
            problems.push_back(file + ":" + std::to_string(f.firstLine) + ": " + f.name + " is " +
                               std::to_string(f.length()) + " lines, over " + std::to_string(functionLines));
    if (scanner.unclosed() > 0)
        problems.push_back(file + ": " + std::to_string(scanner.unclosed()) + " unclosed bracket(s)");
    return problems;
}

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// n lines of one statement (no braces), to make long bodies and files.
std::string lines(int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += "    x += 1;\n";
    return s;
}

}  // namespace size_limits

TEST_CASE("every source file is at most 800 lines and every function body at most 120") {
    using namespace size_limits;
    const fs::path root = CDLAB_SOURCE_DIR;
    std::vector<std::string> problems;
    int files = 0, functions = 0;
    for (const char* top : {"core", "render", "app", "demos", "verification"}) {
        for (auto it = fs::recursive_directory_iterator(root / top); it != fs::recursive_directory_iterator(); ++it) {
            if (it->is_directory() && it->path().filename().string().rfind("build", 0) == 0) {
                it.disable_recursion_pending();
                continue;
            }
            const std::string ext = it->path().extension().string();
            if (!it->is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
            const std::string src = readFile(it->path());
            ++files;
            for (std::string& p : sizeProblems(fs::relative(it->path(), root).string(), src, kFileLines, kFunctionLines,
                                               &functions))
                problems.push_back(p);
        }
    }
    for (const std::string& p : problems) MESSAGE(p);
    CHECK(files > 200);
    CHECK(functions > 1000);
    CHECK(problems.empty());
}

TEST_CASE("the size check catches long functions and files, and only those") {
    using namespace size_limits;
    SUBCASE("a long function, named with its first line and length") {
        const std::string src = "int a = 0;\n\nvoid Foo::bar(int x) const {\n" + lines(125) + "}\n";
        const auto problems = sizeProblems("f.cpp", src);
        REQUIRE(problems.size() == 1);
        CHECK(problems[0] == "f.cpp:3: Foo::bar is 127 lines, over 120");
        CHECK(sizeProblems("f.cpp", "void f() {\n" + lines(118) + "}\n").empty());  // exactly 120
    }
    SUBCASE("a long file") {
        CHECK(sizeProblems("f.h", lines(800)).empty());
        const auto problems = sizeProblems("f.h", lines(801));
        REQUIRE(problems.size() == 1);
        CHECK(problems[0] == "f.h:1: 801 lines, over 800");
        CHECK(lineCount("a\nb") == 2);
    }
    SUBCASE("a class body, a namespace and an initializer are not functions") {
        const std::string src = "namespace n {\nstruct S {\n" + lines(130) + "    int g() const { return 1; }\n};\n" +
                                "const int table[] = {\n" + lines(130) + "};\nenum class E {\n" + lines(130) + "};\n}\n";
        const auto bodies = functionBodies(src);
        REQUIRE(bodies.size() == 1);
        CHECK(bodies[0].name == "g");
        CHECK(bodies[0].length() == 1);
        CHECK(sizeProblems("f.h", src, 800, 120).empty());
    }
    SUBCASE("a constructor's member initializers and a lambda inside a function") {
        const std::string src = "A::A(int x) : b_(x), c_{2} {\n  auto f = [&](int y) {\n" + lines(3) + "  };\n}\n";
        const auto bodies = functionBodies(src);
        REQUIRE(bodies.size() == 1);
        CHECK(bodies[0].name == "A::A");
        CHECK(bodies[0].length() == 7);
    }
    SUBCASE("braces in strings, characters, comments and preprocessor lines do not count") {
        const std::string src = "const char* s = \"{\";\n// {\n/* { */\n#define OPEN {\nchar c = '{';\n"
                                "auto r = R\"x(})\" {)x\";\nint f() {\n  return '}' + \"}\"[0]; // }\n}\n"
                                "int big = 1'000'000;\n";
        const auto bodies = functionBodies(src);
        REQUIRE(bodies.size() == 1);
        CHECK(bodies[0].name == "f");
        CHECK(bodies[0].firstLine == 7);
        CHECK(bodies[0].length() == 3);
        CHECK(sizeProblems("f.cpp", src).empty());
    }
    SUBCASE("an #else branch is dropped") {
        const std::string src = "#if A\nvoid f() {\n#else\nvoid f(int) {\n#endif\n" + lines(2) + "}\n";
        const auto bodies = functionBodies(src);
        REQUIRE(bodies.size() == 1);
        CHECK(bodies[0].firstLine == 2);
        CHECK(bodies[0].length() == 7);
    }
}
