// Face normals exact when the face is axis-aligned in the input (issue 41, class 7): FCL's
// LargeBoxSmallSphere (box 0.115 x 0.01 x 0.0025, sphere radius 0.0015 at (-0.02875, -0.0025,
// 0.002)) asserts the normal (0, 0, -1) exactly. The sphere's centre lies over the face's diagonal,
// where GJK's triangle on the cores (box, point) loses its third point to the weights' rounding and
// ends on the diagonal: its axis -v / |v| carried 1e-14 in x and y. gjkFinish
// (core/gjk_epa/gjk_impl.h) now takes an edge's axis from accurateCross and, where the edge lies in
// a face of A − B, the face's accurate normal: every face of the box, over its diagonals and off
// them, penetrating and separated, in both orders, as an aabb, an obb and a polytope.
#include <doctest/doctest.h>

#include <cmath>

#include "core/query/pair.h"

using namespace cdlab;

namespace {

const Vec3 kHalf(0.0575, 0.005, 0.00125);  // FCL's box 0.115 x 0.01 x 0.0025
constexpr double kRadius = 0.0015;

QueryShape fclBox(int kind) {
    switch (kind) {
        case 0: return QueryShape::aabb(-kHalf, kHalf);
        case 1: return QueryShape::obb(Vec3::Zero(), kHalf);
        default: return QueryShape::polytope(QueryShape::aabb(-kHalf, kHalf).vertices);
    }
}

// Exactly: -0 == 0, but 1e-300 != 0.
bool exactly(const Vec3& n, const Vec3& expected) { return n.x() == expected.x() && n.y() == expected.y() && n.z() == expected.z(); }

}  // namespace

TEST_CASE("face normal: FCL LargeBoxSmallSphere gets exactly (0, 0, -1)") {
    for (const double x : {-0.02875, -2.2e-16}) {
        const Vec3 centre(x, -0.0025, 0.002);
        for (int kind = 0; kind < 3; ++kind) {
            CAPTURE(x);
            CAPTURE(kind);
            const PairResult sb = pairQuery(QueryShape::sphere(centre, kRadius), fclBox(kind));
            REQUIRE(sb.status == PairStatus::Ok);
            CHECK(sb.intersect);
            CHECK(exactly(sb.normal, Vec3(0, 0, -1)));
            CHECK(std::abs(sb.depth - 0.00075) <= 1e-18);
            const PairResult bs = pairQuery(fclBox(kind), QueryShape::sphere(centre, kRadius));
            REQUIRE(bs.status == PairStatus::Ok);
            CHECK(bs.intersect);
            CHECK(exactly(bs.normal, Vec3(0, 0, 1)));
            CHECK(std::abs(bs.depth - 0.00075) <= 1e-18);
        }
    }
}

TEST_CASE("face normal: every face of the FCL box, over its diagonals and off them, exact") {
    int checked = 0;
    for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        for (const double side : {1.0, -1.0}) {
            // Over both diagonals (t, t) and (t, -t), and off them.
            for (const double t : {-0.75, -0.5, -0.25, 0.0, 0.25, 0.5, 0.75}) {
                for (const double u : {t, -t, 0.5 * t + 0.125}) {
                    // Penetrating (centre over the face, within the radius) and separated.
                    for (const double gap : {0.5 * kRadius, 0.25 * kRadius, 2.0 * kRadius, 7.0 * kRadius}) {
                        Vec3 centre = Vec3::Zero();
                        centre[i] = t * kHalf[i];
                        centre[j] = u * kHalf[j];
                        centre[k] = side * (kHalf[k] + gap);
                        Vec3 out = Vec3::Zero();
                        out[k] = side;
                        for (int kind = 0; kind < 3; ++kind) {
                            CAPTURE(k);
                            CAPTURE(side);
                            CAPTURE(t);
                            CAPTURE(u);
                            CAPTURE(gap);
                            CAPTURE(kind);
                            const PairResult bs = pairQuery(fclBox(kind), QueryShape::sphere(centre, kRadius));
                            REQUIRE(bs.status == PairStatus::Ok);
                            CHECK(bs.intersect == (gap < kRadius));
                            CHECK(exactly(bs.normal, out));
                            const PairResult sb = pairQuery(QueryShape::sphere(centre, kRadius), fclBox(kind));
                            REQUIRE(sb.status == PairStatus::Ok);
                            CHECK(exactly(sb.normal, Vec3(-out)));
                            // The distance or depth: |gap - r| up to rounding of the centre.
                            const double value = bs.intersect ? bs.depth : bs.distance;
                            CHECK(std::abs(value - std::abs(gap - kRadius)) <= 1e-15);
                            ++checked;
                        }
                    }
                }
            }
        }
    }
    CHECK(checked == 3 * 2 * 7 * 3 * 4 * 3);
}
