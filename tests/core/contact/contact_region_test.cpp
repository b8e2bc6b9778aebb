// Contact manifolds against the exact contact region (verification/contact_region_oracle.h: the
// clip of the two support faces, or the submerged part of a body on a plane, in rationals): every
// manifold point is a point of the region at its exact depth, the deepest comes first, asking for
// more points never gives fewer or less area, and with maxPoints at the region's corner count every
// corner comes back — except the rim of a submerged corner (depth-0 points within the deepest depth of
// it, the rule in core/contact/contact_manifold.h). Resting, touching and tilted cases; inputs are
// exact doubles (dyadic coordinates, identity poses), so the oracle sees exactly what the code sees.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/contact/contact_box.h"
#include "core/contact/contact_plane.h"
#include "core/contact/contact_sat.h"
#include "core/geometry/polyhedron.h"
#include "verification/contact_region_oracle.h"

using namespace cdlab;
using oracle::ContactRegion;
using oracle::LVec3;

namespace {

LVec3 L(const Vec3& v) { return v.cast<long double>(); }

// A prism: the convex polygon `base` (either orientation) and the same polygon moved by `up`.
ConvexPolyhedron prism(std::vector<Vec3> base, const Vec3& up) {
    if ((base[1] - base[0]).cross(base[2] - base[0]).dot(up) < 0) std::reverse(base.begin(), base.end());
    const int n = static_cast<int>(base.size());
    std::vector<Vec3> v = base;
    for (const Vec3& p : base) v.push_back(p + up);
    std::vector<std::vector<int>> faces;
    std::vector<int> bottom, top;
    for (int i = 0; i < n; ++i) {
        bottom.push_back(n - 1 - i);
        top.push_back(n + i);
        faces.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
    }
    faces.push_back(bottom);
    faces.push_back(top);
    const PolyhedronBuild b = ConvexPolyhedron::fromFaces(v, faces);
    REQUIRE(b.ok());
    return b.polyhedron;
}

std::vector<Vec3> facePoints(const ConvexPolyhedron& m, int f) {
    std::vector<Vec3> p;
    for (int v : m.faceVertices(f)) p.push_back(m.position(v));
    return p;
}

// The face of m whose outward normal is most nearly `direction`.
int faceAlong(const ConvexPolyhedron& m, const Vec3& direction) {
    int best = 0;
    for (int f = 1; f < m.faceCount(); ++f)
        if (m.face(f).normal.dot(direction) > m.face(best).normal.dot(direction)) best = f;
    return best;
}

// A random convex polygon in the plane spanned by u, v about c: the hull of 8 dyadic points of a
// disc (multiples of 1/64 of the radius), at least 3 corners.
std::vector<Vec3> randomPolygon(std::mt19937_64& rng, const Vec3& c, const Vec3& u, const Vec3& v, double radius) {
    std::uniform_int_distribution<int> k(-64, 64);
    for (;;) {
        std::vector<Eigen::Vector2d> p;
        while (p.size() < 8) {
            const Eigen::Vector2d q(k(rng) / 64.0, k(rng) / 64.0);
            if (q.squaredNorm() <= 1.0) p.push_back(q);
        }
        std::sort(p.begin(), p.end(), [](auto& a, auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
        std::vector<Eigen::Vector2d> h(2 * p.size());  // monotone chain, strict turns
        size_t n = 0;
        auto turn = [](auto& o, auto& a, auto& b) { return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x(); };
        for (size_t i = 0; i < p.size(); ++i) {
            while (n >= 2 && turn(h[n - 2], h[n - 1], p[i]) <= 0) --n;
            h[n++] = p[i];
        }
        for (size_t i = p.size() - 1, t = n + 1; i-- > 0;) {
            while (n >= t && turn(h[n - 2], h[n - 1], p[i]) <= 0) --n;
            h[n++] = p[i];
        }
        if (n - 1 < 3) continue;
        std::vector<Vec3> out;
        for (size_t i = 0; i + 1 < n; ++i) out.push_back(c + radius * (h[i].x() * u + h[i].y() * v));
        return out;
    }
}

// Twice the area of the hull of points seen along n (long double).
long double hullArea(std::vector<LVec3> pts, const LVec3& n) {
    const LVec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
    std::vector<std::pair<long double, long double>> p;
    for (const LVec3& x : pts) p.emplace_back(x.dot(e1), x.dot(e2));
    std::sort(p.begin(), p.end());
    if (p.size() < 3) return 0;
    std::vector<std::pair<long double, long double>> h(2 * p.size());
    size_t k = 0;
    auto turn = [](auto& o, auto& a, auto& b) {
        return (a.first - o.first) * (b.second - o.second) - (a.second - o.second) * (b.first - o.first);
    };
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && turn(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    long double a = 0;
    for (size_t i = 0; i + 1 < k; ++i) a += h[i].first * h[i + 1].second - h[i + 1].first * h[i].second;
    return a;
}

LVec3 projected(const LVec3& x, const LVec3& n) { return x - x.dot(n) * n; }

// What a manifold is checked against: the exact region, which of its points lie in the region (the
// incident body's), the tolerance for rounding.
struct Check {
    const ContactRegion& region;
    bool regionOnA;  // the region's points are the manifold's pointA (else pointB)
    double tol;      // world units
};

// The candidates each manifold point is (nearest, checked within tol, depth included).
std::vector<int> matchToRegion(const Check& c, const ContactManifold& m, std::vector<LVec3>& on) {
    const ContactRegion& g = c.region;
    std::vector<int> matched;
    for (size_t i = 0; i < m.size(); ++i) {
        const LVec3 x = L(c.regionOnA ? m[i].pointA : m[i].pointB);
        on.push_back(x);
        long double nearest = INFINITY;
        matched.push_back(-1);
        for (int k = 0; k < static_cast<int>(g.candidates.size()); ++k)
            if ((g.candidates[k].position - x).norm() < nearest) {
                nearest = (g.candidates[k].position - x).norm();
                matched.back() = k;
            }
        CAPTURE(i);
        CAPTURE(static_cast<double>(nearest));
        CHECK(nearest <= c.tol);  // a point of the exact region
        CHECK(std::abs(m[i].depth - g.candidates[matched.back()].depth) <= c.tol);
    }
    return matched;
}

// The candidates the reduction chooses from when maxPoints > 0: all but the rim (depth-0 points
// within the deepest depth, in the plane, of a submerged point). Empty when a candidate sits on
// that distance within rounding (either answer is right there).
std::vector<int> keptAfterRim(const ContactRegion& g, long double deepest, int maxPoints) {
    std::vector<int> kept;
    for (int k = 0; k < static_cast<int>(g.candidates.size()); ++k) {
        long double d = INFINITY;
        for (const auto& q : g.candidates)
            if (q.depthSign > 0) d = std::min(d, projected(q.position - g.candidates[k].position, g.normal).norm());
        if (maxPoints > 0 && g.candidates[k].depthSign == 0 && std::abs(d - deepest) <= 1e-9L * deepest) return {};
        if (maxPoints <= 0 || g.candidates[k].depthSign != 0 || d > deepest) kept.push_back(k);
    }
    return kept;
}

// The manifold checked against the exact region; returns twice the area it spans.
long double checkManifold(const Check& c, const ContactManifold& m, int maxPoints) {
    const ContactRegion& g = c.region;
    REQUIRE(g.error.empty());
    REQUIRE(!g.candidates.empty());
    REQUIRE(!m.empty());
    if (maxPoints > 0) CHECK(static_cast<int>(m.size()) <= maxPoints);
    long double deepest = 0;
    for (const auto& p : g.candidates) deepest = std::max(deepest, p.depth);
    std::vector<LVec3> on;
    const std::vector<int> matched = matchToRegion(c, m, on);
    if (maxPoints > 0) {
        CHECK(std::abs(m[0].depth - deepest) <= c.tol);  // the deepest first
    } else {
        bool present = false;  // a plane contact's full polygon runs counter-clockwise, the deepest in it
        for (size_t i = 0; i < m.size(); ++i) present = present || std::abs(m[i].depth - deepest) <= c.tol;
        CHECK(present);
    }
    const std::vector<int> kept = keptAfterRim(g, deepest, maxPoints);
    if (kept.empty()) return hullArea(on, g.normal);
    // The reduction picks among the submerged points while one of them adds spread, then among the
    // depth-0 ones: with maxPoints at most the submerged hull's corners (the deepest counted), every
    // point is submerged; with maxPoints at the corners of both tiers, every corner of the kept
    // points' hull comes back.
    std::vector<int> submerged;
    for (int k : kept)
        if (g.candidates[k].depthSign > 0) submerged.push_back(k);
    const std::vector<int> corners = oracle::hullCorners(g, kept);
    const std::vector<int> submergedCorners = oracle::hullCorners(g, submerged);
    auto hasDeepest = [&](const std::vector<int>& set) {  // every point at the deepest depth (ties: any may lead)
        for (int k : kept)
            if (g.candidates[k].depth == deepest && std::find(set.begin(), set.end(), k) == set.end()) return false;
        return true;
    };
    const int submergedNeeded =
        static_cast<int>(submergedCorners.size()) + (!submerged.empty() && !hasDeepest(submergedCorners));
    int needed = submergedNeeded;
    for (int k : corners) needed += g.candidates[k].depthSign == 0;
    if (submerged.empty()) needed += !hasDeepest(corners);
    if (maxPoints > 0 && maxPoints <= submergedNeeded)
        for (int k : matched) CHECK(g.candidates[k].depthSign > 0);  // no depth-0 point displaces a submerged one
    if (maxPoints <= 0 || maxPoints >= needed) {
        for (int corner : corners) {
            long double nearest = INFINITY;
            for (const LVec3& x : on)
                nearest = std::min(nearest, projected(x - g.candidates[corner].position, g.normal).norm());
            CAPTURE(corner);
            CAPTURE(static_cast<double>(nearest));
            CHECK(nearest <= c.tol);  // every corner comes back
        }
    }
    return hullArea(on, g.normal);
}

// maxPoints 0, 1, ..., corners + 2: each manifold checked; counts and areas never drop.
template <class Contact>
void checkEveryMaxPoints(const Check& c, Contact contact) {
    size_t previousCount = 0;
    long double previousArea = 0;
    const int most = static_cast<int>(c.region.candidates.size()) + 2;
    for (int k = 1; k <= most; ++k) {
        CAPTURE(k);
        const ContactManifold m = contact(k);
        const long double area = checkManifold(c, m, k);
        CHECK(m.size() >= previousCount);
        CHECK(area >= previousArea * (1 - 1e-12L));
        previousCount = m.size();
        previousArea = area;
    }
    checkManifold(c, contact(0), 0);
}

// A SAT face contact of a and b (identity poses) checked against the clip of the faces it reports.
void checkSatContact(const ConvexPolyhedron& a, const ConvexPolyhedron& b, double tol, SatContactStatus expected) {
    const SatContactResult r = contactPolyhedra(a, {}, b, {});
    REQUIRE(r.status == expected);
    REQUIRE(r.axisKind != SatAxisKind::EdgeEdge);
    const bool onA = r.axisKind == SatAxisKind::FaceA;
    const ConvexPolyhedron& reference = onA ? a : b;
    const ConvexPolyhedron& incident = onA ? b : a;
    const int referenceFace = onA ? r.featureA.index : r.featureB.index;
    const int incidentFace = onA ? r.featureB.index : r.featureA.index;
    // The incident face is the reference normal's most anti-parallel face.
    const Vec3 nRef = reference.face(referenceFace).normal;
    CHECK(incidentFace == faceAlong(incident, -nRef));
    const ContactRegion region =
        oracle::exactFaceClipRegion(facePoints(reference, referenceFace), facePoints(incident, incidentFace));
    CHECK((region.normal - L(onA ? r.normal : Vec3(-r.normal))).norm() <= 1e-15L);  // the exact face normal
    const Check c{region, !onA, tol};
    checkEveryMaxPoints(c, [&](int k) {
        SatContactOptions o;
        o.maxPoints = k;
        return contactPolyhedra(a, {}, b, {}, o).manifold;
    });
}

// An axis-aligned box [lo, hi] as a polyhedron.
ConvexPolyhedron boxBetween(const Vec3& lo, const Vec3& hi) {
    return prism({lo, Vec3(hi.x(), lo.y(), lo.z()), Vec3(hi.x(), hi.y(), lo.z()), Vec3(lo.x(), hi.y(), lo.z())},
                 Vec3(0, 0, hi.z() - lo.z()));
}

}  // namespace

TEST_SUITE("contact_region") {
    TEST_CASE("face clip: a flat prism resting on or touching a box, overhanging its edges") {
        for (double s : {1.0 / 1024, 1.0, 1024.0}) {
            for (double offset : {0.0, 1024.0}) {
                for (double sunk : {0.0, 1.0 / 64}) {
                    CAPTURE(s);
                    CAPTURE(offset);
                    CAPTURE(sunk);
                    const Vec3 o = Vec3(offset, -offset, offset);
                    const ConvexPolyhedron ground = boxBetween(o + s * Vec3(-2, -2, -1), o + s * Vec3(2, 2, 0));
                    // An irregular hexagon over the corner (2, 2): three of its corners hang over.
                    const std::vector<Vec3> hexagon = {o + s * Vec3(1.25, 1.5, -sunk), o + s * Vec3(1.875, 1.125, -sunk),
                                                       o + s * Vec3(2.5, 1.5, -sunk),  o + s * Vec3(2.625, 2.25, -sunk),
                                                       o + s * Vec3(2, 2.75, -sunk),   o + s * Vec3(1.375, 2.375, -sunk)};
                    const ConvexPolyhedron body = prism(hexagon, s * Vec3(0, 0, 0.5));
                    const double tol = 1e-12 * (s + offset);
                    checkSatContact(ground, body, tol,
                                    sunk == 0 ? SatContactStatus::Touching : SatContactStatus::Penetrating);
                    // Both orders: the reference face is then B's.
                    checkSatContact(body, ground, tol,
                                    sunk == 0 ? SatContactStatus::Touching : SatContactStatus::Penetrating);
                    const ContactRegion region = oracle::exactFaceClipRegion(
                        facePoints(ground, faceAlong(ground, Vec3::UnitZ())), facePoints(body, faceAlong(body, -Vec3::UnitZ())));
                    CHECK(region.corners.size() == 5);  // 2 hexagon corners, 2 edge crossings, the box's corner
                }
            }
        }
    }

    TEST_CASE("face clip: axis-aligned boxes (the box path and the general SAT), resting and touching") {
        for (double sunk : {0.0, 1.0 / 128}) {
            const Vec3 ha(2, 1.5, 0.5), hb(0.75, 0.5, 0.25);
            Transform ta, tb;
            ta.position = Vec3(8, -4, 2);
            tb.position = ta.position + Vec3(1.5, -1.25, 0.75 - sunk);  // over the corner of A's top face
            const ConvexPolyhedron a = boxBetween(ta.position - ha, ta.position + ha);
            const ConvexPolyhedron b = boxBetween(tb.position - hb, tb.position + hb);
            const ContactRegion region = oracle::exactFaceClipRegion(facePoints(a, faceAlong(a, Vec3::UnitZ())),
                                                                     facePoints(b, faceAlong(b, -Vec3::UnitZ())));
            REQUIRE(region.corners.size() == 4);
            const Check c{region, false, 1e-12};
            checkEveryMaxPoints(c, [&](int k) {
                SatContactOptions o;
                o.maxPoints = k;
                const SatContactResult r = contactBoxBox(ha, ta, hb, tb, o);
                CHECK(r.axisKind == SatAxisKind::FaceA);
                return r.manifold;
            });
            checkSatContact(a, b, 1e-12, sunk == 0 ? SatContactStatus::Touching : SatContactStatus::Penetrating);
        }
    }

    TEST_CASE("face clip: a tilted incident face keeps the clipped corners behind the reference plane, none in front") {
        const ConvexPolyhedron ground = boxBetween(Vec3(-4, -4, -1), Vec3(4, 4, 0));
        // The bottom z = -1/64 + x/128 - y/256 over a 2 x 2 square: about x = 0 every corner is below
        // z = 0; about x = 1.5 the corner (2.5, -1) stands 1/128 above it and (2.5, 1) touches it.
        for (double cx : {0.0, 1.5}) {
            std::vector<Vec3> bottom;
            for (const auto& [x, y] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}})
                bottom.emplace_back(cx + x, y, -1.0 / 64 + (cx + x) / 128 - y / 256);
            const ConvexPolyhedron body = prism(bottom, Vec3(0, 0, 1));
            CAPTURE(cx);
            checkSatContact(ground, body, 1e-13, SatContactStatus::Penetrating);
            const ContactRegion region = oracle::exactFaceClipRegion(facePoints(ground, faceAlong(ground, Vec3::UnitZ())),
                                                                     facePoints(body, faceAlong(body, -Vec3::UnitZ())));
            CHECK(region.candidates.size() == (cx == 0 ? 4u : 3u));
        }
    }

    TEST_CASE("face clip: random tilted polygons on random boxes, some overhanging (400 pairs)") {
        std::mt19937_64 rng(20261127);
        std::uniform_int_distribution<int> tilt(-8, 8), sink(0, 16), place(-96, 96);
        int checked = 0, edgeAxes = 0;
        for (int trial = 0; trial < 400; ++trial) {
            CAPTURE(trial);
            const Vec3 half(1 + place(rng) / 128.0 + 1, 1.5, 0.5);
            const ConvexPolyhedron ground = boxBetween(-half, half);
            const Vec3 centre(place(rng) / 32.0, place(rng) / 64.0, 0.5);
            const double sx = tilt(rng) / 512.0, sy = tilt(rng) / 512.0, d = sink(rng) / 1024.0;
            std::vector<Vec3> base = randomPolygon(rng, centre, Vec3::UnitX(), Vec3::UnitY(), 1.0);
            for (Vec3& p : base) p.z() = 0.5 - d + sx * (p.x() - centre.x()) + sy * (p.y() - centre.y());
            const ConvexPolyhedron body = prism(base, Vec3(0, 0, 0.75));
            const SatContactResult r = contactPolyhedra(ground, {}, body, {});
            if (r.status == SatContactStatus::Separated) continue;
            if (r.axisKind == SatAxisKind::EdgeEdge) {
                ++edgeAxes;  // the least-penetration axis is an edge pair: one point, no clip
                continue;
            }
            checkSatContact(ground, body, 1e-13, r.status);
            ++checked;
        }
        MESSAGE(checked, " face contacts checked, ", edgeAxes, " edge-edge contacts skipped");
        CHECK(checked >= 250);
    }

    TEST_CASE("face clip on a tilted reference face (a box with axes (1,2,2), (2,1,-2), (2,-2,1))") {
        const Vec3 u(1, 2, 2), v(2, 1, -2), w(2, -2, 1);  // orthogonal, |u| = |v| = |w| = 3: exact corners
        const Vec3 c(0.5, -0.25, 1);
        const ConvexPolyhedron box = prism({c - u - v - w, c - u + v - w, c - u + v + w, c - u - v + w}, 2 * u);
        const Vec3 top = c + u;  // the centre of the +u face
        std::mt19937_64 rng(7);
        for (int trial = 0; trial < 40; ++trial) {
            CAPTURE(trial);
            const double sunk = (trial % 4) / 64.0;  // 0: touching
            const Vec3 at = top + (trial % 5 - 2) / 2.0 * v + (trial % 3 - 1) / 2.0 * w - sunk * u;
            const std::vector<Vec3> base = randomPolygon(rng, at, v, w, 0.75);
            const ConvexPolyhedron body = prism(base, u / 2);
            checkSatContact(box, body, 1e-12, sunk == 0 ? SatContactStatus::Touching : SatContactStatus::Penetrating);
        }
    }

    TEST_CASE("plane: tilted boxes and prisms sunk corner-, edge- and face-first, the box path on tilted planes") {
        const Vec3 u(1, 2, 2), v(2, 1, -2), w(2, -2, 1);
        std::mt19937_64 rng(11);
        std::uniform_int_distribution<int> level(-64, 64);
        int checked = 0;
        for (int trial = 0; trial < 150; ++trial) {
            CAPTURE(trial);
            // A body with exact corners: a box on the integer axes, or a prism on a random polygon.
            const Vec3 c(level(rng) / 16.0, level(rng) / 16.0, level(rng) / 16.0);
            const ConvexPolyhedron body =
                trial % 2 == 0 ? prism({c - u - v - w, c - u + v - w, c - u + v + w, c - u - v + w}, 2 * u)
                               : prism(randomPolygon(rng, c, trial % 3 == 0 ? Vec3::UnitX() : v,
                                                     trial % 3 == 0 ? Vec3::UnitY() : w, 3.0),
                                       trial % 3 == 0 ? Vec3(0, 0, 2) : u);
            std::vector<Vec3> vertices = body.positions();
            double lowest = INFINITY, highest = -INFINITY;
            for (const Vec3& x : vertices) {
                lowest = std::min(lowest, x.z());
                highest = std::max(highest, x.z());
            }
            // The ground z <= h: at a corner (touching), or up to a quarter of the height above it.
            const double h = trial % 5 == 0 ? lowest : lowest + std::ldexp(std::floor((highest - lowest) * 64), -8) * (trial % 4) / 3;
            std::vector<std::pair<int, int>> edges;
            for (int e = 0; e < body.edgeCount(); ++e) edges.push_back(body.edgeVertices(e));
            const ContactRegion region = oracle::exactPlaneRegion(vertices, edges, Vec3::UnitZ(), h);
            const Plane ground{Vec3::UnitZ(), h};
            const double tol = 1e-12 * (1 + c.norm());
            // Vertices within the touching tolerance of the plane count as on it in the code: not here.
            bool nearPlane = false;
            for (const Vec3& x : vertices) nearPlane = nearPlane || (x.z() != h && std::abs(x.z() - h) < 1e-6);
            if (nearPlane) continue;
            const Check check{region, true, tol};
            checkEveryMaxPoints(check, [&](int k) {
                PlaneContactOptions o;
                o.maxPoints = k;
                const PlaneContactResult r = contactPolyhedronPlane(body, {}, ground, o);
                REQUIRE(r.colliding());
                return r.manifold;
            });
            ++checked;
        }
        CHECK(checked >= 140);
        // The box path: an axis-aligned box against tilted planes n · x <= d (n = (1, 2, 2), (-2, 1, 2)).
        for (const Vec3& n : {Vec3(1, 2, 2), Vec3(-2, 1, 2), Vec3(0, 1, 4)}) {
            const Vec3 h(1.5, 1, 0.5);
            Transform pose;
            pose.position = Vec3(4, -2, 8);
            const ConvexPolyhedron box = boxBetween(pose.position - h, pose.position + h);
            std::vector<Vec3> vertices = box.positions();
            double lowest = INFINITY;
            for (const Vec3& x : vertices) lowest = std::min(lowest, n.dot(x));
            std::vector<std::pair<int, int>> edges;
            for (int e = 0; e < box.edgeCount(); ++e) edges.push_back(box.edgeVertices(e));
            for (double sunk : {0.0, 0.25, 1.5, 3.0}) {
                CAPTURE(n);
                CAPTURE(sunk);
                const ContactRegion region = oracle::exactPlaneRegion(vertices, edges, n, lowest + sunk);
                const Check check{region, true, 1e-12 * 16};
                checkEveryMaxPoints(check, [&](int k) {
                    PlaneContactOptions o;
                    o.maxPoints = k;
                    const BoxPlaneContact r = contactBoxPlane(h, pose, Plane{n, lowest + sunk}, o);
                    REQUIRE(r.colliding());
                    return r.manifold;
                });
            }
        }
    }

    TEST_CASE("the oracle: an upright box on a plane, a vertical edge's crossing projects onto its corner") {
        const ConvexPolyhedron box = boxBetween(Vec3(0, 0, -1), Vec3(2, 1, 1));
        std::vector<std::pair<int, int>> edges;
        for (int e = 0; e < box.edgeCount(); ++e) edges.push_back(box.edgeVertices(e));
        const ContactRegion r = oracle::exactPlaneRegion(box.positions(), edges, Vec3(0, 0, 1), 0.0);
        CHECK(r.candidates.size() == 8);  // 4 submerged corners, 4 crossings above them
        CHECK(r.corners.size() == 4);
        long double area = 0;
        std::vector<LVec3> corners;
        for (int k : r.corners) corners.push_back(r.candidates[k].position);
        area = hullArea(corners, r.normal);
        CHECK(area == doctest::Approx(4.0));  // twice the 2 x 1 rectangle
        // A face clip of two unit squares, one turned 45°: the regular octagon's 8 corners.
        const std::vector<Vec3> square = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
        const double q = std::sqrt(2.0);  // not dyadic: the oracle still takes the doubles as given
        const std::vector<Vec3> diamond = {Vec3(0, -q, 0), Vec3(-q, 0, 0), Vec3(0, q, 0), Vec3(q, 0, 0)};
        const ContactRegion octagon = oracle::exactFaceClipRegion(square, diamond);
        REQUIRE(octagon.error.empty());
        CHECK(octagon.corners.size() == 8);
        for (const auto& p : octagon.candidates) CHECK(p.depthSign == 0);
    }
}
