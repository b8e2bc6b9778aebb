// The measuring machinery of `cdlab bench` (app/bench/bench.cpp), public so that other bench
// sections (V-Clip, contact) and `cdlab stress` produce the same rows from the same inputs.
//
// Timing: after one untimed warm-up pass, a configuration runs over its whole input set `reps`
// times; one repetition gives one time per query (total / count); a Row keeps the median and the
// min / max over the repetitions.
// Error: relative, |x - x*| / |x*| on the distance or depth (for touching sets, whose oracle answer
// is 0, |x| / size); for boolean queries 1 per wrong answer (the mean is the fraction wrong).
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "core/base/types.h"
#include "app/bench/peers/bench_peers.h"

namespace cdlab::demos {

/// Error distribution of one row (relative errors, or 0 / 1 per answer for boolean queries).
struct ErrorStats {
    double median = 0, p99 = 0, max = 0;
    double above1e6 = 0, above1e2 = 0;  ///< fraction of answers with error > 1e-6 / > 1e-2
};

/// Median, p99 (nearest rank), max and the fractions above 1e-6 and 1e-2 of `errors`.
ErrorStats errorStats(std::vector<double> errors);

/// One line of the bench table.
struct Row {
    std::string query, input, method;
    int queries = 0;                            ///< inputs in the set
    int reps = 0;                               ///< repetitions of the whole set
    double nsMedian = 0, nsMin = 0, nsMax = 0;  ///< time per query over the repetitions, ns
    ErrorStats error;
    double iterations = 0;       ///< mean per query (0 where meaningless)
    bool boolean = false;        ///< error = wrong answers
    double ratio = 0;            ///< peers: min time / cdlab's min time on the same input (0: not a peer)
    std::vector<double> errors;  ///< every query's error (last repetition), for histograms
};

/// What one query returns: the value compared with the oracle, and its iteration count.
struct Answer {
    double value = 0;
    int iterations = 0;
};

struct Settings {
    bool quick = false;
    int targetQueries = 100000;  ///< per row: reps * count >= this (at least 3 reps)
    bool progress = true;        ///< one line per row on stderr
};

/// Runs run(i) over i in [0, count) `reps` times and scores the answers of the last repetition
/// with error(i, answer). Prints one progress line on stderr when settings.progress.
Row measure(const Settings& settings, std::string query, std::string input, std::string method, int count,
            const std::function<Answer(int)>& run, const std::function<double(int, const Answer&)>& error,
            bool boolean = false);

/// One row per peer, measured as `measure` does on the same `count` inputs, each with its ratio:
/// its min time over rows[reference]'s (cdlab's row on that input). No peers (none installed): no rows.
void appendPeerRows(const Settings& settings, std::vector<Row>& rows, const std::string& query,
                    const std::string& input, const std::vector<PeerRunner>& peers, int count, size_t reference,
                    const std::function<double(int, const Answer&)>& error, bool boolean = false);

/// |x - exact| / exact, or |x - exact| / size when exact is 0 (touching: relative to the size).
double relativeError(double x, double exact, double size);

/// Uniformly random rotation (normalised Gaussian quaternion).
Quat randomRotation(std::mt19937_64& rng);

/// Uniformly random unit vector.
Vec3 randomUnit(std::mt19937_64& rng);

/// n points on a randomly rotated ellipsoid with radii in [0.3, 1] (all in convex position).
std::vector<Vec3> ellipsoidPoints(std::mt19937_64& rng, int n);

/// printf-style formatting of one number ("%.0e", 1e-6 -> "1e-06").
std::string fmt(const char* format, double x);
/// A table cell: fmt(format, x), or "-" for a value not measured (NaN, infinite).
std::string cell(const char* format, double x);

/// CPU model, core count and load average (from /proc), for reports.
std::string machineDescription();

}  // namespace cdlab::demos
