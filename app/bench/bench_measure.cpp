#include "app/bench/bench_measure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>

namespace cdlab::demos {

namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

ErrorStats errorStats(std::vector<double> e) {
    ErrorStats s;
    if (e.empty()) return s;
    std::sort(e.begin(), e.end());
    auto at = [&](double q) { return e[std::min(e.size() - 1, static_cast<size_t>(q * (e.size() - 1) + 0.5))]; };
    s.median = at(0.5);
    s.p99 = at(0.99);
    s.max = e.back();
    for (double x : e) {
        s.above1e6 += x > 1e-6;
        s.above1e2 += x > 1e-2;
    }
    s.above1e6 /= e.size();
    s.above1e2 /= e.size();
    return s;
}

Row measure(const Settings& settings, std::string query, std::string input, std::string method, int count,
            const std::function<Answer(int)>& run, const std::function<double(int, const Answer&)>& error,
            bool boolean) {
    Row row;
    row.query = std::move(query);
    row.input = std::move(input);
    row.method = std::move(method);
    row.queries = count;
    row.boolean = boolean;
    row.reps = std::max(3, (settings.targetQueries + count - 1) / std::max(count, 1));
    if (count <= 0) return row;  // empty input set (e.g. no penetrating pair): an empty row
    std::vector<Answer> answers(count);
    std::vector<double> ns;
    for (int i = 0; i < count; ++i) answers[i] = run(i);  // warm-up pass (caches, predictors, clock): untimed
    for (int r = 0; r < row.reps; ++r) {
        const auto t0 = Clock::now();
        for (int i = 0; i < count; ++i) answers[i] = run(i);
        const auto t1 = Clock::now();
        ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / count);
    }
    std::sort(ns.begin(), ns.end());
    row.nsMedian = ns[ns.size() / 2];
    row.nsMin = ns.front();
    row.nsMax = ns.back();
    std::vector<double> errors;
    double iters = 0;
    for (int i = 0; i < count; ++i) {
        errors.push_back(error(i, answers[i]));
        iters += answers[i].iterations;
    }
    row.error = errorStats(errors);
    row.errors = std::move(errors);
    row.iterations = iters / count;
    if (settings.progress)
        std::fprintf(stderr, "  %-14s %-22s %-22s %9.1f ns  max err %.2e\n", row.query.c_str(), row.input.c_str(),
                     row.method.c_str(), row.nsMedian, row.error.max);
    return row;
}

void appendPeerRows(const Settings& settings, std::vector<Row>& rows, const std::string& query,
                    const std::string& input, const std::vector<PeerRunner>& peers, int count, size_t reference,
                    const std::function<double(int, const Answer&)>& error, bool boolean) {
    for (const PeerRunner& peer : peers) {
        Row row = measure(
            settings, query, input, peer.method, count,
            [&](int i) {
                const PeerAnswer a = peer.run(i);
                return Answer{a.value, a.iterations};
            },
            error, boolean);
        // Ratio of the fastest repetitions: on a shared machine the minimum is the time least
        // disturbed by other processes (medians are reported too).
        row.ratio = row.nsMin / rows[reference].nsMin;
        rows.push_back(row);
    }
}

double relativeError(double x, double exact, double size) {
    const double denom = exact > 0 ? exact : size;
    return std::abs(x - exact) / denom;
}

// ---- Inputs --------------------------------------------------------------------------------------

Quat randomRotation(std::mt19937_64& rng) {
    std::normal_distribution<double> g(0.0, 1.0);
    Quat q(g(rng), g(rng), g(rng), g(rng));
    return q.normalized();
}

Vec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> g(0.0, 1.0);
    return Vec3(g(rng), g(rng), g(rng)).normalized();
}

std::vector<Vec3> ellipsoidPoints(std::mt19937_64& rng, int n) {
    std::uniform_real_distribution<double> radius(0.3, 1.0);
    const Vec3 radii(radius(rng), radius(rng), radius(rng));
    const Quat q = randomRotation(rng);
    std::vector<Vec3> v;
    for (int i = 0; i < n; ++i) v.push_back(q * radii.cwiseProduct(randomUnit(rng)));
    return v;
}

std::string fmt(const char* f, double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, x);
    return buf;
}

std::string cell(const char* format, double x) { return std::isfinite(x) ? fmt(format, x) : "-"; }

std::string machineDescription() {
    std::string model = "unknown CPU";
    if (FILE* f = std::fopen("/proc/cpuinfo", "r")) {
        char line[512];
        while (std::fgets(line, sizeof line, f)) {
            if (std::strncmp(line, "model name", 10) == 0) {
                const char* colon = std::strchr(line, ':');
                if (colon) model = colon + 2;
                model.erase(model.find_last_not_of("\n ") + 1);
                break;
            }
        }
        std::fclose(f);
    }
    std::string load = "?";
    if (FILE* f = std::fopen("/proc/loadavg", "r")) {
        char buf[128] = {};
        if (std::fgets(buf, sizeof buf, f)) load = std::string(buf, std::strcspn(buf, " "));
        std::fclose(f);
    }
    return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores, load average " + load;
}

}  // namespace cdlab::demos
