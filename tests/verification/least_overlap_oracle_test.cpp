// The least-overlap oracle of the contact stress family (verification/least_overlap_oracle.h): its
// exact cross product keeps what a long double one rounds away, and on bodies with closed-form
// answers (boxes overlapping or apart, wedges whose ridges cross at 1e-12 rad, apart) its least
// overlap, axis and distance are the closed forms.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "verification/least_overlap_oracle.h"

using namespace cdlab;
using cdlab::verification::least_overlap::cross;
using cdlab::verification::least_overlap::edge;
using cdlab::verification::least_overlap::LeastOverlap;
using cdlab::verification::least_overlap::LVec;

namespace least_overlap_test {

std::vector<Vec3> cornersOf(const Vec3& centre, const Vec3& half) {
    std::vector<Vec3> c;
    for (int i = 0; i < 8; ++i)
        c.push_back(centre + Vec3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                                  (i & 4) ? half.z() : -half.z()));
    return c;
}

}  // namespace least_overlap_test

using least_overlap_test::cornersOf;

TEST_SUITE("least overlap oracle") {
    TEST_CASE("the cross product of two edges keeps the bits a long double one rounds away") {
        // (1 + 2^-52, 1, 1) x (1, 1 + 2^-52, 1): z = (1 + 2^-52)^2 - 1 = 2^-51 + 2^-104, which a
        // long double product (64-bit significand) rounds to 2^-51.
        const double e = std::ldexp(1.0, -52);
        const LVec c = cross(edge(Vec3::Zero(), Vec3(1 + e, 1, 1)), edge(Vec3::Zero(), Vec3(1, 1 + e, 1)));
        CHECK(c.z() == std::ldexp(1.0L, -51) + std::ldexp(1.0L, -104));
        CHECK(c.x() == -std::ldexp(1.0L, -52));
        CHECK(c.y() == -std::ldexp(1.0L, -52));
        const long double plain = (1 + (long double)e) * (1 + (long double)e) - 1.0L;
        CHECK(plain == std::ldexp(1.0L, -51));  // what the exact product adds to
    }

    TEST_CASE("boxes: the least overlap along a face, and the distance apart") {
        const std::vector<Vec3> a = cornersOf(Vec3::Zero(), Vec3(1, 2, 3));
        const LeastOverlap over(a, cornersOf(Vec3(1.75, 0.5, 0), Vec3(1, 1, 1)));
        CHECK(double(over.leastOverlap()) == doctest::Approx(0.25).epsilon(1e-15));
        CHECK(double(over.leastAxis().x()) == doctest::Approx(1.0).epsilon(1e-15));
        CHECK(over.distance() == 0);
        const LeastOverlap apart(a, cornersOf(Vec3(2.5, 3.5, 0), Vec3(1, 1, 1)));
        // Apart, D* is minus a separation: at most the face axes' (-0.5), at least -distance (here
        // a diagonal candidate, (1, 1, 0), separates by the whole distance).
        CHECK(double(apart.leastOverlap()) <= -0.5);
        CHECK(double(apart.leastOverlap()) >= -std::sqrt(0.5) * (1 + 1e-15));
        CHECK(double(apart.distance()) == doctest::Approx(std::sqrt(0.5 * 0.5 + 0.5 * 0.5)).epsilon(1e-15));
        CHECK(double(apart.signedDistance()) == doctest::Approx(std::sqrt(0.5)).epsilon(1e-15));
    }

    TEST_CASE("ridges crossing at 1e-12 rad, apart: the edge axis and the distance are the gap") {
        // A's ridge along x in z = 0 (the body below), B's along (cos t, sin t, 0) in z = g (the body
        // above): the edge-edge face of A - B has the normal z and separates them by g, their
        // crossing points (0, 0, 0) and (0, 0, g).
        const double t = 1e-12;
        for (const double g : {1e-12, 1e-9, 1e-3, 0.25}) {
            CAPTURE(g);
            const std::vector<Vec3> a = {{-1, 0, 0}, {1, 0, 0}, {-1, 0.5, -1}, {1, -0.5, -1}};
            const std::vector<Vec3> b = {{-std::cos(t), -std::sin(t), g}, {std::cos(t), std::sin(t), g},
                                         {-1, -0.5, g + 1}, {1, 0.5, g + 1}};
            const LeastOverlap o(a, b);
            CHECK(double(o.leastOverlap()) == doctest::Approx(-g).epsilon(1e-15));
            CHECK(double(o.leastAxis().z()) == doctest::Approx(1.0).epsilon(1e-15));  // from A toward B
            CHECK(double(o.distance()) == doctest::Approx(g).epsilon(1e-15));
        }
    }
}
