// EPA's support fallback and uncertified duplicate-support answers (issue 41, reproducers
// exact-2026-11-29 penetration_witness_off_shape and penetration_needle_far), through pairQuery.
// Independent oracle in long double from the input vertices only:
//   depth  = min over candidate directions n (face normals of each shape's vertex triples and cross
//            products of an edge of A with an edge of B, both signs) of h_{A−B}(n);
//   on body = p within tol of every supporting plane of the vertex set (triple planes and, for flat
//            sets, the side planes through each pair), i.e. p in the hull.
// The fix: core/gjk_epa/epa_impl.h epaSupportFallback (candidates from the polytope, accurate
// overlaps, witnesses on the bodies) and epaPenetration (uncertified DuplicateSupport answers).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/query/pair.h"
#include "core/query/shape.h"

using namespace cdlab;

// A named namespace: the unity build merges this file with other tests' helpers.
namespace epa_fallback_oracle {

using LD = long double;
struct V {
    LD x, y, z;
};
V ld(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
V sub(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V crs(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
LD dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V unit(V a) {
    const LD l = std::sqrt(dot(a, a));
    return {a.x / l, a.y / l, a.z / l};
}
bool nonzero(V a) { return dot(a, a) > 0; }

/// h_{A−B}(n) = max_a n·a − min_b n·b.
LD overlap(const std::vector<Vec3>& A, const std::vector<Vec3>& B, V n) {
    LD ha = -INFINITY, lb = INFINITY;
    for (const Vec3& a : A) ha = std::max(ha, dot(n, ld(a)));
    for (const Vec3& b : B) lb = std::min(lb, dot(n, ld(b)));
    return ha - lb;
}

LD oracleDepth(const std::vector<Vec3>& A, const std::vector<Vec3>& B) {
    std::vector<V> dirs;
    const auto faces = [&](const std::vector<Vec3>& P) {
        for (size_t i = 0; i < P.size(); ++i)
            for (size_t j = i + 1; j < P.size(); ++j)
                for (size_t k = j + 1; k < P.size(); ++k) {
                    const V c = crs(sub(ld(P[j]), ld(P[i])), sub(ld(P[k]), ld(P[i])));
                    if (nonzero(c)) dirs.push_back(unit(c));
                }
    };
    faces(A);
    faces(B);
    for (size_t i = 0; i < A.size(); ++i)
        for (size_t j = i + 1; j < A.size(); ++j)
            for (size_t k = 0; k < B.size(); ++k)
                for (size_t l = k + 1; l < B.size(); ++l) {
                    const V c = crs(sub(ld(A[j]), ld(A[i])), sub(ld(B[l]), ld(B[k])));
                    if (nonzero(c)) dirs.push_back(unit(c));
                }
    LD best = INFINITY;
    for (const V& n : dirs) best = std::min({best, overlap(A, B, n), overlap(A, B, {-n.x, -n.y, -n.z})});
    return best;
}

/// Largest signed distance of p beyond a supporting plane of the hull of P (<= 0 inside).
LD outside(const std::vector<Vec3>& P, const Vec3& p) {
    LD worst = -INFINITY;
    const auto plane = [&](V n) {
        if (!nonzero(n)) return;
        n = unit(n);
        LD hi = -INFINITY;
        for (const Vec3& q : P) hi = std::max(hi, dot(n, ld(q)));
        worst = std::max(worst, dot(n, ld(p)) - hi);
    };
    for (size_t i = 0; i < P.size(); ++i)
        for (size_t j = i + 1; j < P.size(); ++j)
            for (size_t k = j + 1; k < P.size(); ++k) {
                const V e = sub(ld(P[j]), ld(P[i]));
                const V c = crs(e, sub(ld(P[k]), ld(P[i])));
                if (!nonzero(c)) continue;
                plane(c);
                plane({-c.x, -c.y, -c.z});
                // Side planes of a flat set: through edge ij, orthogonal to the triple's plane.
                for (size_t a = 0; a < P.size(); ++a)
                    for (size_t b = a + 1; b < P.size(); ++b) {
                        const V s = crs(sub(ld(P[b]), ld(P[a])), c);
                        plane(s);
                        plane({-s.x, -s.y, -s.z});
                    }
            }
    return worst;
}

struct Case {
    std::vector<Vec3> a, b;
    PairOptions options;
    double exactDepth;  // the reproducer's .expected.json
};

void check(const Case& c) {
    const PairResult r = pairQuery(QueryShape::polytope(c.a), QueryShape::polytope(c.b), c.options);
    REQUIRE(r.status == PairStatus::Ok);
    REQUIRE(r.intersect);
    const LD oracle = oracleDepth(c.a, c.b);
    CHECK(std::abs(double(oracle) - c.exactDepth) <= 1e-6 * c.exactDepth);  // long double: ~u_ld |B| / depth
    // Depth: the least overlap up to rounding, and the overlap along the returned normal.
    CHECK(std::abs(r.depth - double(oracle)) <= 1e-4 * double(oracle));
    const V n = ld(r.normal);
    CHECK(std::abs(double(overlap(c.a, c.b, n)) - r.depth) <= 1e-4 * double(oracle));
    // Witnesses on their bodies and pointA − pointB = depth · normal.
    const double tol = 1e-3 * double(oracle);
    CHECK(double(outside(c.a, r.pointA)) <= tol);
    CHECK(double(outside(c.b, r.pointB)) <= tol);
    const Vec3 gap = r.pointA - r.pointB - r.depth * r.normal;
    CHECK(gap.norm() <= tol);
}

}  // namespace epa_fallback_oracle

TEST_CASE("EPA degenerate fallback: least overlap over the polytope's candidates, witnesses on the bodies") {
    // penetration_witness_off_shape: a 1e-9 square at the origin inside a face of a 1e5 tetrahedron;
    // before: depth 2.0535e-08 (exact 2.0069e-08), pointA 54 830 away from A.
    const double q = 4.3254897793869003e-10;
    epa_fallback_oracle::Case c;
    c.a = {{q, -q, -q}, {q, -q, q}, {q, q, -q}, {q, q, q}};
    c.b = {{52235.791888125794, 5283.418222812142, 15805.216711761446},
           {539.3340524520635, -361.592716596062, -107.46804417524768},
           {-40244.88947452094, 26981.902640152974, 8019.22209045319},
           {-8399.208693475246, 69703.97638345223, -6707.950543762599}};
    c.options.initialDirection = Vec3(-2.151937437856163, -0.4588760000018163, -0.8151411717048327);
    c.exactDepth = 2.0069471413397885e-08;
    epa_fallback_oracle::check(c);
}

TEST_CASE("EPA duplicate support on a far needle: an uncertified face goes to the fallback") {
    // penetration_needle_far: a needle tetrahedron (width 3.3e-7, length 2434) at 1.6e6; before:
    // depth 1.68e-6 (exact 1.186e-5), normal 1.43 rad off (overlap along it 2155).
    epa_fallback_oracle::Case c;
    c.a = {{1565434.431911736, 424904.62710779114, 184008.95991055568},
           {1563663.6260810446, 423692.2873830186, 185157.063790351},
           {1564621.451478409, 424348.0395597128, 184536.05665599692},
           {1564868.4540519568, 424517.1439458488, 184375.9122697257}};
    c.b = {{1566255.9074028688, 424122.86371655675, 184450.47986691367},
           {1564612.9564235045, 425686.39051283937, 183567.43997325902},
           {1564485.1015721774, 422910.5239917842, 185598.58374670896},
           {1562842.150592813, 424474.0507880668, 184715.54385305432},
           {1562544.4557717824, 423056.56012985477, 182759.5884740932}};
    c.exactDepth = 1.1859318548616629e-05;
    epa_fallback_oracle::check(c);
}

TEST_CASE("EPA fallback witness: a 1e-6 body touching a vertex of a 1e3 one stays on its body") {
    // cdlab stress, "tiny against huge" (seed 1): B's vertex 7 lies inside A's hull to ~1e-9; the
    // uncertified duplicate-support answer goes to the fallback, whose witnesses must lie on the
    // 1e-6 body within 1e-9 of its size + 8 ulps of its coordinates (the stress tolerance).
    const std::vector<Vec3> a = {{414.9556185095432, 733.610478501455, -275.93026767548673},
                                 {414.9556172599714, 733.6104787429966, -275.93026760915956},
                                 {414.9556170520349, 733.6104782660645, -275.9302674315028},
                                 {414.95561789808875, 733.6104781889848, -275.9302661024539},
                                 {414.955617263152, 733.6104777891237, -275.9302670591864},
                                 {414.95561720336394, 733.6104785601334, -275.93026678990805},
                                 {414.9556179987712, 733.6104775217793, -275.9302680106614},
                                 {414.9556189467603, 733.6104778936377, -275.9302674203634}};
    const std::vector<Vec3> b = {{719.3324496391731, 46.4425039720152, -311.8245890947086},
                                 {793.3672384442551, 417.81115703727403, -552.3454067796366},
                                 {-469.483751877087, 269.47205979033725, 252.68103203775811},
                                 {-21.623900022986867, -626.7906645421018, 57.95678333940195},
                                 {-84.17622853402825, -156.20681429270655, 613.5182810030287},
                                 {-151.4378824911243, -558.0760763316935, 517.2917612982308},
                                 {414.95561726239816, 733.6104778384514, -275.93026707424167},
                                 {678.7382099666544, 326.06558367060114, -663.0062139307124},
                                 {-369.45461088771805, -117.59641784457664, 673.1466528406911},
                                 {818.0375776815597, 411.9793598344557, -405.41392765970005},
                                 {-497.0526437815536, 257.6447584287832, 157.08205187847992},
                                 {773.158195410709, 542.0366362255426, -538.1586228744866}};
    const PairResult r = pairQuery(QueryShape::polytope(a), QueryShape::polytope(b));
    REQUIRE(r.status == PairStatus::Ok);
    REQUIRE(r.intersect);
    const double u = std::ldexp(1.0, -53);
    const double tolA = 1e-9 * 2e-6 + 8 * u * 734.0, tolB = 1e-9 * 1.2e3 + 8 * u * 819.0;
    CHECK(double(epa_fallback_oracle::outside(a, r.pointA)) <= tolA);
    CHECK(double(epa_fallback_oracle::outside(b, r.pointB)) <= tolB);
    CHECK((r.pointA - r.pointB - r.depth * r.normal).norm() <= tolB);
    const double oracle = double(epa_fallback_oracle::oracleDepth(a, b));
    CHECK(std::abs(r.depth - oracle) <= 1e-10 * 1.2e3);
}
