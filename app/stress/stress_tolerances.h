// The stress suite's tolerances, shared by stress.cpp (the checks) and stress_cli.cpp (the
// report's figures). The file comment of stress.cpp states the 8 u M term they are added to.
#pragma once

namespace cdlab::demos::stress_tolerances {

// ---- Tolerances (relative to the size L; see the file comment for the 8 u M term) ---------------

// GJK / EPA distances and depths: both algorithms subtract support points of magnitude ~L
// (exactly, by Sterbenz, when the shapes are far from the origin) and stop at a relative gap of
// 1e-13; their rounding floor is a few ulps of L (~1e-15 L), the oracle's the same in long double.
// 1e-12 L leaves a factor ~100 for ill-conditioned features (slivers, nearly parallel edges) and
// still catches a wrong feature or an early stop at any gap above 1e-12 L.
constexpr double kDistanceTol = 1e-12;
// EPA's depth and normal: the face normals come from cross products of polytope edges, whose
// relative error grows as 1 / (face size / L) on thin faces; 1e-10 L keeps 4 digits for that.
constexpr double kDepthTol = 1e-10;
// Booleans: within the distance tolerance of touching either answer is right (a touching pair
// rounds either way); outside it the answer must match the oracle's.
constexpr double kBooleanBand = kDistanceTol;
// SAT OBB-OBB is conservative by design (kSatParallelEpsilon = 1e-9 added to |R_ij|: at most
// 1e-9 x the sum of the six half extents <= 6e-9 L): a separated pair closer than 1e-8 L may be
// reported as overlapping, never the reverse.
constexpr double kSatBand = 1e-8;
// Closest point on a triangle: the distance comes from a world-frame point (rounded coordinates).
constexpr double kClosestTol = 1e-12;
// Float-rounded input: moving every vertex by at most 2^-24 |x| moves the distance / depth by at
// most 2^-24 (max |a| + max |b|) (conv is 1-Lipschitz in the Hausdorff distance), plus the above.
constexpr double kFloatU = 0x1p-24;
// Witness points (verification/witness_oracle.h): a witness on its body within 1e-9 of that body's
// own size L_body (+ 8 u M_body: the witness is a world-frame point), and pointA - pointB = s n
// within 1e-9 L (+ 8 u M). Both witnesses are convex combinations of support points with weights
// from the final simplex / face (errors of a few ulps, ~1e-15, on well-shaped features, growing as
// 1 / (feature size / L) on slivers): 1e-9 leaves the same margin as the depth tolerance and still
// catches a witness on the wrong feature (an error of the feature's size) anywhere above 1e-9 L.
// A bound to be measured: `cdlab stress` reports the worst error of every witness cell.
constexpr double kWitnessTol = 1e-9;
// GJK's separating axis is (pointB - pointA) / distance: witnesses within tau of a closest pair
// turn it by at most 2 * 2 tau / d, and h_{A-B} is Lipschitz with constant max |A - B| <= d + 4 L,
// so |h_{A-B}(n) + d| <= 4 tau (1 + 4 L / d) with tau the offset tolerance above. The factor
// kAxisFactor is that 4; the check is meaningful where d >> tau (every separated case but the
// near-touching ones, where any axis nearly separates).
constexpr double kAxisFactor = 4.0;
// The hull oracle's own resolution where a body is 1e9 times smaller than the pair's size: the hull
// of the rounded differences (tolerance ~4096 ulps of their magnitude, ~1e-12 L) merges the tiny
// body's features; measured against the brute force in the "tiny against huge" family: worst
// 6.3e-11 L (60 s of `cdlab stress`). Added to that family's verdict, distance and depth tolerances.
constexpr double kHullOracleSlack = 1e-10;

}  // namespace cdlab::demos::stress_tolerances
