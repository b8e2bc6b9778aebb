// GJK / EPA on shapes with margins (core/gjk_epa/margins.h) against closed forms evaluated in long
// double, independent of GJK: sphere pairs (centre distance), capsule pairs (segment–segment
// distance by its critical points), rounded boxes against spheres (the clamped point, the nearest
// face), plus the degenerate cores (coincident centres, crossing and collinear segments) and bad radii.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/gjk_epa/margins.h"
#include "core/geometry/shapes.h"
#include "tests/random_vectors.h"

using namespace cdlab;

namespace {

using LD = long double;

struct LongVec {
    LD x, y, z;
};
LongVec lv(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
LongVec operator-(const LongVec& a, const LongVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
LongVec operator+(const LongVec& a, const LongVec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
LongVec operator*(LD s, const LongVec& a) { return {s * a.x, s * a.y, s * a.z}; }
LD dot(const LongVec& a, const LongVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
LD norm(const LongVec& a) { return std::sqrt(dot(a, a)); }

// Distance from p to segment [a, b].
LD pointSegment(const LongVec& p, const LongVec& a, const LongVec& b) {
    const LongVec e = b - a;
    const LD ee = dot(e, e);
    const LD t = ee > 0 ? std::clamp(dot(p - a, e) / ee, LD(0), LD(1)) : LD(0);
    return norm(p - (a + t * e));
}

// Segment–segment distance: the minimum is at an endpoint against the other segment, or at the
// interior critical point of |(a + s e) − (c + t f)|² when that lies inside both parameter ranges.
LD segmentSegment(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
    const LongVec a = lv(a0), b = lv(a1), c = lv(b0), d = lv(b1);
    LD best = std::min({pointSegment(a, c, d), pointSegment(b, c, d), pointSegment(c, a, b), pointSegment(d, a, b)});
    const LongVec e = b - a, f = d - c, r = a - c;
    const LD ee = dot(e, e), ff = dot(f, f), ef = dot(e, f), er = dot(e, r), fr = dot(f, r);
    const LD det = ee * ff - ef * ef;
    if (det > 1e-30L * ee * ff) {
        const LD s = (ef * fr - ff * er) / det, t = (ee * fr - ef * er) / det;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) best = std::min(best, norm((a + s * e) - (c + t * f)));
    }
    return best;
}

Transformed<SphereShape> sphere(const Vec3& centre, double radius) {
    Transformed<SphereShape> s;
    s.shape.radius = radius;
    s.transform.position = centre;
    return s;
}

Quat randomRotation(std::mt19937_64& rng) {
    std::normal_distribution<double> g(0.0, 1.0);
    return Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
}

using cdlab::test::randomVec;

// The answer's own consistency: unit normal, pointA − pointB = depth n (penetration) or the
// closest points `distance` apart along the axis (separated).
void checkPenetrationWitnesses(const EpaResult& r, double size) {
    REQUIRE(std::abs(r.normal.norm() - 1.0) <= 1e-14);
    CHECK((r.pointA - r.pointB - r.depth * r.normal).norm() <= 1e-13 * size);
}

}  // namespace

TEST_SUITE("gjk_epa/margins") {
    TEST_CASE("spheres: distance and depth = centre distance against the radii, witnesses on the spheres") {
        std::mt19937_64 rng(71);
        std::uniform_real_distribution<double> radius(0.05, 1.0);
        int separated = 0, overlapping = 0;
        for (int k = 0; k < 2000; ++k) {
            const double ra = radius(rng), rb = radius(rng);
            const Vec3 ca = randomVec(rng, 2.0), cb = ca + randomVec(rng, 1.5);
            const auto A = sphere(ca, ra), B = sphere(cb, rb);
            const LD centres = norm(lv(cb) - lv(ca));
            const double exact = double(centres - ra - rb);  // signed: < 0 overlapping
            CAPTURE(k);
            const GjkResult g = gjkDistanceWithMargins(A, B);
            REQUIRE(g.status != GjkStatus::InvalidInput);
            CHECK(g.iterations <= 3);  // point cores: GJK ends at once (the full sphere takes ~16)
            const EpaResult e = penetrationWithMargins(A, B);
            if (exact > 1e-12) {
                ++separated;
                REQUIRE(!g.intersect());
                CHECK(std::abs(g.distance - exact) <= 4e-16 * (centres + 2));
                CHECK(std::abs((g.pointA - ca).norm() - ra) <= 1e-15 * 4);
                CHECK(std::abs((g.pointB - cb).norm() - rb) <= 1e-15 * 4);
                CHECK(std::abs((g.pointB - g.pointA).norm() - g.distance) <= 1e-15 * 8);
                CHECK(e.status == EpaStatus::Separated);
            } else if (exact < -1e-12) {
                ++overlapping;
                CHECK(g.intersect());
                REQUIRE(e.status == EpaStatus::Penetrating);
                CHECK(std::abs(e.depth + exact) <= 4e-16 * (centres + 2));
                checkPenetrationWitnesses(e, 4.0);
                if (centres > 1e-9) {  // the normal along the centres, from A toward B
                    const Vec3 n = (cb - ca).normalized();
                    CHECK((e.normal - n).norm() <= 1e-14 / double(centres));
                }
                CHECK(std::abs((e.pointA - ca).norm() - ra) <= 1e-14);  // A's deepest point is on A
            }
        }
        CHECK(separated > 300);
        CHECK(overlapping > 300);
    }

    TEST_CASE("spheres with one centre: depth ra + rb along a unit normal") {
        for (const Vec3& c : {Vec3(0, 0, 0), Vec3(1e3, -2e3, 5), Vec3(0.25, 0.5, -0.75)}) {
            const EpaResult e = penetrationWithMargins(sphere(c, 0.3), sphere(c, 0.7));
            CAPTURE(c.transpose());
            REQUIRE(e.status == EpaStatus::Penetrating);
            CHECK(e.depth == doctest::Approx(1.0).epsilon(1e-15));
            checkPenetrationWitnesses(e, 1e3);
            CHECK(std::abs((e.pointA - c).norm() - 0.3) <= 1e-12);
        }
    }

    TEST_CASE("capsules: segment distance against the radii, crossing and collinear cores") {
        std::mt19937_64 rng(72);
        std::uniform_real_distribution<double> half(0.1, 1.0), radius(0.05, 0.5);
        int separated = 0, overlapping = 0, coresApart = 0;
        for (int k = 0; k < 3000; ++k) {
            Transformed<CapsuleShape> A, B;
            A.shape = CapsuleShape::alongY(half(rng), radius(rng));
            B.shape = CapsuleShape::alongY(half(rng), radius(rng));
            A.transform.rotation = randomRotation(rng);
            B.transform.rotation = randomRotation(rng);
            A.transform.position = randomVec(rng, 3.0);
            B.transform.position = A.transform.position + randomVec(rng, k % 2 ? 2.5 : 0.8);
            const Vec3 a0 = A.transform.apply(A.shape.a), a1 = A.transform.apply(A.shape.b);
            const Vec3 b0 = B.transform.apply(B.shape.a), b1 = B.transform.apply(B.shape.b);
            const LD seg = segmentSegment(a0, a1, b0, b1);
            const double radii = A.shape.radius + B.shape.radius;
            const double exact = double(seg - radii);
            CAPTURE(k);
            const GjkResult g = gjkDistanceWithMargins(A, B);
            const EpaResult e = penetrationWithMargins(A, B);
            REQUIRE(g.status != GjkStatus::InvalidInput);
            CHECK(g.iterations <= 6);  // segment cores (full support: ~17)
            if (exact > 1e-12) {
                ++separated;
                REQUIRE(!g.intersect());
                CHECK(std::abs(g.distance - exact) <= 1e-14);
                CHECK(e.status == EpaStatus::Separated);
            } else if (exact < -1e-12) {
                ++overlapping;
                coresApart += seg > 1e-9;
                REQUIRE(e.status == EpaStatus::Penetrating);
                if (seg > 1e-9) CHECK(std::abs(e.depth + exact) <= 1e-14);  // cores apart: rA + rB − seg
                checkPenetrationWitnesses(e, 8.0);
                // Translating B by depth along the normal leaves the capsules touching: the cores'
                // distance becomes rA + rB (the normal is the minimum translation when the cores are apart).
                const Vec3 shift = e.depth * e.normal;
                if (seg > 1e-9) CHECK(double(segmentSegment(a0, a1, b0 + shift, b1 + shift)) == doctest::Approx(radii).epsilon(1e-12));
            }
        }
        CHECK(separated > 500);
        CHECK(overlapping > 500);
        CHECK(coresApart > 300);

        // Crossing cores (distance 0): depth rA + rB along the normal of both axes.
        const Transformed<CapsuleShape> x{CapsuleShape{Vec3(-1, 0, 0), Vec3(1, 0, 0), 0.2}, Transform{}};
        const Transformed<CapsuleShape> y{CapsuleShape{Vec3(0, -1, 0), Vec3(0, 1, 0), 0.3}, Transform{}};
        const EpaResult crossing = penetrationWithMargins(x, y);
        REQUIRE(crossing.status == EpaStatus::Penetrating);
        CHECK(crossing.depth == doctest::Approx(0.5).epsilon(1e-14));
        CHECK(std::abs(std::abs(crossing.normal.z()) - 1.0) <= 1e-14);
        checkPenetrationWitnesses(crossing, 1.0);
        // Collinear overlapping cores: depth rA + rB along any normal perpendicular to them.
        const Transformed<CapsuleShape> z{CapsuleShape{Vec3(0.5, 0, 0), Vec3(3, 0, 0), 0.3}, Transform{}};
        const EpaResult collinear = penetrationWithMargins(x, z);
        REQUIRE(collinear.status == EpaStatus::Penetrating);
        CHECK(collinear.depth == doctest::Approx(0.5).epsilon(1e-14));
        CHECK(std::abs(collinear.normal.x()) <= 1e-14);
        checkPenetrationWitnesses(collinear, 1.0);
    }

    TEST_CASE("rounded box against a sphere: the clamped point outside, the nearest face inside") {
        std::mt19937_64 rng(73);
        std::uniform_real_distribution<double> half(0.2, 1.0), radius(0.02, 0.3);
        int outside = 0, inside = 0;
        for (int k = 0; k < 2000; ++k) {
            Transformed<RoundedShape<BoxShape>> box;
            box.shape.inner.halfExtents = Vec3(half(rng), half(rng), half(rng));
            box.shape.radius = radius(rng);
            box.transform.rotation = randomRotation(rng);
            box.transform.position = randomVec(rng, 1.0);
            const double rs = radius(rng);
            const Vec3 c = box.transform.position + randomVec(rng, 1.6);
            const auto S = sphere(c, rs);
            const Vec3 h = box.shape.inner.halfExtents;
            const Vec3 local = box.transform.applyInverse(c);  // the centre in the box frame
            const Vec3 clamped = local.cwiseMax(-h).cwiseMin(h);
            const double radii = box.shape.radius + rs;
            CAPTURE(k);
            const GjkResult g = gjkDistanceWithMargins(box, S);
            const EpaResult e = penetrationWithMargins(box, S);
            REQUIRE(g.status != GjkStatus::InvalidInput);
            if (clamped != local) {  // centre outside the box: distance to the clamped point
                const double outsideBy = double(norm(lv(local) - lv(clamped)));
                const double exact = outsideBy - radii;
                ++outside;
                if (exact > 1e-12) {
                    REQUIRE(!g.intersect());
                    CHECK(std::abs(g.distance - exact) <= 1e-14);
                } else if (exact < -1e-12) {
                    REQUIRE(e.status == EpaStatus::Penetrating);
                    CHECK(std::abs(e.depth + exact) <= 1e-14);
                    checkPenetrationWitnesses(e, 4.0);
                }
            } else {  // inside the box: out through the nearest face
                const double toFace = (h - local.cwiseAbs()).minCoeff();
                ++inside;
                REQUIRE(e.status == EpaStatus::Penetrating);
                CHECK(std::abs(e.depth - (toFace + radii)) <= 1e-14);
                checkPenetrationWitnesses(e, 4.0);
            }
        }
        CHECK(outside > 500);
        CHECK(inside > 100);
    }

    // Cores apart by 2.75e-14 .. 1e-11 (less than 1e-13 of the coordinates): the normal is the cores'
    // own axis, exact there. EPA, which needs a simplex holding the origin, would give depths
    // 3x .. 38000x too large and normals along a coordinate axis.
    TEST_CASE("cores apart by a hair: the cores' axis, not EPA") {
        const CapsuleShape A{Vec3(-0.087361662159125636, 0.12180682528121861, 0.064072713244759938),
                             Vec3(0.39644674898118304, -0.59631227169508572, 0.56430704220252648), 0.05};
        const CapsuleShape B{Vec3(0.17705241975889738, -0.27066423839308734, 0.33746399332504823),
                             Vec3(-0.65614398891109804, -0.71986314770682935, 0.6599606358668999), 0.05};
        const LD seg = segmentSegment(A.a, A.b, B.a, B.b);  // 2.75e-14
        REQUIRE(seg > 0);
        REQUIRE(seg < 1e-13);
        const EpaResult e = penetrationWithMargins(A, B);
        REQUIRE(e.status == EpaStatus::Penetrating);
        CHECK(std::abs(e.depth - double(0.1L - seg)) <= 1e-16);
        checkPenetrationWitnesses(e, 1.0);
        const Vec3 shift = e.depth * e.normal;  // B moved by depth along the normal: touching
        CHECK(std::abs(double(segmentSegment(A.a, A.b, B.a + shift, B.b + shift) - 0.1L)) <= 1e-15);

        const CapsuleShape C{Vec3(999.99705271591154, 299.98432632769652, -199.99490937250562),
                             Vec3(1000.0016520937114, 299.99603817449298, -200.00817940631822), 5e-8};
        const CapsuleShape D{Vec3(999.99784866559276, 299.98635313240908, -199.99720583074696),
                             Vec3(1000.0035890859751, 300.00097052784599, -200.0137679780386), 5e-8};
        const LD gap = segmentSegment(C.a, C.b, D.a, D.b);  // 9.95e-12
        const EpaResult f = penetrationWithMargins(C, D);
        REQUIRE(f.status == EpaStatus::Penetrating);
        CHECK(std::abs(f.depth - double(1e-7L - gap)) <= 1e-7 * 1e-5);  // the gap is known to ~1e-13 (coordinates 1e3)

        for (double offset : {0.0, 1e6}) {
            const EpaResult s = penetrationWithMargins(sphere(Vec3(offset, 0, 0), 5e-8), sphere(Vec3(offset, 5e-8, 0), 5e-8));
            CAPTURE(offset);
            REQUIRE(s.status == EpaStatus::Penetrating);
            CHECK(s.depth == doctest::Approx(5e-8).epsilon(1e-9));
            CHECK(s.normal.y() == doctest::Approx(1.0).epsilon(1e-12));
        }
    }

    TEST_CASE("nearly parallel cores crossing: the deepest points where they cross, on each capsule") {
        // Cores 5.6e-18 apart at an angle of ~1e-2: EPA's start on their flat difference is blown up,
        // and its witnesses would put pointA 0.39 off A; the witnesses lie on each capsule.
        const CapsuleShape A{Vec3(-0.06384617321017472, -0.042449289430044015, -0.0775290882964929),
                             Vec3(1.2731867605939553, 0.36920813999860513, -0.31357009551208964), 0.1};
        const CapsuleShape B{Vec3(-0.5154235067889756, -0.18152815246451445, 0.0021401574709631332),
                             Vec3(1.3605382611563082, 0.39618603910536876, -0.32888983667686805), 0.05};
        const EpaResult e = penetrationWithMargins(A, B);
        REQUIRE(e.status == EpaStatus::Penetrating);
        CHECK(e.depth == doctest::Approx(0.15).epsilon(1e-14));
        checkPenetrationWitnesses(e, 2.0);
        CHECK(double(pointSegment(lv(e.pointA), lv(A.a), lv(A.b))) == doctest::Approx(0.1).epsilon(1e-12));
        CHECK(double(pointSegment(lv(e.pointB), lv(B.a), lv(B.b))) == doctest::Approx(0.05).epsilon(1e-12));
    }

    TEST_CASE("nearly parallel capsules: pointA - pointB = -distance * axis") {
        // Cores parallel to 8.6e-9 rad (stress "spheres and capsules" #29372): A − B's cores span a
        // parallelogram 1e-8 wide whose face normal GJK's edge stop took for the axis, 0.95e-9 rad
        // from the edge's own: the witnesses' difference left −distance · axis by 1.5e-9 (> 1e-9 L).
        const CapsuleShape A{Vec3(0.2475999184331345, -0.55124933310580659, -0.434122679682443),
                             Vec3(-0.2475999184331345, 0.55124933310580659, 0.434122679682443), 0.67177968178219383};
        const CapsuleShape B{Vec3(-0.024552492472814436, 0.98475469865844156, -1.1379827912171283),
                             Vec3(-0.42487730459449458, 1.8760263646059805, -0.43608399386853336), 0.80898665768103684};
        const GjkResult g = gjkDistanceWithMargins(A, B);
        REQUIRE(g.status == GjkStatus::Separated);
        const LD seg = segmentSegment(A.a, A.b, B.a, B.b);
        CHECK(std::abs(g.distance - double(seg - LD(A.radius) - LD(B.radius))) <= 1e-15);
        const LongVec off = lv(g.pointA) - lv(g.pointB) + LD(g.distance) * lv(g.separatingAxis);
        CHECK(double(norm(off)) <= 1e-12);
        CHECK(double(pointSegment(lv(g.pointA), lv(A.a), lv(A.b))) == doctest::Approx(A.radius).epsilon(1e-13));
        CHECK(double(pointSegment(lv(g.pointB), lv(B.a), lv(B.b))) == doctest::Approx(B.radius).epsilon(1e-13));
    }

    TEST_CASE("no margin: the plain queries, bad radii: invalid input") {
        const PolytopeShape a({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)});
        const PolytopeShape b({Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(2, 1, 0), Vec3(2, 0, 1)});
        const GjkResult plain = gjkDistance(a, b), withMargins = gjkDistanceWithMargins(a, b);
        CHECK(withMargins.distance == plain.distance);
        CHECK(withMargins.pointA == plain.pointA);
        CHECK(penetrationWithMargins(a, b).status == EpaStatus::Separated);
        CHECK(gjkDistanceWithMargins(sphere(Vec3::Zero(), -1.0), sphere(Vec3(3, 0, 0), 1.0)).status ==
              GjkStatus::InvalidInput);
        CHECK(penetrationWithMargins(sphere(Vec3::Zero(), NAN), sphere(Vec3(3, 0, 0), 1.0)).status ==
              EpaStatus::InvalidInput);
        CHECK(penetrationWithMargins(sphere(Vec3(NAN, 0, 0), 1.0), sphere(Vec3(3, 0, 0), 1.0)).status ==
              EpaStatus::InvalidInput);
    }
}
