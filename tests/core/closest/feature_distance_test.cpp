// Feature-pair closest points (V–V ... F–F) against dense sampling in long double, exact small
// cases, parallel edges / faces, the contact normal rule and its unstable cases, offsets, scales.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "core/closest/feature_distance.h"

using namespace cdlab;

namespace {

using LVec = Eigen::Matrix<long double, 3, 1>;
LVec toL(const Vec3& v) { return LVec(v.x(), v.y(), v.z()); }

// Sample points of a feature: the vertex; the segment at n+1 points; a triangle fan of the
// polygon with a barycentric grid of step 1/n. Returns the points and the spacing bound h
// (every feature point lies within h of a sample).
std::vector<LVec> samples(const FeatureGeometry& f, int n, long double& h) {
    std::vector<LVec> s;
    h = 0;
    if (f.type == FeatureType::Vertex) {
        s.push_back(toL(f.points[0]));
        return s;
    }
    if (f.type == FeatureType::Edge) {
        const LVec a = toL(f.points[0]), b = toL(f.points[1]);
        for (int i = 0; i <= n; ++i) s.push_back(a + (b - a) * ((long double)i / n));
        h = (b - a).norm() / n;
        return s;
    }
    const LVec o = toL(f.points[0]);
    for (size_t k = 1; k + 1 < f.points.size(); ++k) {
        const LVec b = toL(f.points[k]), c = toL(f.points[k + 1]);
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j)
                s.push_back(o + (b - o) * ((long double)i / n) + (c - o) * ((long double)j / n));
        h = std::max({h, (b - o).norm() / n, (c - o).norm() / n, (c - b).norm() / n});
    }
    return s;
}

Vec3 rnd(std::mt19937_64& rng, double s) {
    std::uniform_real_distribution<double> u(-1, 1);
    return Vec3(u(rng), u(rng), u(rng)) * s;
}

// A random convex planar polygon: a regular-ish k-gon in a random plane, CCW about its normal.
std::vector<Vec3> randomPolygon(std::mt19937_64& rng, int k, const Vec3& c, double r) {
    const Vec3 n = rnd(rng, 1).normalized(), u = n.unitOrthogonal(), w = n.cross(u);
    std::vector<Vec3> p;
    const double phase = std::uniform_real_distribution<double>(0, 1)(rng);
    for (int i = 0; i < k; ++i) {
        const double a = 2 * M_PI * (i + phase) / k;
        p.push_back(c + r * (std::cos(a) * u + std::sin(a) * w));
    }
    return p;
}

FeatureGeometry randomFeature(std::mt19937_64& rng, FeatureType t, const Vec3& c, double s) {
    FeatureGeometry f{t, {}};
    if (t == FeatureType::Vertex) f.points = {c + rnd(rng, s)};
    else if (t == FeatureType::Edge) f.points = {c + rnd(rng, s), c + rnd(rng, s)};
    else f.points = randomPolygon(rng, 3 + int(rng() % 3), c + rnd(rng, 0.3 * s), s);
    return f;
}

}  // namespace

TEST_SUITE("feature_distance") {
    TEST_CASE("all six pair types vs dense sampling (long double), offsets and scales") {
        std::mt19937_64 rng(3);
        const FeatureType types[] = {FeatureType::Vertex, FeatureType::Edge, FeatureType::Face};
        for (double scale : {1e-3, 1.0, 1e3}) {
            for (double offset : {0.0, 1e4, 1e6}) {
                for (FeatureType ta : types) {
                    for (FeatureType tb : types) {
                        for (int k = 0; k < 6; ++k) {
                            const Vec3 base = Vec3(1, -2, 3).normalized() * offset;
                            const FeatureGeometry a = randomFeature(rng, ta, base, scale);
                            const FeatureGeometry b = randomFeature(rng, tb, base + rnd(rng, 1.5 * scale), scale);
                            const FeatureDistanceResult r = featureDistance(a, b);
                            REQUIRE(r.valid);
                            long double ha, hb;
                            const int n = (ta == FeatureType::Face && tb == FeatureType::Face) ? 24 : 60;
                            const auto sa = samples(a, n, ha), sb = samples(b, n, hb);
                            long double best = INFINITY;
                            for (const LVec& p : sa)
                                for (const LVec& q : sb) best = std::min(best, (p - q).norm());
                            CAPTURE(nameOf(r.type));
                            CAPTURE(scale);
                            CAPTURE(offset);
                            const double round = 1e-12 * (scale + offset);
                            // Sampled points are feature points: the true minimum is no larger...
                            CHECK(r.distance <= (double)best + round);
                            // ...and the true closest pair is within ha + hb of a sampled pair.
                            CHECK(r.distance >= (double)(best - ha - hb) - round);
                            CHECK(std::abs((r.pointA - r.pointB).norm() - r.distance) <= round);
                            if (r.normalDefined) CHECK(std::abs(r.normal.norm() - 1) < 1e-12);
                        }
                    }
                }
            }
        }
    }

    TEST_CASE("exact small cases and the normal rule") {
        const std::vector<Vec3> square = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 2, 0), Vec3(0, 2, 0)};
        // V–F above the interior: projection, normal = -(B's outward normal) = from A toward B.
        FeatureDistanceResult r = featureDistance({FeatureType::Vertex, {Vec3(1, 1, 3)}}, {FeatureType::Face, square});
        CHECK(r.type == ContactType::VF);
        CHECK(r.distance == 3.0);
        CHECK(r.pointB == Vec3(1, 1, 0));
        CHECK(r.normal == Vec3(0, 0, -1));
        CHECK(std::string(r.normalRule) == "face B");
        // F–V (face first): A's outward normal.
        r = featureDistance({FeatureType::Face, square}, {FeatureType::Vertex, {Vec3(1, 1, 3)}});
        CHECK(r.normal == Vec3(0, 0, 1));
        CHECK(r.pointA == Vec3(1, 1, 0));
        // V–F outside the face: nearest boundary point.
        r = featureDistance({FeatureType::Vertex, {Vec3(3, 1, 0)}}, {FeatureType::Face, square});
        CHECK(r.distance == 1.0);
        // E–F piercing: distance 0 at the crossing.
        r = featureDistance({FeatureType::Edge, {Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1)}}, {FeatureType::Face, square});
        CHECK(r.type == ContactType::EF);
        CHECK(r.distance == 0.0);
        CHECK(r.pointA == Vec3(0.5, 0.5, 0));
        // E–F parallel above the face: continuum, flagged.
        r = featureDistance({FeatureType::Edge, {Vec3(0.5, 0.5, 1), Vec3(1.5, 0.5, 1)}}, {FeatureType::Face, square});
        CHECK(r.distance == 1.0);
        CHECK(r.parallel);
        // F–F stacked: parallel, distance = gap, normal = A's face normal.
        std::vector<Vec3> top = square;
        for (Vec3& p : top) p.z() = 0.5;
        std::reverse(top.begin(), top.end());  // outward normal -z
        r = featureDistance({FeatureType::Face, top}, {FeatureType::Face, square});
        CHECK(r.type == ContactType::FF);
        CHECK(r.distance == 0.5);
        CHECK(r.parallel);
        CHECK(r.normal == Vec3(0, 0, -1));
        // F–F crossing: 0.
        r = featureDistance({FeatureType::Face, {Vec3(1, 1, -1), Vec3(1, 1, 1), Vec3(1, 3, 0)}},
                            {FeatureType::Face, square});
        CHECK(r.distance == 0.0);
        // E–E skew: closest points line, stable.
        r = featureDistance({FeatureType::Edge, {Vec3(-1, 0, 0), Vec3(1, 0, 0)}},
                            {FeatureType::Edge, {Vec3(0, -1, 2), Vec3(0, 1, 2)}});
        CHECK(r.type == ContactType::EE);
        CHECK(r.distance == 2.0);
        CHECK(r.normal == Vec3(0, 0, 1));
        CHECK(!r.normalUnstable);
        // E–E crossing exactly: cross product fallback, flagged unstable.
        r = featureDistance({FeatureType::Edge, {Vec3(-1, 0, 0), Vec3(1, 0, 0)}},
                            {FeatureType::Edge, {Vec3(0, -1, 0), Vec3(0, 1, 0)}});
        CHECK(r.distance == 0.0);
        CHECK(r.normalUnstable);
        CHECK(std::string(r.normalRule) == "edge cross product");
        CHECK(std::abs(r.normal.z()) == 1.0);
        // E–E parallel overlapping / disjoint.
        r = featureDistance({FeatureType::Edge, {Vec3(0, 0, 0), Vec3(2, 0, 0)}},
                            {FeatureType::Edge, {Vec3(1, 1, 0), Vec3(3, 1, 0)}});
        CHECK(r.parallel);
        CHECK(r.distance == doctest::Approx(1.0));
        CHECK(r.normal.isApprox(Vec3(0, 1, 0)));
        r = featureDistance({FeatureType::Edge, {Vec3(0, 0, 0), Vec3(2, 0, 0)}},
                            {FeatureType::Edge, {Vec3(5, 0, 0), Vec3(3, 0, 0)}});
        CHECK(r.distance == doctest::Approx(1.0));
        CHECK(r.pointA == Vec3(2, 0, 0));
        CHECK(r.pointB == Vec3(3, 0, 0));
        // V–V coincident: no normal.
        r = featureDistance({FeatureType::Vertex, {Vec3(1, 2, 3)}}, {FeatureType::Vertex, {Vec3(1, 2, 3)}});
        CHECK(r.type == ContactType::VV);
        CHECK(!r.normalDefined);
        CHECK(r.normalUnstable);
        // V–E nearly touching: defined but unstable.
        r = featureDistance({FeatureType::Vertex, {Vec3(0.5, 1e-12, 0)}},
                            {FeatureType::Edge, {Vec3(0, 0, 0), Vec3(1, 0, 0)}});
        CHECK(r.type == ContactType::VE);
        CHECK(r.normalDefined);
        CHECK(r.normalUnstable);
    }

    TEST_CASE("the type and normal follow the features that hold the closest points") {
        // Reproducer (polyhedron_plane/contact_types pair 04): an edge under a face, its highest
        // point outside the face's side x = 0.5. The closest pair is edge–edge (p_B on that side),
        // so the normal is the closest-point line, not the face normal.
        const std::vector<Vec3> face = {Vec3(-0.5, -0.5, 0.5), Vec3(-0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.5),
                                        Vec3(0.5, -0.5, 0.5)};
        FeatureDistanceResult r = featureDistance({FeatureType::Edge, {Vec3(-0.4, 0.3, 0.0), Vec3(0.7, -0.2, 0.15)}},
                                                  {FeatureType::Face, face});
        CHECK(r.type == ContactType::EE);
        CHECK(r.realizedB == FeatureType::Edge);
        CHECK(r.pointB.x() == doctest::Approx(0.5));
        CHECK(std::string(r.normalRule) == "closest points");
        CHECK((r.normal - (r.pointB - r.pointA) / r.distance).norm() <= 1e-15);
        // Under the face's interior a sloping edge is closest at its upper endpoint: vertex–face;
        // only an edge parallel to the face is edge–face (one of a continuum of closest pairs).
        r = featureDistance({FeatureType::Edge, {Vec3(-0.4, 0.3, 0.0), Vec3(0.3, -0.2, 0.15)}},
                            {FeatureType::Face, face});
        CHECK(r.type == ContactType::VF);
        CHECK(r.pointA == Vec3(0.3, -0.2, 0.15));
        r = featureDistance({FeatureType::Edge, {Vec3(-0.4, 0.3, 0.1), Vec3(0.3, -0.2, 0.1)}},
                            {FeatureType::Face, face});
        CHECK(r.type == ContactType::EF);
        CHECK(std::string(r.normalRule) == "face B");
        CHECK(r.distance == doctest::Approx(0.4));
        // A vertex beside a face: vertex–edge; beyond its corner: vertex–vertex.
        const std::vector<Vec3> square = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 2, 0), Vec3(0, 2, 0)};
        r = featureDistance({FeatureType::Vertex, {Vec3(3, 1, 1)}}, {FeatureType::Face, square});
        CHECK(r.type == ContactType::VE);
        r = featureDistance({FeatureType::Vertex, {Vec3(3, 3, 1)}}, {FeatureType::Face, square});
        CHECK(r.type == ContactType::VV);
        CHECK(r.pointB == Vec3(2, 2, 0));
        // Edges whose closest points are endpoints: vertex–edge, vertex–vertex.
        r = featureDistance({FeatureType::Edge, {Vec3(0, 0, 0), Vec3(1, 0, 0)}},
                            {FeatureType::Edge, {Vec3(2, -1, 1), Vec3(2, 1, 1)}});
        CHECK(r.type == ContactType::VE);
        r = featureDistance({FeatureType::Edge, {Vec3(0, 0, 0), Vec3(1, 0, 0)}},
                            {FeatureType::Edge, {Vec3(2, 0, 0), Vec3(3, 1, 0)}});
        CHECK(r.type == ContactType::VV);
        // Parallel pairs keep their features: stacked faces, an edge above a face.
        std::vector<Vec3> top = square;
        for (Vec3& p : top) p.z() = 0.5;
        std::reverse(top.begin(), top.end());
        CHECK(featureDistance({FeatureType::Face, top}, {FeatureType::Face, square}).type == ContactType::FF);
        CHECK(featureDistance({FeatureType::Edge, {Vec3(0.5, 0.5, 1), Vec3(1.5, 0.5, 1)}}, {FeatureType::Face, square})
                  .type == ContactType::EF);
    }

    TEST_CASE("random pairs: the normal is the closest-point direction whenever the features are apart") {
        // The property the contact_types figure broke: for every pair at a distance, the contact
        // normal is parallel to p_B - p_A (a face's normal only when the closest points lie along it).
        std::mt19937_64 rng(77);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        const auto point = [&] { return Vec3(u(rng), u(rng), u(rng)); };
        int checked = 0;
        for (int trial = 0; trial < 3000; ++trial) {
            const FeatureType ta = FeatureType(1 + trial % 3), tb = FeatureType(1 + (trial / 3) % 3);
            const auto feature = [&](FeatureType t, const Vec3& offset) {
                FeatureGeometry f{t, {}};
                if (t == FeatureType::Vertex) f.points = {offset + point()};
                else if (t == FeatureType::Edge) f.points = {offset + point(), offset + point()};
                else {  // a random triangle
                    f.points = {offset + point(), offset + point(), offset + point()};
                }
                return f;
            };
            const FeatureGeometry a = feature(ta, Vec3::Zero()), b = feature(tb, Vec3(0, 0, 1.5));
            const FeatureDistanceResult r = featureDistance(a, b);
            REQUIRE(r.valid);
            if (r.distance < 1e-6 || r.parallel || !r.normalDefined) continue;
            CAPTURE(trial);
            CHECK(std::abs(r.normal.dot((r.pointB - r.pointA) / r.distance)) >= 1 - 1e-9);
            ++checked;
        }
        CHECK(checked > 2000);
    }

    TEST_CASE("invalid features") {
        CHECK(!featureDistance({FeatureType::Edge, {Vec3::Zero()}}, {FeatureType::Vertex, {Vec3::Zero()}}).valid);
        CHECK(!featureDistance({FeatureType::Vertex, {Vec3(NAN, 0, 0)}}, {FeatureType::Vertex, {Vec3::Zero()}}).valid);
        CHECK(
            !featureDistance({FeatureType::Face, {Vec3::Zero(), Vec3::UnitX()}}, {FeatureType::Vertex, {Vec3::Zero()}})
                 .valid);
        // Zero-area face: answered as its boundary polyline.
        const FeatureDistanceResult r = featureDistance(
            {FeatureType::Vertex, {Vec3(1, 1, 0)}}, {FeatureType::Face, {Vec3::Zero(), Vec3::UnitX(), Vec3(2, 0, 0)}});
        CHECK(r.valid);
        CHECK(r.distance == doctest::Approx(1.0));
    }
}
