// Rays within rounding of a face plane (issue 41 class 3): the exact decision of
// intersectRayTriangle said hit, then Möller–Trumbore's t came from a near-zero d · n and was
// anywhere (t = 0 with the point at the origin 5548 from the shape; a t whose point was 5.3e-3
// outside a body of size 0.08). Truth: an exact-rational Cyrus–Beck oracle written here — the
// facets of conv(P) by brute force over triples and the ray's entry parameter as a fraction of
// BigInts (verification/closest_oracle.h), the input doubles taken as exact rationals — never the
// code under test.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/cast/ray_cast.h"
#include "core/overlap/intersect_ray.h"
#include "core/query/cast.h"
#include "verification/closest_oracle.h"

using namespace cdlab;
using oracle::BigInt;
using oracle::BigVec;

namespace {

BigInt neg(const BigInt& x) {
    BigInt r = x;
    r.sign = -r.sign;
    return r;
}
long double toLD(const BigInt& x) {
    long double v = 0;
    for (std::size_t i = x.mag.size(); i-- > 0;) v = v * 4294967296.0L + x.mag[i];
    return x.sign < 0 ? -v : v;
}
// num / den as long double (den > 0), good to ~1e-19 relative while both fit a long double.
long double ratio(const BigInt& num, const BigInt& den) {
    // Drop common low limbs to keep both in range.
    BigInt n = num, d = den;
    while (n.mag.size() > 8 && d.mag.size() > 8) n.mag.erase(n.mag.begin()), d.mag.erase(d.mag.begin());
    return toLD(n) / toLD(d);
}
// a/b < c/d for b, d > 0.
bool less(const BigInt& a, const BigInt& b, const BigInt& c, const BigInt& d) { return (c * b - a * d).sign > 0; }

struct ExactCast {
    bool valid = false, hit = false, inside = false;
    long double tEnter = 0, tExit = 0;
};

// Cyrus–Beck (Ericson §5.3.8) of o + t d, t >= 0, against the facet half-spaces of conv(points),
// in exact rationals: every coordinate scaled by 2^K to an integer (t is unchanged).
ExactCast exactCast(const Vec3& o, const Vec3& d, const std::vector<Vec3>& points) {
    ExactCast out;
    int K = oracle::commonShift({o, d});
    for (const Vec3& p : points) K = std::max(K, oracle::commonShift({p}));
    const BigVec O = oracle::toBig(o, K), D = oracle::toBig(d, K);
    std::vector<BigVec> P;
    for (const Vec3& p : points) P.push_back(oracle::toBig(p, K));
    BigInt enterNum, enterDen = BigInt::fromParts(1, 0, false);  // 0 / 1
    bool bounded = false, parallelOutside = false, insideAll = true;
    BigInt exitNum, exitDen;
    const std::size_t n = P.size();
    int facets = 0;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                BigVec N = oracle::cross(oracle::sub(P[j], P[i]), oracle::sub(P[k], P[i]));
                if (N.v[0].sign == 0 && N.v[1].sign == 0 && N.v[2].sign == 0) continue;
                bool above = false, below = false;
                for (std::size_t m = 0; m < n; ++m) {
                    const int s = oracle::dotv(N, oracle::sub(P[m], P[i])).sign;
                    above |= s > 0, below |= s < 0;
                }
                if (above && below) continue;
                if (above) N = {{neg(N.v[0]), neg(N.v[1]), neg(N.v[2])}};  // outward
                ++facets;
                // Inside the half-space: N · (x − P_i) <= 0. Along the ray: s0 + t rate.
                const BigInt s0 = oracle::dotv(N, oracle::sub(O, P[i])), rate = oracle::dotv(N, D);
                if (s0.sign > 0) insideAll = false;
                if (rate.sign == 0) {
                    if (s0.sign > 0) parallelOutside = true;
                    continue;
                }
                // t = −s0 / rate, as num / den with den > 0.
                BigInt num = neg(s0), den = rate;
                if (den.sign < 0) num = neg(num), den = neg(den);
                if (rate.sign < 0) {
                    if (less(enterNum, enterDen, num, den)) enterNum = num, enterDen = den;
                } else if (!bounded || less(num, den, exitNum, exitDen)) {
                    exitNum = num, exitDen = den, bounded = true;
                }
            }
    if (facets < 4) return out;
    out.valid = true;
    out.inside = insideAll;
    out.hit = !parallelOutside && (!bounded || !less(exitNum, exitDen, enterNum, enterDen));
    out.tEnter = ratio(enterNum, enterDen);
    out.tExit = bounded ? ratio(exitNum, exitDen) : std::numeric_limits<long double>::infinity();
    return out;
}

using LVec = Eigen::Matrix<long double, 3, 1>;
LVec L(const Vec3& v) { return v.cast<long double>(); }

// Largest signed distance of x from the facet planes of conv(points) (long double; <= 0 inside).
long double outside(const LVec& x, const std::vector<Vec3>& points) {
    long double worst = -std::numeric_limits<long double>::infinity();
    const std::size_t n = points.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                LVec N = (L(points[j]) - L(points[i])).cross(L(points[k]) - L(points[i]));
                if (!(N.norm() > 0)) continue;
                N /= N.norm();
                bool above = false, below = false;
                for (std::size_t m = 0; m < n; ++m) {
                    const long double s = N.dot(L(points[m]) - L(points[i]));
                    above |= s > 1e-15L, below |= s < -1e-15L;
                }
                if (above && below) continue;
                if (above) N = -N;
                worst = std::max(worst, N.dot(x - L(points[i])));
            }
    return worst;
}

// First t >= 0 at which o + t d is in the polytope with every facet plane pushed out by tol (long
// double Cyrus–Beck): a lower bound of the first t at which the ray comes within tol of conv(points).
long double offsetEntry(const Vec3& o, const Vec3& d, const std::vector<Vec3>& points, long double tol) {
    long double enter = 0;
    const std::size_t n = points.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                LVec N = (L(points[j]) - L(points[i])).cross(L(points[k]) - L(points[i]));
                if (!(N.norm() > 0)) continue;
                N /= N.norm();
                bool above = false, below = false;
                for (std::size_t m = 0; m < n; ++m) {
                    const long double s = N.dot(L(points[m]) - L(points[i]));
                    above |= s > 1e-15L, below |= s < -1e-15L;
                }
                if (above && below) continue;
                if (above) N = -N;
                const long double s0 = N.dot(L(o) - L(points[i])) - tol, rate = N.dot(L(d));
                if (rate < 0) enter = std::max(enter, -s0 / rate);
            }
    return enter;
}

long double extent(const std::vector<Vec3>& points) {
    long double e = 0;
    for (const Vec3& p : points)
        for (const Vec3& q : points) e = std::max(e, (L(p) - L(q)).norm());
    return e;
}

struct Reproducer {
    Vec3 origin, direction;
    std::vector<Vec3> vertices;
    double exactT;
    Vec3 exactPoint;
};

}  // namespace

TEST_SUITE("ray_cast_face_plane") {
    TEST_CASE("the reproducers: raycast_face_plane_t0 and raycast_face_plane_wrong_t") {
        // /work/shared/reproducers/exact-2026-11-29/raycast_face_plane_{t0,wrong_t}.jsonl, as C++.
        const Reproducer cases[] = {
            {Vec3(-794.624655342423, -3614.0129251864237, -7008.667761732427),
             Vec3(-0.0024747875494326027, 0.005302842599821392, 0.007086220266032992),
             {Vec3(-169.61173377726746, 2281.3246064248015, -5709.103707819921),
              Vec3(-1751.3246257807084, -3376.5682631368386, 2143.8324443069873),
              Vec3(2518.2038096559195, -1351.795268404718, 4094.5727667453175),
              Vec3(-4297.203691127979, 2649.8563120329645, 2490.465958770188),
              Vec3(-3744.8274355765184, -1251.6109032333563, -251.7314222089224)},
             1042854.1621862464,
             Vec3(-3375.4671517949137, 1916.07855145585, 381.226536868609)},
            {Vec3(0.010011027805569664, -0.06723237211045718, -0.007537497862767773),
             Vec3(6.433477310990139, 50.7414406488337, 2.5021517379612295),
             {Vec3(0.03175535948170796, -0.023899266463025665, -0.0022261927715888914),
              Vec3(0.03162169981398272, -0.006504247092019835, -0.023193571399726012),
              Vec3(-0.005878187877578296, 0.016248494476715346, -0.02241576697933573),
              Vec3(0.04298004863202041, -0.014834441553229154, 0.00018903536409727067),
              Vec3(-0.0023685995929071902, -0.02059068703275759, -0.008811113311969699)},
             0.0008846723365698878,
             Vec3(0.01570254721055267, -0.022342823250731187, -0.005323913438293206)},
        };
        for (const Reproducer& c : cases) {
            const ExactCast e = exactCast(c.origin, c.direction, c.vertices);
            REQUIRE(e.valid);
            REQUIRE(e.hit);
            CHECK(std::abs(e.tEnter - c.exactT) <= 1e-15L * c.exactT);  // the oracle agrees with the file
            const RayCastQueryResult r = rayCastQuery(c.origin, c.direction, QueryShape::polytope(c.vertices),
                                                      std::numeric_limits<double>::infinity());
            REQUIRE(r.hit);
            CHECK_FALSE(r.inside);
            const long double size = extent(c.vertices), norm = L(c.direction).norm();
            CAPTURE(r.t);
            // Before: t = 0 (5548 off) and t = 0.00078125 (5.3e-3 off).
            CHECK(std::abs(r.t - e.tEnter) * norm <= 1e-13L * (size + e.tEnter * norm));
            CHECK((L(r.point) - L(c.exactPoint)).norm() <= 1e-13L * size);
            CHECK(std::abs(outside(L(r.point), c.vertices)) <= 1e-13L * size);
        }
    }

    TEST_CASE("random rays within rounding of a face plane: the exact entry, never before it") {
        // Polytopes of five random points; each ray runs from outside through a point of a hull face
        // along a direction in that face's plane (rounded: within rounding of it), 1 in 3 of them
        // turned by 1e-9 into or out of the body.
        std::mt19937_64 rng(41);
        std::uniform_real_distribution<double> u(-1.0, 1.0), w01(0.0, 1.0);
        int hits = 0, hard = 0, tried = 0;
        for (int i = 0; i < 3000; ++i) {
            const double scale = std::ldexp(1.0, int(u(rng) * 14));
            std::vector<Vec3> P;
            for (int k = 0; k < 5; ++k) P.push_back(scale * Vec3(u(rng), u(rng), u(rng)));
            // A hull face (i0, i1, i2): no point strictly outside its plane (long double is plenty
            // for random points).
            int f[3] = {-1, -1, -1};
            for (int a = 0; a < 5 && f[0] < 0; ++a)
                for (int b = a + 1; b < 5 && f[0] < 0; ++b)
                    for (int c = b + 1; c < 5 && f[0] < 0; ++c) {
                        const LVec N = (L(P[b]) - L(P[a])).cross(L(P[c]) - L(P[a]));
                        int above = 0, below = 0;
                        for (int m = 0; m < 5; ++m) {
                            const long double s = N.dot(L(P[m]) - L(P[a]));
                            above += s > 0, below += s < 0;
                        }
                        if (above == 0 || below == 0) f[0] = a, f[1] = b, f[2] = c;
                    }
            if (f[0] < 0) continue;
            double l0 = w01(rng), l1 = w01(rng) * (1 - l0);
            const Vec3 q = P[f[0]] + l0 * (P[f[1]] - P[f[0]]) + l1 * (P[f[2]] - P[f[0]]);
            Vec3 d = u(rng) * (P[f[1]] - P[f[0]]) + u(rng) * (P[f[2]] - P[f[0]]);
            if (i % 3 == 1) d += 1e-9 * d.norm() * (P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]).normalized();
            if (i % 3 == 2) d -= 1e-9 * d.norm() * (P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]).normalized();
            d *= std::ldexp(1.0, int(u(rng) * 20));
            const Vec3 o = q - (1.0 + 3.0 * w01(rng)) * d;
            const ExactCast e = exactCast(o, d, P);
            if (!e.valid || e.inside) continue;
            ++tried;
            const long double size = extent(P), norm = L(d).norm();
            const long double tol = 1e-12L * (size + e.tEnter * norm);
            const RayCastQueryResult r = rayCastQuery(o, d, QueryShape::polytope(P), std::numeric_limits<double>::infinity());
            CAPTURE(i);
            CAPTURE(e.tEnter);
            CAPTURE(r.t);
            if (e.hit && (e.tExit - e.tEnter) * norm > tol) CHECK(r.hit);  // a clear hit is found
            if (!r.hit) continue;
            ++hits;
            if (!e.hit || (e.tExit - e.tEnter) * norm <= 1e-6L * size) ++hard;
            if (r.inside) {  // the origin within the touching tolerance of the shape: t = 0
                CHECK(outside(L(o), P) <= tol);
                continue;
            }
            // The point is on the surface, up to rounding of the size ...
            CHECK(std::abs(outside(L(r.point), P)) <= tol);
            // ... no earlier t comes within rounding of the shape (a graze along the face answers its
            // first point within rounding of it), and the hit is never after the exact entry.
            CHECK(r.t * norm >= offsetEntry(o, d, P, tol) * norm - tol);
            if (e.hit) CHECK(r.t * norm <= e.tEnter * norm + tol);
            if (e.hit && (e.tExit - e.tEnter) * norm > 1e-6L * size) CHECK(std::abs(r.t - e.tEnter) * norm <= tol);
        }
        MESSAGE("rays: " << tried << ", hits: " << hits << ", of them grazing (exit − entry ≤ 1e-6 size or an exact miss): " << hard);
        CHECK(hits > 1000);
    }

    TEST_CASE("a ray lying exactly in a face plane hits at the first point of the face") {
        // The unit cube; rays in the plane z = 1 (exactly) and in the plane x = 0 across a face.
        std::vector<Vec3> cube;
        for (int k = 0; k < 8; ++k) cube.push_back(Vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1));
        const ConvexCastHit h = castRayRoundedHull(Ray{Vec3(-2, 0.25, 1), Vec3(1, 0.125, 0)}, cube);
        REQUIRE(h.hit);
        CHECK(h.t == 2.0);  // enters at x = 0, the face's first point: (0, 0.5, 1)
        CHECK(h.point == Vec3(0, 0.5, 1));
        // Against one triangle: the first point of the triangle in its plane.
        const RayTriangleHit t = intersectRayTriangle(Ray{Vec3(-1, 0.25, 0), Vec3(1, 0, 0)},
                                                      Triangle{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
        REQUIRE(t.hit);
        CHECK(t.coplanar);
        CHECK(t.t == 1.0);
        // A ray just below the plane z = 0 of the triangle, 2^-60 steep: the crossing point, exactly.
        const RayTriangleHit s = intersectRayTriangle(Ray{Vec3(-1, 0.25, -0x1p-60), Vec3(1, 0, 0x1p-60)},
                                                      Triangle{Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0)});
        REQUIRE(s.hit);
        CHECK(s.t == 1.0);
        CHECK(s.point == Vec3(0, 0.25, 0));
    }
}
