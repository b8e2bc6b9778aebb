#include "app/bench/bench_inputs.h"

#include <random>

#include "core/geometry/convex_hull.h"
#include "app/bench/bench_measure.h"

namespace cdlab::demos {

PolytopeShape polytopeOf(const std::vector<Vec3>& v) {
    const HullResult h = convexHull(v);
    return h.ok() ? PolytopeShape(h.polyhedron) : PolytopeShape(v);
}

std::vector<PolyPair> polyPairs(int n, int count, double offset, std::uint64_t seed, double moveBy) {
    std::mt19937_64 rng(seed);
    std::vector<PolyPair> pairs;
    for (int i = 0; i < count; ++i) {
        PolyPair p;
        p.va = ellipsoidPoints(rng, n);
        p.vb = ellipsoidPoints(rng, n);
        const Vec3 shift = offset * randomUnit(rng);
        for (Vec3& x : p.vb) x += shift;
        pairs.push_back(std::move(p));
    }
    if (moveBy > 0.0) {  // warm-start set: the same pairs moved slightly (next frame)
        std::mt19937_64 move(seed ^ 0x5DEECE66Dull);
        for (PolyPair& p : pairs) {
            const Vec3 d = moveBy * randomUnit(move);
            for (Vec3& x : p.vb) x += d;
        }
    }
    for (PolyPair& p : pairs) {
        p.a = polytopeOf(p.va);
        p.b = polytopeOf(p.vb);
        p.oracle = minkowskiOracle(p.va, p.vb);
    }
    return pairs;
}

std::vector<Vec3> boxCorners(const Transformed<BoxShape>& box) {
    std::vector<Vec3> c;
    const Vec3& h = box.shape.halfExtents;
    for (int i = 0; i < 8; ++i)
        c.push_back(
            box.transform.apply(Vec3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z())));
    return c;
}

std::vector<OrientedBoxPair> boxPairs(int count, double offset, bool touching, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> half(0.2, 1.0), lateral(-0.3, 0.3);
    std::vector<OrientedBoxPair> pairs;
    for (int i = 0; i < count; ++i) {
        OrientedBoxPair p;
        p.a.shape.halfExtents = Vec3(half(rng), half(rng), half(rng));
        p.b.shape.halfExtents = Vec3(half(rng), half(rng), half(rng));
        if (touching) {
            // Face x = +h_a of A against face x = -h_b of B, lateral shift inside both faces:
            // exact in binary (sums of doubles of similar size, then compared by the oracle).
            p.b.transform.position =
                Vec3(p.a.shape.halfExtents.x() + p.b.shape.halfExtents.x(), lateral(rng) * p.a.shape.halfExtents.y(),
                     lateral(rng) * p.a.shape.halfExtents.z());
        } else {
            p.a.transform.rotation = randomRotation(rng);
            p.b.transform.rotation = randomRotation(rng);
            p.b.transform.position = offset * randomUnit(rng);
        }
        p.va = boxCorners(p.a);
        p.vb = boxCorners(p.b);
        p.oracle = minkowskiOracle(p.va, p.vb);
        p.obbA = Obb{p.a.transform.position, p.a.shape.halfExtents, p.a.transform.rotation.toRotationMatrix()};
        p.obbB = Obb{p.b.transform.position, p.b.shape.halfExtents, p.b.transform.rotation.toRotationMatrix()};
        pairs.push_back(std::move(p));
    }
    return pairs;
}

}  // namespace cdlab::demos
