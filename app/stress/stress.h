// `cdlab stress`: families of hard inputs from fixed seeds, each answer checked against an
// independent oracle (docs/accuracy.md). Checks need no trust in any one algorithm:
//  - gjk_distance = the Minkowski-hull oracle (verification/minkowski_hull_oracle.h), SV and Johnson;
//  - gjk_intersect and SAT OBB-OBB = the oracle's boolean (so SAT = GJK), outside a rounding band;
//  - epa_depth = the oracle's depth, and the EPA normal valid: |h_{A-B}(n) - depth| small, with the
//    support function h evaluated by brute force over the vertex lists;
//  - every witness field (verification/witness_oracle.h): GJK's (separated answers) and EPA's
//    witness points on their bodies (judged against each body's own size), pointA - pointB =
//    -distance * axis / depth * normal, GJK's axis separating by the distance;
//  - closest point on a triangle: region = the exact rational (BigInt) Ericson region, distance =
//    the long double brute force;
//  - rays and times of impact (stress_witness_runs.cpp): the verdict against the first contact of
//    the path with the body / with B − A; t neither early (apart at t) nor late (no overlap before
//    t, and t no later than the first time the path certainly lies inside B − A, its points exact
//    in long double); the contact points on the bodies at t, equal, the normal a touching direction;
//  - spheres and capsules: distance and penetration against the long double signed distance of the
//    cores minus the radii, every witness field as above;
//  - contact manifolds (stress_contact_runs.cpp): the verdict, the depth within the face
//    preference's range of the least overlap over every face normal and edge cross product of the
//    vertex lists (verification/least_overlap_oracle.h), the normal realising the depth, every
//    point on its body with pointA - pointB = depth_i n, the distance and closest pair apart, the
//    features holding the points and supporting the normal;
//  - no NaN, no hang: every query's iterations are counted, reaching the cap is a failure.
// Every failure becomes one `cdlab query` line (docs/query.md, %.17g numbers) that replays it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace cdlab::demos {

struct StressOptions {
    double seconds = 20.0;  ///< time budget; every family runs at least minCasesPerFamily
    int minCasesPerFamily = 50;
    std::uint64_t seed = 1;      ///< case i of family f draws from seed, f, i only (replayable)
    bool progress = false;       ///< progress lines on stderr
    int maxFailureLines = 2000;  ///< reproducers kept (failures are all counted)
    /// Test hook: called with (check name, answer) before each answer is checked, e.g. to corrupt
    /// it and see the check fire. nullptr in normal runs.
    std::function<void(const std::string& check, double& value)> tamper;
};

/// One (family, check) cell of the report.
struct StressCell {
    std::string family, check;
    bool informational = false;  ///< reported, not judged (e.g. Johnson's sub-algorithm)
    int cases = 0;               ///< answers checked
    int failures = 0;            ///< error > tolerance, NaN, or iteration cap reached
    double worstError = 0.0;     ///< largest error (relative to the problem size; booleans: 1)
    double worstRatio = 0.0;     ///< largest error / tolerance (> 1: failure)
    std::string tolerance;       ///< the tolerance as stated in the report
    int maxIterations = 0;       ///< largest iteration count of one query (0: not iterative)
    int iterationCapHits = 0;
    /// (family parameter, error) per case, for the error-vs-parameter figures (capped in size).
    std::vector<std::pair<double, double>> samples;
};

struct StressReport {
    std::vector<StressCell> cells;
    std::vector<std::string> failureLines;     ///< `cdlab query` reproducers (JSON Lines)
    std::vector<std::string> familyParameter;  ///< per family: what the sample parameter is
    double seconds = 0.0;
    int totalCases = 0, totalFailures = 0;  ///< over judged cells
    bool ok() const { return totalFailures == 0; }
};

/// Runs every family within the budget. Deterministic for a given seed and case count.
StressReport runStressSuite(const StressOptions& options);

/// The report as a terminal table (one line per family x check).
std::string stressTable(const StressReport& report);

/// argv[0] is "stress"; returns the exit status (0 all checks pass, 1 a failure, 2 usage).
int runStress(int argc, char** argv);

}  // namespace cdlab::demos
