// The witness oracle (verification/witness_oracle.h) accepts right contact answers and flags
// constructed wrong ones: a witness moved off its body, pointA - pointB != s n, a normal rotated
// off the least-overlap direction, a non-unit or NaN normal. Boxes, a sphere against a capsule, a
// flat body, tied least-overlap directions, and a rotated pair 1e9 from the origin.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "verification/witness_oracle.h"

using namespace cdlab;
using cdlab::verification::checkRayHit;
using cdlab::verification::checkWitness;
using cdlab::verification::RayHitCheck;
using cdlab::verification::RayHitTolerances;
using cdlab::verification::WitnessBody;
using cdlab::verification::WitnessCheck;
using cdlab::verification::WitnessTolerances;

namespace {

std::vector<Vec3> box(const Vec3& centre, const Vec3& half, const Quat& q = Quat::Identity(),
                      const Vec3& offset = Vec3::Zero()) {
    std::vector<Vec3> c;
    for (int i = 0; i < 8; ++i)
        c.push_back(offset + q * (centre + Vec3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                                                (i & 4) ? half.z() : -half.z())));
    return c;
}

WitnessTolerances tight(double t = 1e-12) {
    WitnessTolerances tol;
    tol.onBodyA = tol.onBodyB = tol.offset = tol.normal = t;
    return tol;
}

/// Witnesses judged loosely, the offset and the normal tightly: a rotated normal with witnesses
/// built from it leaves them slightly off a curved or tilted body; only the normal check must fire.
WitnessTolerances looseBodies(double onBody) {
    WitnessTolerances tol = tight();
    tol.onBodyA = tol.onBodyB = onBody;
    return tol;
}

RayHitTolerances rayTight(double t = 1e-12) {
    RayHitTolerances tol;
    tol.point = tol.surface = tol.firstContact = tol.normal = t;
    return tol;
}

Vec3 rotatedZ(const Vec3& v, double angle) { return Eigen::AngleAxisd(angle, Vec3::UnitZ()) * v; }

}  // namespace

TEST_SUITE("witness oracle") {
    TEST_CASE("overlapping boxes: the right answer passes, and a moved witness and a rotated normal are flagged") {
        // A = [-1,1]^3, B = [0.5,2.5] x [-1,1]^2: depth 0.5 along +x (least overlap: y and z give 2).
        const WitnessBody a = WitnessBody::polytope(box(Vec3::Zero(), Vec3(1, 1, 1)));
        const WitnessBody b = WitnessBody::polytope(box(Vec3(1.5, 0, 0), Vec3(1, 1, 1)));
        CHECK(a.solid());
        const Vec3 pA(1, 0.2, 0.3), pB(0.5, 0.2, 0.3), n = Vec3::UnitX();
        const WitnessCheck right = checkWitness(a, b, pA, pB, n, 0.5, tight());
        CHECK(right.ok());
        CHECK(right.pointAOff <= 1e-15);
        CHECK(right.offset <= 1e-15);
        CHECK(right.normal <= 1e-15);

        // pointA 0.1 outside A (and pointB moved along, so only the body check fails)
        const WitnessCheck off = checkWitness(a, b, pA + Vec3(0.1, 0, 0), pB + Vec3(0.1, 0, 0), n, 0.5, tight());
        CHECK(off.failed == WitnessCheck::Failed::PointAOffBody);
        CHECK(off.size == doctest::Approx(0.1));
        CHECK(off.pointBOff <= 1e-15);
        CHECK(off.offset <= 1e-15);
        // pointB off B by 0.25 across its y face
        const WitnessCheck offB = checkWitness(a, b, pA + Vec3(0, 1.05, 0), pB + Vec3(0, 1.05, 0), n, 0.5, tight());
        CHECK(offB.failed == WitnessCheck::Failed::PointAOffBody);  // A's first: both are out
        CHECK(offB.pointBOff == doctest::Approx(0.25));
        // pointA - pointB != depth n: the depth misreported
        const WitnessCheck gap = checkWitness(a, b, pA, pB, n, 0.6, tight());
        CHECK(gap.failed == WitnessCheck::Failed::Offset);
        CHECK(gap.offset == doctest::Approx(0.1));

        // Normal rotated by 0.01 rad about z, witnesses kept consistent with it (both on their
        // bodies, pointA - pointB = 0.5 n'): only the least-overlap check can see it.
        const Vec3 nr = rotatedZ(n, 0.01);
        const WitnessCheck rot = checkWitness(a, b, pA, pA - 0.5 * nr, nr, 0.5, tight());
        CHECK(rot.pointAOff <= 1e-15);
        CHECK(rot.pointBOff <= 1e-15);
        CHECK(rot.offset <= 1e-15);
        CHECK(rot.failed == WitnessCheck::Failed::Normal);
        // h(n') = h_A(n') + h_B(-n') = (cos + sin) + (-0.5 cos + sin)
        CHECK(rot.normal == doctest::Approx(0.5 * std::cos(0.01) + 2 * std::sin(0.01) - 0.5));
        // The opposite normal (witnesses on their bodies, h_{A-B}(-n) = 1 + 2.5), a non-unit one, a NaN witness
        const WitnessCheck flipped = checkWitness(a, b, pA, pA + 0.5 * n, -n, 0.5, tight());
        CHECK(flipped.failed == WitnessCheck::Failed::Normal);
        CHECK(flipped.normal == doctest::Approx(3.0));
        CHECK(checkWitness(a, b, pA, pB, 1.001 * n, 0.5, tight()).failed == WitnessCheck::Failed::NotUnit);
        CHECK(checkWitness(a, b, Vec3(NAN, 0, 0), pB, n, 0.5, tight()).failed == WitnessCheck::Failed::NotFinite);
    }

    TEST_CASE("separated boxes: s = -distance, the separating axis passes, a tilted one is flagged") {
        const WitnessBody a = WitnessBody::polytope(box(Vec3::Zero(), Vec3(1, 1, 1)));
        const WitnessBody b = WitnessBody::polytope(box(Vec3(3, 0.5, 0), Vec3(1, 1, 1)));
        const Vec3 n = Vec3::UnitX();
        CHECK(checkWitness(a, b, Vec3(1, 0.5, 0), Vec3(2, 0.5, 0), n, -1.0, tight()).ok());
        // a closest pair on the wrong features: pointB on B but not facing A (offset fails)
        CHECK(checkWitness(a, b, Vec3(1, 0.5, 0), Vec3(2.5, 0.5, 0), n, -1.0, tight()).failed ==
              WitnessCheck::Failed::Offset);
        const Vec3 nr = rotatedZ(n, 1e-3);
        // pointB = pointA + 1 n' lies 5e-7 outside B's face: bodies judged to 1e-6 here
        const WitnessCheck tilt =
            checkWitness(a, b, Vec3(1, 0.5, 0), Vec3(1, 0.5, 0) + 1.0 * nr, nr, -1.0, looseBodies(1e-6));
        CHECK(tilt.failed == WitnessCheck::Failed::Normal);
        // h(n') = h_A(n') + h_B(-n') = (cos + sin) + (-2 cos + 0.5 sin)
        CHECK(tilt.normal == doctest::Approx(std::abs(-std::cos(1e-3) + 1.5 * std::sin(1e-3) + 1.0)));
    }

    TEST_CASE("tied least-overlap directions: each tied axis passes, their bisector does not") {
        // A - B overlaps the origin by 0.5 along x and along y, by 1.5 along z.
        const WitnessBody a = WitnessBody::polytope(box(Vec3::Zero(), Vec3(1, 1, 1)));
        const WitnessBody b = WitnessBody::polytope(box(Vec3(1.5, 1.5, 0.5), Vec3(1, 1, 1)));
        const Vec3 p(1, 1, 0.5);  // a corner region common to both
        CHECK(checkWitness(a, b, p, p - 0.5 * Vec3::UnitX(), Vec3::UnitX(), 0.5, tight()).ok());
        CHECK(checkWitness(a, b, p, p - 0.5 * Vec3::UnitY(), Vec3::UnitY(), 0.5, tight()).ok());
        const Vec3 diag = Vec3(1, 1, 0).normalized();
        // along the bisector h = sqrt(2) * 0.5 + ... > 0.5: not a least-overlap direction
        CHECK(checkWitness(a, b, p, p - 0.5 * diag, diag, 0.5, tight()).failed == WitnessCheck::Failed::Normal);
    }

    TEST_CASE("sphere against capsule: rounded bodies (core + radius)") {
        const WitnessBody a = WitnessBody::rounded({Vec3::Zero()}, 1.0);
        const WitnessBody b = WitnessBody::rounded({Vec3(1.5, -1, 0), Vec3(1.5, 1, 0)}, 0.25);
        CHECK_FALSE(b.solid());
        const Vec3 n = Vec3::UnitX();
        // apart by 0.25
        CHECK(checkWitness(a, b, Vec3(1, 0, 0), Vec3(1.25, 0, 0), n, -0.25, tight()).ok());
        const WitnessCheck off = checkWitness(a, b, Vec3(1, 0, 0), Vec3(1.25, 0, 0.3), n, -0.25, tight(1e-9));
        CHECK(off.failed == WitnessCheck::Failed::PointBOffBody);
        CHECK(off.pointBOff == doctest::Approx(std::sqrt(0.25 * 0.25 + 0.09) - 0.25));
        // pointA inside the sphere but not on its surface: on the body, the offset check fails
        CHECK(checkWitness(a, b, Vec3(0.9, 0, 0), Vec3(1.25, 0, 0), n, -0.25, tight()).failed ==
              WitnessCheck::Failed::Offset);
        // overlapping by 0.25 (capsule core at x = 1), normal tilted: flagged
        const WitnessBody c = WitnessBody::rounded({Vec3(1, -1, 0), Vec3(1, 1, 0)}, 0.25);
        CHECK(checkWitness(a, c, Vec3(1, 0, 0), Vec3(0.75, 0, 0), n, 0.25, tight()).ok());
        const Vec3 nr = rotatedZ(n, 0.05);
        // pointB = 0.75 n' lies 9.4e-4 outside the capsule: bodies judged to 1e-2 here
        const WitnessCheck tilt = checkWitness(a, c, nr, nr - 0.25 * nr, nr, 0.25, looseBodies(1e-2));
        CHECK(tilt.failed == WitnessCheck::Failed::Normal);
        CHECK(tilt.normal == doctest::Approx(1.0 - std::cos(0.05) + std::sin(0.05)));
    }

    TEST_CASE("a flat body (a triangle) and a point set with duplicates and interior points") {
        const WitnessBody tri = WitnessBody::polytope({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
        CHECK_FALSE(tri.solid());
        CHECK(tri.signedDistance(Vec3(0.25, 0.25, 0)) <= 1e-18L);
        CHECK(double(tri.signedDistance(Vec3(0.25, 0.25, 1e-3))) == doctest::Approx(1e-3));
        CHECK(double(tri.signedDistance(Vec3(1, 1, 0))) == doctest::Approx(std::sqrt(0.5)));
        std::vector<Vec3> v = box(Vec3::Zero(), Vec3(1, 2, 3));
        v.push_back(v[0]);
        v.push_back(Vec3(0.1, 0.2, 0.3));
        const WitnessBody b = WitnessBody::polytope(v);
        CHECK(b.solid());
        CHECK(double(b.signedDistance(Vec3(0, 0, 0))) == doctest::Approx(-1.0));
        CHECK(double(b.signedDistance(Vec3(0, 2.5, 0))) == doctest::Approx(0.5));
    }

    TEST_CASE("1e9 from the origin, rotated: the rounded right answer passes 8 u M, a 1e-6 error does not") {
        const Quat q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
        const Vec3 o(1e9, -2e9, 3e8);
        const WitnessBody a = WitnessBody::polytope(box(Vec3::Zero(), Vec3(1, 1, 1), q, o));
        const WitnessBody b = WitnessBody::polytope(box(Vec3(1.5, 0, 0), Vec3(1, 1, 1), q, o));
        const Vec3 n = q * Vec3::UnitX();
        const Vec3 pA = o + q * Vec3(1, 0.2, 0.3), pB = o + q * Vec3(0.5, 0.2, 0.3);
        const double tol = 8 * 0x1p-53 * 2e9 + 1e-9;
        CHECK(checkWitness(a, b, pA, pB, n, 0.5, tight(tol)).ok());
        const Vec3 away = o + q * Vec3(1 + 1e-5, 0.2, 0.3);
        CHECK(checkWitness(a, b, away, away - 0.5 * n, n, 0.5, tight(tol)).failed ==
              WitnessCheck::Failed::PointAOffBody);
        const Vec3 nr = q * rotatedZ(Vec3::UnitX(), 1e-4);
        CHECK(checkWitness(a, b, pA, pA - 0.5 * nr, nr, 0.5, tight(tol)).failed == WitnessCheck::Failed::Normal);
    }

    TEST_CASE("ray hits: the first contact passes, and a later point, the exit, a wrong normal are flagged") {
        const WitnessBody b = WitnessBody::polytope(box(Vec3::Zero(), Vec3(1, 1, 1)));
        const Vec3 o(-3, 0, 0), d(1, 0, 0);
        CHECK(double(b.firstContact(o, d, 10)) == doctest::Approx(2.0));
        CHECK(checkRayHit(b, o, d, 2.0, Vec3(-1, 0, 0), Vec3(-1, 0, 0), rayTight()).ok());
        // a point inside, on the ray: off the surface
        const RayHitCheck inside = checkRayHit(b, o, d, 2.5, Vec3(-0.5, 0, 0), Vec3(-1, 0, 0), rayTight());
        CHECK(inside.failed == RayHitCheck::Failed::PointOffSurface);
        CHECK(inside.offSurface == doctest::Approx(0.5));
        // the exit point: on the ray and the surface, not the first contact
        const RayHitCheck exit = checkRayHit(b, o, d, 4.0, Vec3(1, 0, 0), Vec3(1, 0, 0), rayTight());
        CHECK(exit.failed == RayHitCheck::Failed::NotFirstContact);
        CHECK(exit.earlier == doctest::Approx(2.0));
        // a point off the ray
        CHECK(checkRayHit(b, o, d, 2.0, Vec3(-1, 0.5, 0), Vec3(-1, 0, 0), rayTight()).failed ==
              RayHitCheck::Failed::PointOffRay);
        // normals: tangent to the wrong face, facing away, not unit
        const RayHitCheck side = checkRayHit(b, o, d, 2.0, Vec3(-1, 0, 0), Vec3(0, 1, 0), rayTight());
        CHECK(side.failed == RayHitCheck::Failed::Normal);
        CHECK(side.support == doctest::Approx(1.0));
        CHECK(checkRayHit(b, o, d, 2.0, Vec3(-1, 0, 0), Vec3(1, 0, 0), rayTight()).failed ==
              RayHitCheck::Failed::Normal);
        CHECK(checkRayHit(b, o, d, 2.0, Vec3(-1, 0, 0), Vec3(-1.1, 0, 0), rayTight()).failed ==
              RayHitCheck::Failed::NotUnit);
        // a ray that misses, reported as a hit
        const RayHitCheck miss = checkRayHit(b, Vec3(-3, 2, 0), d, 3.0, Vec3(0, 2, 0), Vec3(0, 1, 0), rayTight());
        CHECK_FALSE(miss.ok());
        CHECK(miss.earlier == INFINITY);
    }

    TEST_CASE("rays in a face plane: the graze enters at the edge, either face's normal is right") {
        const WitnessBody b = WitnessBody::polytope(box(Vec3::Zero(), Vec3(1, 1, 1)));
        const Vec3 o(-3, 0.25, 1), d(2, 0, 0);  // in the plane z = 1 of the top face
        CHECK(double(b.firstContact(o, d, 10)) == doctest::Approx(1.0));
        CHECK(checkRayHit(b, o, d, 1.0, Vec3(-1, 0.25, 1), Vec3(-1, 0, 0), rayTight()).ok());
        CHECK(checkRayHit(b, o, d, 1.0, Vec3(-1, 0.25, 1), Vec3(0, 0, 1), rayTight()).ok());
        CHECK(checkRayHit(b, o, d, 1.0, Vec3(-1, 0.25, 1), Vec3(-1, 0, 1).normalized(), rayTight()).ok());
        // the point halfway along the face: on the surface, but after the entry
        CHECK(checkRayHit(b, o, d, 1.5, Vec3(0, 0.25, 1), Vec3(0, 0, 1), rayTight()).failed ==
              RayHitCheck::Failed::NotFirstContact);
        // just above the plane: no contact at all
        CHECK(b.firstContact(Vec3(-3, 0.25, 1 + 1e-9), d, 10) < 0);
    }

    TEST_CASE("a ray against a sphere (a rounded body: first contact by root finding)") {
        const WitnessBody s = WitnessBody::rounded({Vec3::Zero()}, 1.0);
        const Vec3 o(-3, 0.5, 0), d(1, 0, 0);
        const double t = 3 - std::sqrt(0.75);
        const Vec3 p = o + t * d;
        CHECK(double(s.firstContact(o, d, 10)) == doctest::Approx(t).epsilon(1e-14));
        CHECK(checkRayHit(s, o, d, t, p, p.normalized(), rayTight(1e-12)).ok());
        CHECK(checkRayHit(s, o, d, t, p, Vec3(-1, 0, 0), rayTight(1e-12)).failed == RayHitCheck::Failed::Normal);
        const double t2 = 3 + std::sqrt(0.75);
        // the exit: not the first contact, and its normal faces away from the ray
        const RayHitCheck exit = checkRayHit(s, o, d, t2, o + t2 * d, (o + t2 * d).normalized(), rayTight(1e-12));
        CHECK(exit.failed == RayHitCheck::Failed::NotFirstContact);
        CHECK(exit.support == doctest::Approx(std::sqrt(0.75) * (o + t2 * d - o).norm()));
    }
}
