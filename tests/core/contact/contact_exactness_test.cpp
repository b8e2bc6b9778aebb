// Issue 41: the contact of two polytopes against an independent oracle — the least overlap of the
// projections over every face normal and every edge cross product, computed by brute force in long
// double from the input vertices (every vertex triple and every pair of vertex differences: a
// superset of the SAT's axes, each a valid direction, so the minimum is the least overlap). The
// shapes are the reproducers of /work/shared/reproducers/exact-2026-11-29/contact_*.jsonl:
//   (b) nearly parallel edges whose axis is the least overlap (the double cross product's direction
//       was off by ~1e-16 / sine: a face axis at 2.1e6 x the depth was answered);
//   (c) an edge axis answered with depth 0 and the normal reversed (a needle, nearly parallel edges);
//   (d) manifold points with point_a − point_b ≠ depth_i·n (closest points of nearly parallel edges);
//   (a) the face preference: least overlap <= depth <= least overlap · (1 + faceBiasRelative) + tol;
//   (e) a 2e-9 cube beside a 1550-size body answers (its hull's tolerance was relative to the frame
//       origin, A's first vertex ~1e3 away, not to the cube).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/contact/contact_sat.h"
#include "core/query/contact.h"

using namespace cdlab;

namespace contact_exactness {

using LVec = std::array<long double, 3>;

LVec lsub(const Vec3& p, const Vec3& q) { return {(long double)p.x() - q.x(), (long double)p.y() - q.y(), (long double)p.z() - q.z()}; }
LVec lcross(const LVec& u, const LVec& w) {
    return {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
}
long double ldot(const LVec& u, const Vec3& p) { return u[0] * p.x() + u[1] * p.y() + u[2] * p.z(); }
long double lnorm(const LVec& u) { return std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]); }

// h_A(u) + h_B(-u): the overlap of the projections on unit u (A toward B), long double.
long double overlapAlong(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const LVec& u) {
    long double maxA = -INFINITY, minB = INFINITY;
    for (const Vec3& p : a) maxA = std::max(maxA, ldot(u, p));
    for (const Vec3& p : b) minB = std::min(minB, ldot(u, p));
    return maxA - minB;
}

// The least overlap over every triple normal of each body and every cross product of a vertex
// difference of A with one of B, both orientations (negative: separated).
long double leastOverlap(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    std::vector<LVec> axes;
    for (const std::vector<Vec3>* s : {&a, &b}) {
        const std::vector<Vec3>& v = *s;
        for (size_t i = 0; i < v.size(); ++i)
            for (size_t j = i + 1; j < v.size(); ++j)
                for (size_t k = j + 1; k < v.size(); ++k) axes.push_back(lcross(lsub(v[j], v[i]), lsub(v[k], v[i])));
    }
    for (size_t i = 0; i < a.size(); ++i)
        for (size_t j = i + 1; j < a.size(); ++j)
            for (size_t k = 0; k < b.size(); ++k)
                for (size_t l = k + 1; l < b.size(); ++l) axes.push_back(lcross(lsub(a[j], a[i]), lsub(b[l], b[k])));
    long double best = INFINITY;
    for (LVec u : axes) {
        const long double len = lnorm(u);
        if (!(len > 0)) continue;
        for (long double& x : u) x /= len;
        const LVec m = {-u[0], -u[1], -u[2]};
        best = std::min({best, overlapAlong(a, b, u), overlapAlong(a, b, m)});
    }
    return best;
}

double diagonal(const std::vector<Vec3>& v) {
    Vec3 lo = v[0], hi = v[0];
    for (const Vec3& p : v) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    return (hi - lo).norm();
}

// The contract of a colliding polytope pair (core/contact/contact_sat.h, step 3): the depth within
// [least, least · (1 + faceBiasRelative) + tol], realised by the normal, every point pair
// pointA − pointB = depth_i · n.
void checkContract(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    const ContactResult r = contactQuery(QueryShape::polytope(a), QueryShape::polytope(b));
    REQUIRE(r.status == ContactStatus::Ok);
    REQUIRE(r.colliding);
    const double tol = 1e-9 * std::max(diagonal(a), diagonal(b));
    const long double least = leastOverlap(a, b);
    const double f = SatContactOptions{}.faceBiasRelative;
    INFO("depth ", r.depth, " least overlap ", double(least), " tol ", tol);
    CHECK(r.depth >= double(least) - tol);
    CHECK(r.depth <= double(least) * (1 + f) + tol);
    const long double alongNormal = overlapAlong(a, b, LVec{r.normal.x(), r.normal.y(), r.normal.z()});
    CHECK(std::abs(double(alongNormal) - r.depth) <= tol);
    for (const ContactPoint& p : r.points) {
        INFO("point depth ", p.depth);
        CHECK((p.pointA - p.pointB - p.depth * r.normal).norm() <= tol);
        CHECK(p.depth <= r.depth + tol);
    }
}

}  // namespace contact_exactness

using namespace contact_exactness;

TEST_SUITE("contact_exactness") {
    TEST_CASE("(b) nearly parallel edges: the edge axis of least overlap, not a face axis at 2.1e6 x the depth") {
        // contact_parallel_edges_depth: least overlap 5.4e-14 along an edge axis (sine ~2e-8); the
        // answer was a face axis, depth 1.15e-7.
        const std::vector<Vec3> a = {{4.896728157947427, -3.3912549077685887, -5.769056534492141},
                                     {-13.174938485751449, 9.124373097129016, 15.5219898418676},
                                     {9.526460410233012, 19.952201676330628, 3.4679759344415793},
                                     {-13.042159302216158, 10.349276621113606, -13.039378331959005}};
        const std::vector<Vec3> b = {{7.876219741521683, -5.454717378730533, -9.279329848214633},
                                     {-12.12876233512088, 8.399838102929095, 14.289442150130334},
                                     {12.156203237187372, -13.487363987270504, 15.929385322368917},
                                     {-11.46666377088812, -17.99053244614091, -1.4862432586570091}};
        checkContract(a, b);
        const ContactResult r = contactQuery(QueryShape::polytope(a), QueryShape::polytope(b));
        CHECK(r.depth <= 4e-9);  // 1.15e-7 before
    }

    TEST_CASE("(c) a needle against a tetrahedron far from the origin: depth and normal of the least overlap") {
        // contact_edge_edge_depth0: answered edge-edge, depth 0, normal reversed (overlap 6.53 along
        // it); least overlap 1.9e-3.
        const std::vector<Vec3> a = {{84033.84426320039, -99495.55749702104, -37915.41394470847},
                                     {84038.09133883212, -99494.68854034902, -37920.30611036106},
                                     {84035.0983481128, -99495.30090977626, -37916.85851308228},
                                     {84035.60977680967, -99495.1962708563, -37917.44762289204}};
        const std::vector<Vec3> b = {{84034.00048675867, -99492.36932801151, -37914.712031845396},
                                     {84037.93222539105, -99497.87603933163, -37921.010413030046},
                                     {84038.2475623904, -99491.50037133948, -37919.60419749798},
                                     {84043.20628531542, -99492.65006427585, -37915.50355181749}};
        checkContract(a, b);
        const ContactResult r = contactQuery(QueryShape::polytope(a), QueryShape::polytope(b));
        CHECK(r.normal.dot(Vec3(0.7586188205028218, -0.17588776636872702, 0.6273443861394853)) > 0.999999);
    }

    TEST_CASE("(d) touching nearly parallel edges: point_a − point_b = depth_i · n") {
        // contact_points_pair: point_a − point_b was off depth_i·n by 3.4e-4.
        const std::vector<Vec3> a = {{-1914.928685844128, -7112.9745798306985, 31.973684848650024},
                                     {1817.4681653827552, 6750.9589028483315, -30.346380401516683},
                                     {5830.618380008566, 475.8736695359286, 10172.958307525672},
                                     {-10956.71916733277, 1354.855638022748, 2315.08654802126}};
        const std::vector<Vec3> b = {{-2020.228725523976, -7504.108569921136, 33.73171450743868},
                                     {2030.0371663062135, 7540.541102220244, -33.89539559553708},
                                     {9632.284068095381, -6949.887517963165, -2694.3361546227798},
                                     {-5852.337831384487, 140.94318830243867, -9758.125769967037}};
        checkContract(a, b);
    }

    TEST_CASE("(a) the face preference: depth within least overlap · (1 + faceBiasRelative) + tol") {
        // contact_face_bias: a box and a wedge; the face axis (0.2) is kept over the least overlap
        // (0.199007 along the wedge's tilted face): within the 2 % bound.
        std::vector<Vec3> box;
        for (int i = 0; i < 8; ++i) box.push_back(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
        const std::vector<Vec3> wedge = {{-1, -1, 0.8}, {1, -1, 1.0}, {-1, 1, 0.8}, {1, 1, 1.0},
                                         {-1, -1, 3},   {1, -1, 3},   {-1, 1, 3},   {1, 1, 3}};
        checkContract(box, wedge);
        const ContactResult r = contactQuery(QueryShape::polytope(box), QueryShape::polytope(wedge));
        CHECK(r.axis == SatAxisKind::FaceA);
        CHECK(r.depth > double(leastOverlap(box, wedge)) + 1e-4);  // the preference, not the least overlap
    }

    TEST_CASE("(e) a 2e-9 cube beside a 1550-size body answers, with the distance") {
        // contact_tiny_cube_refused: "its convex hull failed" — the hull's tolerance was 4096 ulps of
        // the cube's coordinates in a frame whose origin was a vertex of A, ~1e3 away.
        const std::vector<Vec3> a = {{1192.2611122399185, 560.6023306131739, -783.9047031884043},
                                     {338.6274091970301, 1195.8704793447503, -167.1981340531562},
                                     {162.91552540415205, 443.38868693233877, 957.3390619705461},
                                     {-856.9072834896876, 1550.228751071609, -1194.8392259070345},
                                     {264.97053582221525, 124.58940480235432, -174.21658992977368},
                                     {-716.6935658281724, -336.99000916195735, 471.2218489815651}};
        std::vector<Vec3> cube;
        for (int i = 0; i < 8; ++i) cube.push_back(Vec3(i & 4 ? 1e-9 : -1e-9, i & 2 ? 1e-9 : -1e-9, i & 1 ? 1e-9 : -1e-9));
        const ContactResult r = contactQuery(QueryShape::polytope(a), QueryShape::polytope(cube));
        REQUIRE(r.status == ContactStatus::Ok);
        CHECK_FALSE(r.colliding);
        CHECK(std::abs(r.distance - 1.1670682512434476e-06) <= 1e-9 * 3000);
    }

    TEST_CASE("(e) a needle 1e-12 of its length wide is a solid, as for every other op") {
        // contact_needle_refused: "all 4 points lie in one plane within eps = 9.04e-13" (4096 ulps of
        // the needle's own coordinates and diagonal); its vertices lie ~2e-13 off each other's plane.
        const std::vector<Vec3> a = {{0.0, 0.0, 0.0},
                                     {-0.11340471236568012, 0.2272825786766557, -0.09021370630661538},
                                     {-0.07207777772528108, 0.14445628268034696, -0.05733803591898995},
                                     {-0.07548258733536625, 0.15128010764994432, -0.060046569697702085}};
        const std::vector<Vec3> b = {{0.10868463068080857, 0.024072740203421237, -0.07597553733559315},
                                     {0.22069573544629928, 0.1607517594739946, 0.12756529459421295},
                                     {-0.10868463068036159, -0.024072740202875843, 0.07597553733640533},
                                     {0.0033264740851291215, 0.11260627906769752, 0.27951636926621143},
                                     {-0.004720081684871552, 0.2513553188800769, -0.1661892436422085},
                                     {0.10729102308061916, 0.3880343381506503, 0.037351588287597576},
                                     {-0.22208934304604172, 0.20320983847377985, -0.014238168970210048},
                                     {-0.11007823828055101, 0.33988885774435323, 0.18930266295959605}};
        const ContactResult r = contactQuery(QueryShape::polytope(a), QueryShape::polytope(b));
        REQUIRE(r.status == ContactStatus::Ok);
        CHECK_FALSE(r.colliding);
        CHECK(std::abs(r.distance - 5.377827704152724e-13) <= 1e-9 * 0.6);
        // Exactly coplanar points stay refused.
        const ContactResult flat = contactQuery(QueryShape::polytope({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}),
                                                QueryShape::polytope(b));
        CHECK(flat.status == ContactStatus::HullFailed);
    }

    // A 2 x 2 x 2e-6 plate and a box 1e5 from the origin (a reviewer's pair). The query's re-run
    // on the input's exact vertices hinges on the nearly parallel pairs the SAT met, so it tests
    // every pair (no edge pruning), traced or not: the untraced answer is the traced one. There an
    // edge pair of the plate that the rounded Gauss arcs admitted claimed a separation of +0.18;
    // checked against the support gap along its axis it no longer hides the overlap: the depth is
    // the long-double brute force's 0.113343570973659.
    TEST_CASE("a far pair with nearly parallel edges: untraced query = traced query = the brute-force depth") {
        const std::vector<Vec3> a = {
            {-0x1.218716d031fddp+10, 0x1.58d1afa410076p+16, 0x1.b917d8778dc94p+15}, {-0x1.21c2e7d21fdfp+10, 0x1.58d1ed452235bp+16, 0x1.b91b59587147dp+15},
            {-0x1.21b2e32b619a9p+10, 0x1.58d376bbe2942p+16, 0x1.b916a06e33759p+15}, {-0x1.21eeb42d4f7bcp+10, 0x1.58d3b45cf4c28p+16, 0x1.b91a214f16f43p+15},
            {-0x1.218716d70898ap+10, 0x1.58d1afa40131cp+16, 0x1.b917d87774acbp+15}, {-0x1.21c2e7d8f679dp+10, 0x1.58d1ed4513602p+16, 0x1.b91b5958582b5p+15},
            {-0x1.21b2e33238356p+10, 0x1.58d376bbd3be9p+16, 0x1.b916a06e1a591p+15}, {-0x1.21eeb43426169p+10, 0x1.58d3b45ce5ecep+16, 0x1.b91a214efdd7ap+15}};
        const std::vector<Vec3> b = {
            {-0x1.21ac881b11757p+10, 0x1.58d31b0808cf1p+16, 0x1.b9189294db6a4p+15}, {-0x1.21ca709bedf9fp+10, 0x1.58d339d891813p+16, 0x1.b91a53054db62p+15},
            {-0x1.21b9abd019a01p+10, 0x1.58d3a38f2e568p+16, 0x1.b91834f873fdbp+15}, {-0x1.21d79450f6249p+10, 0x1.58d3c25fb708ap+16, 0x1.b919f568e6499p+15},
            {-0x1.21c16686fae0fp+10, 0x1.58d2edc2b4faep+16, 0x1.b91845f29fa2fp+15}, {-0x1.21df4f07d7657p+10, 0x1.58d30c933dadp+16, 0x1.b91a066311eedp+15},
            {-0x1.21ce8a3c030b9p+10, 0x1.58d37649da825p+16, 0x1.b917e85638366p+15}, {-0x1.21ec72bcdf901p+10, 0x1.58d3951a63347p+16, 0x1.b919a8c6aa824p+15}};
        ContactOptions options;
        options.maxPoints = 3;
        ContactTrace trace;
        const ContactResult untraced = contactQuery(QueryShape::polytope(a), QueryShape::polytope(b), options);
        const ContactResult traced = contactQuery(QueryShape::polytope(a), QueryShape::polytope(b), options, &trace);
        CHECK(untraced.status == traced.status);
        CHECK(untraced.depth == traced.depth);
        CHECK(untraced.axis == traced.axis);
        CHECK(untraced.points.size() == traced.points.size());
        CHECK(untraced.colliding);
        CHECK(untraced.depth == doctest::Approx(0.113343570973659).epsilon(1e-9));
    }
}
