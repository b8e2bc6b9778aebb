// timeOfImpactQuery where the motion dwarfs the shapes (|motion| / size up to 1e300), and a relative
// path that slides along a face of the Minkowski difference within rounding
// (/work/shared/reproducers/exact-2026-11-29/toi_large_motion.jsonl, toi_sliding_late.jsonl).
// Oracles: the closed form of boxes and spheres moving along an axis, with the gap at t and just
// before it evaluated in long double; the reproducer's exact t for the slide.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/query/cast.h"

using namespace cdlab;

namespace {

using LD = long double;

// Box [0,1]^3 moving by (m, 0, 0) against the box [5,6]×[0,1]^2: the x gap at time t (long double).
LD boxGap(LD t, LD m) { return LD(5) - (LD(1) + t * m); }
// Unit spheres at 0 and (5, 0, 0), the first moving by (m, 0, 0).
LD sphereGap(LD t, LD m) { return std::fabs(LD(5) - t * m) - LD(2); }

void checkTouching(const ImpactQueryResult& r, double t, LD (*gap)(LD, LD), double m) {
    REQUIRE(r.status == PairStatus::Ok);
    REQUIRE(r.result.hit);
    CHECK_FALSE(r.result.initiallyOverlapping);
    CHECK(std::fabs(double(gap(LD(r.result.t), LD(m)))) <= 1e-9);  // touching at t
    CHECK(gap(LD(r.result.t) * (LD(1) - LD(1e-9)), LD(m)) > 0);     // apart just before
    CHECK(std::fabs(r.result.t - t) <= 1e-12 * t);
    CHECK((r.result.normal - Vec3(1, 0, 0)).norm() <= 1e-12);
    CHECK((r.result.pointA - r.result.pointB).norm() <= 1e-9);
}

using V = Eigen::Matrix<long double, 3, 1>;

// The largest separating-axis gap of two point sets' hulls at time t, in long double: the axes are
// the normals of every triple of either set and the cross products of every pair of edge directions
// (a complete set for polytopes: > 0 exactly when the hulls are apart, and at most their distance).
long double satGap(const std::vector<Vec3>& a, const Vec3& ma, const std::vector<Vec3>& b, const Vec3& mb, long double t) {
    std::vector<V> pa, pb;
    for (const Vec3& v : a) pa.push_back(v.cast<long double>() + t * ma.cast<long double>());
    for (const Vec3& v : b) pb.push_back(v.cast<long double>() + t * mb.cast<long double>());
    std::vector<V> axes, da, db;
    for (const auto* p : {&pa, &pb}) {
        const std::vector<V>& q = *p;
        for (std::size_t i = 0; i < q.size(); ++i)
            for (std::size_t j = i + 1; j < q.size(); ++j) {
                (p == &pa ? da : db).push_back(q[j] - q[i]);
                for (std::size_t k = j + 1; k < q.size(); ++k) axes.push_back((q[j] - q[i]).cross(q[k] - q[i]));
            }
    }
    for (const V& x : da)
        for (const V& y : db) axes.push_back(x.cross(y));
    long double best = -INFINITY;
    for (V n : axes) {
        const long double len = n.norm();
        if (!(len > 0)) continue;
        n /= len;
        for (int side = 0; side < 2; ++side, n = -n) {
            long double hiA = -INFINITY, loB = INFINITY;
            for (const V& v : pa) hiA = std::max(hiA, n.dot(v));
            for (const V& v : pb) loB = std::min(loB, n.dot(v));
            best = std::max(best, loB - hiA);
        }
    }
    return best;
}

}  // namespace

TEST_CASE("time of impact: boxes with |motion| / size from 1e81 to 1e300 touch on the face x = 5") {
    for (double m : {1e81, 1e90, 1e120, 1e160, 1e170, 1e300}) {
        CAPTURE(m);
        const ImpactQueryResult r = timeOfImpactQuery(QueryShape::aabb(Vec3(0, 0, 0), Vec3(1, 1, 1)), Vec3(m, 0, 0),
                                                      QueryShape::aabb(Vec3(5, 0, 0), Vec3(6, 1, 1)), Vec3::Zero());
        checkTouching(r, double(LD(4) / LD(m)), boxGap, m);
        CHECK(std::fabs(r.result.pointA.x() - 5) <= 1e-12);
        // Both points on the touching face square [0,1]^2 (they were (5,0,0) and (5,1,1), then interior).
        for (const Vec3& p : {r.result.pointA, r.result.pointB})
            for (int i = 1; i < 3; ++i) CHECK((p[i] >= -1e-12 && p[i] <= 1 + 1e-12));
    }
}

TEST_CASE("time of impact: spheres with |motion| / size from 1e81 to 1e300 touch at (4, 0, 0)") {
    for (double m : {1e81, 1e160, 1e200, 1e300}) {
        CAPTURE(m);
        const ImpactQueryResult r = timeOfImpactQuery(QueryShape::sphere(Vec3(0, 0, 0), 1), Vec3(m, 0, 0),
                                                      QueryShape::sphere(Vec3(5, 0, 0), 1), Vec3::Zero());
        checkTouching(r, double(LD(3) / LD(m)), sphereGap, m);
        CHECK((r.result.pointA - Vec3(4, 0, 0)).norm() <= 1e-12);
        CHECK((r.result.pointB - Vec3(4, 0, 0)).norm() <= 1e-12);
    }
}

TEST_CASE("time of impact: the motion split between the bodies and moderate ratios keep the closed form") {
    for (double m : {0.5, 10.0, 1e6, 1e40}) {
        CAPTURE(m);
        // The same relative motion, half on each body.
        const ImpactQueryResult r = timeOfImpactQuery(QueryShape::aabb(Vec3(0, 0, 0), Vec3(1, 1, 1)), Vec3(m / 2, 0, 0),
                                                      QueryShape::aabb(Vec3(5, 0, 0), Vec3(6, 1, 1)), Vec3(-m / 2, 0, 0));
        if (m < 4) {
            CHECK_FALSE(r.result.hit);
            continue;
        }
        REQUIRE(r.result.hit);
        CHECK(std::fabs(r.result.t - 4 / m) <= 1e-12 * (4 / m));
        CHECK((r.result.pointA - r.result.pointB).norm() <= 1e-9);
        CHECK(std::fabs(double(LD(r.result.pointA.x()) - (LD(5) + LD(r.result.t) * LD(-m / 2)))) <= 1e-9 * (1 + m / 2 * r.result.t));
    }
}

TEST_CASE("time of impact: a path sliding along a face of A - B within rounding touches at its first contact") {
    const std::vector<Vec3> a = {{252.1119129259992, -5.247846647292025, -45.103336894633365},
                                 {-252.1119129259992, 5.247846647292025, 45.103336894633365},
                                 {-42.17807886471592, -107.03322233102203, 228.88242945536626},
                                 {-99.88335877055987, 58.70394051665994, 228.47194475733556}};
    const std::vector<Vec3> b = {{-519.256634285548, -86.70597958123368, 472.63364474476185},
                                 {-554.556718183753, 14.680509889396378, 472.3825387055388},
                                 {-481.42862161838207, -73.42241522468808, 518.1998005784967},
                                 {-577.2462670307054, -106.76271518006078, 526.6223443650193},
                                 {-612.5463509289102, -5.376225709430724, 526.3712383257963},
                                 {-539.4182543635394, -93.47915082351518, 572.1885001987541},
                                 {-574.7183382617442, 7.907338647114867, 571.9373941595312}};
    const Vec3 ma(-606.9859968797683, -209.93679517007558, 565.107642658437);
    const Vec3 mb(203.87376367671072, 70.51333109094435, -189.8077098705626);
    const ImpactQueryResult r = timeOfImpactQuery(QueryShape::polytope(a), ma, QueryShape::polytope(b), mb);
    REQUIRE(r.status == PairStatus::Ok);
    REQUIRE(r.result.hit);
    CHECK_FALSE(r.result.initiallyOverlapping);
    const double exact = 0.43272277707581674;  // the reproducer's exact t (it was 0.494)
    CHECK(std::fabs(r.result.t - exact) <= 1e-9 * exact);
    // Touching at t (the gap within the touch rule's scale, ~1e-9 of the size 1000) and apart just before.
    CHECK(std::fabs(double(satGap(a, ma, b, mb, r.result.t))) <= 1e-6);
    CHECK(satGap(a, ma, b, mb, LD(r.result.t) * (1 - LD(1e-9))) > 0);
    CHECK(satGap(a, ma, b, mb, LD(0.494)) <= 1e-6);  // the former answer: already touching long before
    CHECK((r.result.pointA - r.result.pointB).norm() <= 1e-9 * 1000);
    CHECK(std::fabs(r.result.normal.norm() - 1) <= 1e-12);
}

TEST_CASE("time of impact: a path inside a facet plane of B - A within 1e-17 answers its first touch, not later") {
    // cdlab stress "time of impact, sliding paths" #1013 (seed 1, tilt 0): the path lies ~1e-17 W
    // inside a facet plane of B − A; the cast on the rounded differences crossed the rounded facet
    // at t = 0.680312 — 12 units of travel (4 % of the size) after the bodies certainly overlap
    // (t = 0.633903032, the stress oracle: B − A's points exact in long double).
    const std::vector<Vec3> a = {{-134.5113563895549, -116.77060811636758, -149.99293494847424},
                                 {-143.9731943898005, -91.0426244941, -146.87471193630412},
                                 {-105.2293733070436, -83.73167489527759, -143.35176331126704},
                                 {-137.82019460298056, -100.66816561719497, -152.57103933463156},
                                 {-146.22625654918508, -103.87272674751792, -116.86728574327111},
                                 {-144.8084850358728, -105.5167362304889, -148.9479808273427},
                                 {-123.46021008509949, -76.4041592497114, -142.12466858219943}};
    const std::vector<Vec3> b = {{-22.23091561814164, -23.16034990514992, 13.59559320367594},
                                 {-31.472973858260694, -23.046923900767258, 3.7867899645346563},
                                 {-22.78872315837596, -18.99087608606373, 8.93552340046336},
                                 {-32.92667078235563, -33.07177605494945, -8.984054764217449}};
    const Vec3 ma(77.91785724687776, 125.15403109243812, 181.89279988291537);
    const Vec3 mb(-36.97387096023183, 39.497899617698344, -37.38671151806936);
    const ImpactQueryResult r = timeOfImpactQuery(QueryShape::polytope(a), ma, QueryShape::polytope(b), mb);
    REQUIRE(r.status == PairStatus::Ok);
    REQUIRE(r.result.hit);
    CHECK_FALSE(r.result.initiallyOverlapping);
    const double firstOverlap = 0.63390303219358328;
    CHECK(r.result.t <= firstOverlap + 1e-12);
    // Touching at t (within the touch rule's scale: 1e-13 of the size ~100, plus rounding) and apart before.
    CHECK(std::fabs(double(satGap(a, ma, b, mb, r.result.t))) <= 1e-9);
    CHECK(satGap(a, ma, b, mb, LD(r.result.t) * (1 - LD(1e-6))) > 0);
    CHECK((r.result.pointA - r.result.pointB).norm() <= 1e-9 * 100);
    CHECK(std::fabs(r.result.normal.norm() - 1) <= 1e-12);
}

TEST_CASE("time of impact: a path sliding at the band's rounding level along a facet answers where it first touches") {
    // cdlab stress "time of impact, sliding paths" #26565 (600 s): the path slides along a facet of
    // B − A at a distance of ~2.4 touching bands (4e-14: the rounding of coordinates ~500); Newton's
    // steps crept along the facet and the cast's t = 0.56918 stood, 0.0054 of travel (1.3e-6 L) after
    // the first touch, t = 0.549843858022 (an exact-rational oracle: the first t with a common point).
    const std::vector<Vec3> a = {{-505.4616405255627, -563.8951039750392, -167.11074829073019},
                                 {-505.476094867452, -563.8898281786217, -167.08904937341458},
                                 {-505.46843406045843, -563.9014263679114, -167.10984769969096},
                                 {-505.4591772287915, -563.906707952463, -167.088366990058},
                                 {-505.47400453643405, -563.8975042757635, -167.08502463096906},
                                 {-505.4501588523984, -563.8903770323478, -167.0872778887273},
                                 {-505.46670278076175, -563.8822443490698, -167.08077210859125}};
    const std::vector<Vec3> b = {{-505.40817604257956, -563.9287762982223, -166.9548968998852},
                                 {-505.4159062970916, -563.9409132650356, -166.95381238384948},
                                 {-505.4135655842221, -563.9406788837251, -166.95524998978615},
                                 {-505.3927240027362, -563.9383046696225, -166.93310561461547},
                                 {-505.4013150076402, -563.9151985210664, -166.93710289314117},
                                 {-505.4130252935519, -563.9407461029882, -166.94216840486675},
                                 {-505.3864183560457, -563.9189039188398, -166.93323814152552},
                                 {-505.3923132720747, -563.926070487304, -166.94572132998923}};
    const Vec3 ma(0.11162843426977276, -0.08999809849257724, 0.23754975469390238);
    const Vec3 mb(-0.004183959040649053, 0.0030983348977997806, 0.0006670344004794246);
    const ImpactQueryResult r = timeOfImpactQuery(QueryShape::polytope(a), ma, QueryShape::polytope(b), mb);
    REQUIRE(r.status == PairStatus::Ok);
    REQUIRE(r.result.hit);
    const double firstTouch = 0.549843858022;
    CHECK(std::fabs(r.result.t - firstTouch) <= 1e-9);
    CHECK(std::fabs(double(satGap(a, ma, b, mb, r.result.t))) <= 1e-12);
    CHECK((r.result.pointA - r.result.pointB).norm() <= 1e-9);
}

TEST_CASE("time of impact: a path grazing a facet at 3e-10 rad answers a touching t before the exact contact") {
    // cdlab stress "time of impact, sliding paths" #38204 (600 s): the path enters B − A through a
    // facet at 3.3e-10 rad, so the last 1 % of the distance (its rounding) spans 2e-4 of the path;
    // Newton's last step reached the cast's t, which crossed the rounded facet 2.8e-8 after the exact
    // first contact t0 = 0.5446588255950197 (an exact-rational oracle: the facets of B − A from the
    // input doubles). The answer is the first t within the touching band: before t0, apart by at most
    // 8 roundings of the coordinates (~228), and no earlier than where the path meets the facet's
    // plane (9.5e-3 before t0; the distance is 6e-5 at 1e-2 before).
    const std::vector<Vec3> a = {{21.601340273210862, 227.81393306460907, 163.52172111283696},
                                 {21.601799024673003, 227.81466578223916, 163.5285223131711},
                                 {21.585415569719494, 227.81036400928608, 163.53509351453496},
                                 {21.59755393189808, 227.8129889892566, 163.52159609497713}};
    const std::vector<Vec3> b = {{21.54920922806885, 227.90530700632044, 163.47314004521817},
                                 {21.52659351272781, 227.90431074408397, 163.47662389803273},
                                 {21.53851382841237, 227.90111906098116, 163.48112246296108},
                                 {21.523750193957785, 227.89209791936523, 163.4786649200113}};
    const Vec3 ma(-0.10625593428223276, 0.15090134723870333, -0.1524020841249903);
    const Vec3 mb(0.025553981992366328, -0.0032275481518557626, -0.07413564311221353);
    const ImpactQueryResult r = timeOfImpactQuery(QueryShape::polytope(a), ma, QueryShape::polytope(b), mb);
    REQUIRE(r.status == PairStatus::Ok);
    REQUIRE(r.result.hit);
    const double t0 = 0.5446588255950197;
    CHECK(r.result.t <= t0);
    CHECK(r.result.t >= t0 - 0.01);
    const long double gap = satGap(a, ma, b, mb, r.result.t);
    CHECK(gap >= 0);
    CHECK(double(gap) <= 8 * 0x1p-53 * 230 + 2e-14);  // 8 roundings of the moved coordinates + the band
    CHECK((r.result.pointA - r.result.pointB).norm() <= 1e-12);
}
