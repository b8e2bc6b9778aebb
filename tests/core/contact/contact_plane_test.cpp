// Polyhedron–plane contact: signed distance against long double vertex depths, face-on / edge-on
// resting manifolds, manifold points inside the body and on/below the plane, brute-force vs
// hill-climbing boolean, large offsets / scales, invalid input.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/contact/contact_plane.h"
#include "core/geometry/polyhedron_presets.h"
#include "tests/core/contact/random_pose.h"

using namespace cdlab;

namespace {

// Oracle: min over vertices of (n·x - d)/|n| in long double (shares no code with contact_plane).
long double minDepthL(const ConvexPolyhedron& b, const Transform& t, const Plane& p) {
    const long double len =
        std::sqrt((long double)p.normal.x() * p.normal.x() + (long double)p.normal.y() * p.normal.y() +
                  (long double)p.normal.z() * p.normal.z());
    long double best = INFINITY;
    for (const auto& v : b.vertices()) {
        const Vec3 x = t.apply(v.position);
        long double s = 0;
        for (int k = 0; k < 3; ++k) s += (long double)p.normal[k] * x[k];
        best = std::min(best, (s - p.offset) / len);
    }
    return best;
}

// The world point x is inside the posed body up to tol: behind every face plane.
using cdlab::test::insideBody;

// The same pose as 0.3 · g + offset: a spread of 0.3 about (offset, offset, offset).
Transform randomPose(std::mt19937_64& rng, double offset) { return test::randomPose(rng, Vec3::Constant(offset), 0.3); }

}  // namespace

TEST_SUITE("contact_plane") {
    TEST_CASE("face-on resting box: the whole face, 4 points of equal depth") {
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e4, 1e6}) {
                const ConvexPolyhedron box = presets::box(Vec3(1, 2, 0.5) * scale);
                Transform t;
                t.position = Vec3(offset, -offset, offset + 0.5 * scale - 0.01 * scale);  // 1% of the size below
                const Plane ground{Vec3(0, 0, 3), 3 * offset};
                const PlaneContactResult r = contactPolyhedronPlane(box, t, ground);
                CAPTURE(scale);
                CAPTURE(offset);
                REQUIRE(r.status == PlaneContactStatus::Penetrating);
                CHECK(r.feature.type == FeatureType::Face);
                CHECK(r.featurePoints.size() == 4);
                REQUIRE(r.manifold.size() == 4);
                for (const ContactPoint& c : r.manifold) {
                    CHECK(c.depth == doctest::Approx(0.01 * scale).epsilon(1e-6));
                    CHECK((c.pointA - c.pointB - c.depth * r.normal).norm() <= 1e-9 * (scale + offset));
                }
                CHECK(r.normal.isApprox(Vec3(0, 0, -1)));
                // Exactly touching: Touching, still the face.
                t.position.z() = offset + 0.5 * scale;
                const PlaneContactResult touch = contactPolyhedronPlane(box, t, ground);
                CHECK(touch.status == PlaneContactStatus::Touching);
                CHECK(touch.feature.type == FeatureType::Face);
                CHECK(touch.manifold.size() == 4);
            }
        }
    }

    TEST_CASE("edge-on resting: the edge, 2 points, vertex-on: 1 point") {
        const ConvexPolyhedron box = presets::box(Vec3(1, 1, 1));
        Transform t;
        t.rotation = Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()));
        t.position = Vec3(0, 0, std::sqrt(2.0) - 1e-3);
        PlaneContactResult r = contactPolyhedronPlane(box, t, Plane{Vec3::UnitZ(), 0.0});
        REQUIRE(r.status == PlaneContactStatus::Penetrating);
        CHECK(r.feature.type == FeatureType::Edge);
        CHECK(r.featurePoints.size() == 2);
        // Slightly sunk: the crossings (depth 0) lie 1e-3 beside the edge; the manifold keeps the
        // deepest endpoint and spans the edge's length.
        double span = 0;
        for (const ContactPoint& a : r.manifold)
            for (const ContactPoint& b : r.manifold) span = std::max(span, (a.pointB - b.pointB).norm());
        CHECK(span >= 2.0);
        CHECK(r.manifold[0].depth == doctest::Approx(1e-3));
        // Exactly resting on the edge: the two endpoints, nothing else.
        t.position.z() = std::sqrt(2.0);
        r = contactPolyhedronPlane(box, t, Plane{Vec3::UnitZ(), 0.0});
        CHECK(r.status == PlaneContactStatus::Touching);
        CHECK(r.feature.type == FeatureType::Edge);
        REQUIRE(r.manifold.size() == 2);
        CHECK((r.manifold[0].pointA - r.manifold[1].pointA).norm() == doctest::Approx(2.0));
        // Corner down: a single vertex feature, deepest point first.
        t.rotation = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3(0, 0, -1));
        t.position = Vec3(0, 0, std::sqrt(3.0) - 1e-3);
        r = contactPolyhedronPlane(box, t, Plane{Vec3::UnitZ(), 0.0});
        CHECK(r.feature.type == FeatureType::Vertex);
        REQUIRE(!r.manifold.empty());
        CHECK(r.manifold[0].depth == doctest::Approx(1e-3).epsilon(1e-6));
        r = contactPolyhedronPlane(box, t, Plane{Vec3::UnitZ(), 0.0}, PlaneContactOptions{.maxPoints = 1});
        CHECK(r.manifold.size() == 1);
    }

    TEST_CASE("random poses: depth vs long double, manifold inside the body, below the plane") {
        std::mt19937_64 rng(7);
        const ConvexPolyhedron bodies[] = {presets::box(Vec3(1, 0.5, 0.3)), presets::icosahedron(1.0),
                                           presets::tetrahedron(1.0), presets::prism(7, 1.0, 0.4),
                                           presets::randomHull(60, 3)};
        int colliding = 0, separated = 0;
        for (const ConvexPolyhedron& body : bodies) {
            for (int k = 0; k < 200; ++k) {
                const double offset = (k % 4 == 3) ? 1e5 : 0.0;
                const Transform t = randomPose(rng, offset);
                const Vec3 n = Vec3(std::normal_distribution<double>()(rng), 1.0, 0.2).normalized() * 2.5;
                const Plane p{
                    n, n.dot(Vec3::Constant(offset)) + 2.5 * std::uniform_real_distribution<double>(-1.5, 0.5)(rng)};
                const PlaneContactResult r = contactPolyhedronPlane(body, t, p);
                const long double oracle = minDepthL(body, t, p);
                const double tol = 1e-12 * (1 + offset);
                CHECK(std::abs(r.signedDistance - (double)oracle) <= tol);
                CHECK(intersectPolyhedronPlane(body, t, p) == (oracle <= 0));
                const PolytopeShape shape(body);
                CHECK(intersectPolytopePlane(shape, t, p) == intersectPolyhedronPlane(body, t, p));
                for (const Vec3& fp : r.featurePoints)
                    CHECK(std::abs(n.normalized().dot(fp) - p.offset / 2.5 - r.signedDistance) <= r.tolerance + tol);
                if (!r.colliding()) {
                    ++separated;
                    CHECK(r.manifold.empty());
                    continue;
                }
                ++colliding;
                REQUIRE(!r.manifold.empty());
                CHECK(r.manifold.size() <= 4);
                CHECK(r.manifold[0].depth == doctest::Approx(std::max(0.0, -(double)oracle)).epsilon(1e-9));
                for (const ContactPoint& c : r.manifold) {
                    const double sA = n.normalized().dot(c.pointA) - p.offset / 2.5;
                    const double sB = n.normalized().dot(c.pointB) - p.offset / 2.5;
                    CHECK(sA <= r.tolerance + tol);  // on / below the plane
                    CHECK(std::abs(sB) <= tol);      // pointB on the plane
                    CHECK(c.depth == doctest::Approx(std::max(0.0, -sA)).epsilon(1e-6));
                    CHECK(insideBody(body, t, c.pointA, tol + 1e-12));  // a point of the body
                }
                // Every submerged vertex projects into the (convex) contact polygon.
                if (r.polygon.size() >= 3) {
                    const Vec3 nn = n.normalized();
                    for (const auto& v : body.vertices()) {
                        const Vec3 x = t.apply(v.position);
                        if (nn.dot(x) - p.offset / 2.5 > -r.tolerance) continue;
                        const Vec3 q = x - (nn.dot(x) - p.offset / 2.5) * nn;
                        for (size_t i = 0; i < r.polygon.size(); ++i) {
                            const Vec3& a = r.polygon[i].pointB;
                            const Vec3& b = r.polygon[(i + 1) % r.polygon.size()].pointB;
                            CHECK((b - a).cross(q - a).dot(nn) >= -1e-9 * (1 + offset));
                        }
                    }
                }
            }
        }
        CHECK(colliding > 100);
        CHECK(separated > 100);
    }

    TEST_CASE("hill climbing on a large polytope agrees with the vertex loop") {
        const ConvexPolyhedron sphere = presets::geodesicSphere(3, 2.0);  // 642 vertices: climbs
        const PolytopeShape shape(sphere);
        REQUIRE(shape.vertexCount() > PolytopeShape::kLoopMaxVertices);
        std::mt19937_64 rng(11);
        int hint = -1;
        for (int k = 0; k < 500; ++k) {
            const Transform t = randomPose(rng, 0.0);
            const Vec3 n = Vec3(std::normal_distribution<double>()(rng), std::normal_distribution<double>()(rng), 1.0);
            const Plane p{n, std::uniform_real_distribution<double>(-3, 3)(rng)};
            CHECK(intersectPolytopePlane(shape, t, p, &hint) == (minDepthL(sphere, t, p) <= 0));
        }
    }

    TEST_CASE("separated: closest feature and its projections") {
        const ConvexPolyhedron box = presets::box(Vec3(1, 1, 1));
        Transform t;
        t.position = Vec3(0, 0, 3);
        const PlaneContactResult r = contactPolyhedronPlane(box, t, Plane{Vec3::UnitZ(), 0.0});
        CHECK(r.status == PlaneContactStatus::Separated);
        CHECK(r.signedDistance == 2.0);
        CHECK(r.feature.type == FeatureType::Face);
        REQUIRE(r.featurePointsOnPlane.size() == 4);
        for (const Vec3& q : r.featurePointsOnPlane) CHECK(q.z() == 0.0);
        CHECK(r.manifold.empty());
    }

    TEST_CASE("trace: vertex depths, crossings, polygon, reduction") {
        const ConvexPolyhedron box = presets::box(Vec3(1, 1, 1));
        Transform t;
        t.rotation = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()));
        t.position = Vec3(0, 0, 0.9);
        PlaneContactTrace tr;
        const PlaneContactResult r = contactPolyhedronPlane(box, t, Plane{Vec3::UnitZ(), 0.0}, {}, &tr);
        REQUIRE(tr.vertexDistances.size() == 8);
        CHECK(tr.crossings.size() == 4);  // two bottom-face edges, two side edges... crossing the plane
        for (const auto& c : tr.crossings) CHECK(std::abs(c.point.z()) < 1e-15);
        // The two side-edge crossings lie 0.108 beside the submerged bottom corners (depth 0.351):
        // the rim of those corners, dropped (contact_manifold.h rule 0); the two bottom-face
        // crossings 1.13 away stay. Four points left for four asked: kept without reduction steps.
        CHECK(tr.reduction.empty());
        REQUIRE(r.manifold.size() == 4);
        CHECK(r.manifold[0].depth == doctest::Approx(std::cos(0.3) + std::sin(0.3) - 0.9));
        int submerged = 0;
        for (const ContactPoint& c : r.manifold) submerged += c.depth > 0.3;
        CHECK(submerged == 2);
        CHECK(r.polygon.size() == 4);
    }

    TEST_CASE("invalid input: NaN pose, zero normal, empty body") {
        const ConvexPolyhedron box = presets::box(Vec3(1, 1, 1));
        Transform t;
        t.position.x() = NAN;
        CHECK(contactPolyhedronPlane(box, t, Plane{Vec3::UnitZ(), 0.0}).status == PlaneContactStatus::InvalidInput);
        CHECK(!intersectPolyhedronPlane(box, t, Plane{Vec3::UnitZ(), 0.0}));
        CHECK(std::isnan(signedDistancePolyhedronPlane(box, t, Plane{Vec3::UnitZ(), 0.0})));
        Transform ok;
        const PlaneContactResult z = contactPolyhedronPlane(box, ok, Plane{Vec3::Zero(), 0.0});
        CHECK(z.status == PlaneContactStatus::InvalidInput);
        CHECK(z.message.find("zero") != std::string::npos);
        CHECK(contactPolyhedronPlane(ConvexPolyhedron{}, ok, Plane{Vec3::UnitZ(), 0.0}).status ==
              PlaneContactStatus::InvalidInput);
        Transform bad;
        bad.rotation = Quat(2, 0, 0, 0);
        CHECK(contactPolyhedronPlane(box, bad, Plane{Vec3::UnitZ(), 0.0}).status == PlaneContactStatus::InvalidInput);
        // Tiny / huge plane normals are normalised without underflow / overflow.
        CHECK(contactPolyhedronPlane(box, ok, Plane{Vec3(0, 0, 1e-300), 0.0}).status ==
              PlaneContactStatus::Penetrating);
        CHECK(contactPolyhedronPlane(box, ok, Plane{Vec3(0, 0, 1e300), 0.0}).depth == 1.0);
    }
}

// Issue 21 §2: which points a manifold keeps (core/contact/contact_manifold.h, rules 0-5).
TEST_SUITE("contact_plane manifold rules") {
    TEST_CASE("asking for more points never returns fewer, every corner once maxPoints reaches their count") {
        // A hexagonal prism standing on the plane, sunk 0.01: six submerged corners, all at one depth.
        const ConvexPolyhedron hex = presets::prism(6, 1.0, 0.5);  // axis y
        Transform t;
        t.rotation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));  // axis y -> z: standing on a cap
        t.position = Vec3(0.3, -0.2, 0.49);
        size_t previous = 0;
        for (int k = 1; k <= 8; ++k) {
            PlaneContactOptions o;
            o.maxPoints = k;
            const PlaneContactResult r = contactPolyhedronPlane(hex, t, Plane{Vec3::UnitZ(), 0.0}, o);
            CAPTURE(k);
            CHECK(r.manifold.size() == size_t(std::min(k, 6)));
            CHECK(r.manifold.size() >= previous);
            previous = r.manifold.size();
            for (const ContactPoint& c : r.manifold) CHECK(c.depth == doctest::Approx(0.01));
        }
    }

    TEST_CASE("depth-0 crossings beside a submerged corner never displace it") {
        // The hexagonal prism lying on a side edge, sunk 0.001 (axis y; vertex 0's edge turned down).
        const ConvexPolyhedron hex = presets::prism(6, 1.0, 0.5);
        Transform side;
        side.rotation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));  // (1, y, 0) -> (0, y, -1)
        side.position = Vec3(0, 0, 1.0 - 0.001);
        const PlaneContactResult r = contactPolyhedronPlane(hex, side, Plane{Vec3::UnitZ(), 0.0});
        REQUIRE(r.status == PlaneContactStatus::Penetrating);
        int full = 0;
        for (const ContactPoint& c : r.manifold) full += c.depth == doctest::Approx(0.001);
        CHECK(full == 2);  // both ends of the bottom edge, not one end and a crossing 0.0017 away
        REQUIRE(r.manifold.size() >= 2);
        CHECK(r.manifold[0].depth == doctest::Approx(0.001));  // the submerged points come first
        CHECK(r.manifold[1].depth == doctest::Approx(0.001));
        // A cone (a 32-sided pyramid) on its apex: the apex alone, not the apex and its rim crossings.
        std::vector<Vec3> v = {Vec3(0, 0, 0)};
        for (const Vec3& p : presets::regularPolygon(32, 0.5)) v.push_back(p + Vec3(0, 0, 1));
        std::vector<std::vector<int>> faces;
        std::vector<int> top;
        for (int i = 0; i < 32; ++i) {
            faces.push_back({0, 1 + (i + 1) % 32, 1 + i});
            top.push_back(1 + i);
        }
        faces.push_back(top);
        const PolyhedronBuild cone = ConvexPolyhedron::fromFaces(v, faces);
        REQUIRE(cone.polyhedron.faceCount() == 33);
        Transform apexDown;
        apexDown.position = Vec3(0, 0, -0.001);
        const PlaneContactResult c = contactPolyhedronPlane(cone.polyhedron, apexDown, Plane{Vec3::UnitZ(), 0.0});
        REQUIRE(c.manifold.size() == 1);
        CHECK(c.manifold[0].depth == doctest::Approx(0.001));
    }
}
