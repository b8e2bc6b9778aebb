// The tests' main: doctest's, plus one rule. ctest runs each TEST_CASE on its own with
// --test-case=<name> (doctest_discover_tests); a run whose filter selects no test case fails, so a
// name ctest cannot pass through whole (a ';' splits it into two filters that match nothing) is a
// failure, not a silent pass of zero cases.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdio>
#include <cstring>

namespace {

int g_selected = -1;  // test cases that passed the filters (-1: no run end seen)

struct SelectionCount : doctest::IReporter {
    explicit SelectionCount(const doctest::ContextOptions&) {}
    void report_query(const doctest::QueryData&) override {}
    void test_run_start() override {}
    void test_run_end(const doctest::TestRunStats& stats) override { g_selected = int(stats.numTestCasesPassingFilters); }
    void test_case_start(const doctest::TestCaseData&) override {}
    void test_case_reenter(const doctest::TestCaseData&) override {}
    void test_case_end(const doctest::CurrentTestCaseStats&) override {}
    void test_case_exception(const doctest::TestCaseException&) override {}
    void subcase_start(const doctest::SubcaseSignature&) override {}
    void subcase_end() override {}
    void log_assert(const doctest::AssertData&) override {}
    void log_message(const doctest::MessageData&) override {}
    void test_case_skipped(const doctest::TestCaseData&) override {}
};

REGISTER_LISTENER("selection_count", 1, SelectionCount);

}  // namespace

int main(int argc, char** argv) {
    doctest::Context context(argc, argv);
    const int status = context.run();
    if (context.shouldExit()) return status;
    bool filtered = false;
    for (int i = 1; i < argc; ++i)
        filtered = filtered || std::strncmp(argv[i], "--test-case=", 12) == 0 || std::strncmp(argv[i], "-tc=", 4) == 0;
    if (status == 0 && filtered && g_selected == 0) {
        std::fprintf(stderr, "no test case matches the --test-case filter: a name with ';' is split by ctest\n");
        return 1;
    }
    return status;
}
