// The figures runner's writer thread (app/harness/background_writer.h): tasks run one at a time
// in submission order, reports come back in that order, finish() waits for all, and the
// synchronous mode (profiling) runs each task inside submit().
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "app/harness/background_writer.h"

using namespace cdlab::demos;

TEST_CASE("background writer: submission order, one task at a time, all reports at finish") {
    for (bool threaded : {true, false}) {
        CAPTURE(threaded);
        BackgroundWriter writer(threaded, 2);
        std::atomic<int> running{0}, maxRunning{0}, next{0};
        std::atomic<bool> outOfOrder{false};
        for (int i = 0; i < 12; ++i) {
            writer.submit([&, i] {
                maxRunning = std::max(maxRunning.load(), ++running);
                if (next.fetch_add(1) != i) outOfOrder = true;
                std::this_thread::sleep_for(std::chrono::milliseconds(i % 3));
                --running;
                return WriteReport{i % 5 == 0 ? "scene " + std::to_string(i) + ": failed" : "", i, ""};
            });
            if (!threaded) CHECK(next == i + 1);  // ran inside submit()
        }
        const std::vector<WriteReport> reports = writer.finish();
        REQUIRE(reports.size() == 12);
        for (int i = 0; i < 12; ++i) {
            CHECK(reports[i].frames == i);
            CHECK(reports[i].error.empty() == (i % 5 != 0));
        }
        CHECK(!outOfOrder);
        CHECK(maxRunning == 1);
        CHECK(writer.finish().empty());  // reports are handed back once
    }
}
