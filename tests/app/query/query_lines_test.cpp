// `cdlab query` as a stream: errors name their input line, a line the strict reader refuses keeps its
// id when it can be read, blank lines are skipped, and answers stay matchable by id.
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

#include "app/query/query.h"

using cdlab::demos::Json;
using cdlab::demos::runQueries;

TEST_SUITE("query") {
    TEST_CASE("query lines: errors name the line, duplicate keys keep the id, blank lines are skipped") {
        std::istringstream in(
            "{\"id\":1,\"op\":\"intersect\",\"a\":{\"point\":[0,0,0]},\"b\":{\"point\":[0,0,0]}}\n"
            "\n"
            "   \t\n"
            "{\"id\":\"dup\",\"op\":\"intersect\",\"a\":{\"point\":[0,0,0]},\"a\":{\"point\":[1,0,0]},\"b\":{\"point\":[0,0,0]}}\n"
            "{\"id\":5,\"op\":\"raycast\"}\n"
            "not json\n");
        std::ostringstream out;
        CHECK(runQueries(in, out) == 1);
        std::vector<Json> answers;
        std::istringstream lines(out.str());
        for (std::string line; std::getline(lines, line);) answers.push_back(Json::parse(line));
        REQUIRE(answers.size() == 4);  // the two blank lines are not queries
        CHECK(answers[0]["id"] == 1);
        CHECK(answers[1]["id"] == "dup");
        CHECK(answers[1]["error"].get<std::string>().rfind("query: line 4: ", 0) == 0);
        CHECK(answers[1]["error"].get<std::string>().find("duplicate key") != std::string::npos);
        CHECK(answers[2]["id"] == 5);
        CHECK(answers[2]["error"].get<std::string>().rfind("query: line 5: $: missing required key 'ray'", 0) == 0);
        CHECK(answers[3]["id"].is_null());
        CHECK(answers[3]["error"].get<std::string>().rfind("query: line 6: ", 0) == 0);
    }
}
