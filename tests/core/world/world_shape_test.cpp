// The world's shapes: mass properties against a voxel sum (an oracle that knows nothing of the
// closed forms), bounding boxes against the shapes' sampled surfaces.
#include <doctest/doctest.h>

#include <cmath>

#include "core/world/world_shape.h"

using namespace cdlab;

namespace {

// Volume and inertia about the origin of the solid given by `inside`, by the midpoint rule on an
// n³ grid over [-e, e]³.
template <class Inside>
void voxelSum(Inside inside, double e, int n, double& volume, Mat3& inertia) {
    const double h = 2 * e / n, dv = h * h * h;
    volume = 0;
    inertia = Mat3::Zero();
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const Vec3 p(-e + (i + 0.5) * h, -e + (j + 0.5) * h, -e + (k + 0.5) * h);
                if (!inside(p)) continue;
                volume += dv;
                inertia += dv * (p.squaredNorm() * Mat3::Identity() - p * p.transpose());
            }
}

}  // namespace

TEST_CASE("world shapes: capsule and sphere mass properties match a voxel sum to 1 %") {
    const double r = 0.3, h = 0.5;
    const WorldShapeBuild c = worldCapsule(h, r);
    REQUIRE(c.ok());
    double volume = 0;
    Mat3 inertia;
    voxelSum([&](const Vec3& p) { return Vec3(p.x(), p.y() - std::clamp(p.y(), -h, h), p.z()).norm() <= r; },
             h + r, 160, volume, inertia);
    CHECK(c.volume == doctest::Approx(volume).epsilon(0.01));
    for (int a = 0; a < 3; ++a) CHECK(c.unitInertia(a, a) == doctest::Approx(inertia(a, a)).epsilon(0.01));
    const WorldShapeBuild s = worldSphere(r);
    voxelSum([&](const Vec3& p) { return p.norm() <= r; }, r, 120, volume, inertia);
    CHECK(s.volume == doctest::Approx(volume).epsilon(0.01));
    CHECK(s.unitInertia(1, 1) == doctest::Approx(inertia(1, 1)).epsilon(0.01));
}

TEST_CASE("world shapes: box inertia closed form equals the polyhedron's exact integral, hulls are recentred") {
    const WorldShapeBuild b = worldBox(Vec3(0.5, 0.2, 0.1));
    double volume = 0;
    Mat3 inertia;
    voxelSum([&](const Vec3& p) { return std::abs(p.x()) <= 0.5 && std::abs(p.y()) <= 0.2 && std::abs(p.z()) <= 0.1; },
             0.5, 100, volume, inertia);
    CHECK(b.volume == doctest::Approx(volume).epsilon(0.02));
    for (int a = 0; a < 3; ++a) CHECK(b.unitInertia(a, a) == doctest::Approx(inertia(a, a)).epsilon(0.02));
    // A hull of an offset box: its body frame is centred, inputOrigin says where the input's was.
    std::vector<Vec3> pts;
    for (int k = 0; k < 8; ++k) pts.push_back(Vec3(k & 1 ? 3.0 : 1.0, k & 2 ? 0.5 : -0.5, k & 4 ? 2.25 : 2.0));
    const WorldShapeBuild hull = worldHull(pts);
    REQUIRE(hull.ok());
    CHECK((hull.inputOrigin - Vec3(-2.0, 0.0, -2.125)).norm() < 1e-12);
    CHECK(hull.shape.boundingRadius == doctest::Approx(Vec3(1.0, 0.5, 0.125).norm()));
}

TEST_CASE("world shapes: bounding boxes hold every sampled surface point and touch it on each side") {
    const Transform pose{Vec3(1, -2, 3), Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()))};
    const WorldShapeBuild shapes[] = {worldBox(Vec3(0.5, 0.2, 0.1)), worldCapsule(0.4, 0.2), worldSphere(0.3)};
    for (const WorldShapeBuild& s : shapes) {
        const Aabb box = worldBounds(s.shape, pose);
        Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
        for (int i = 0; i < 4000; ++i) {
            // Support points along a spiral of directions: the solid's extreme points.
            const double z = 1 - (i + 0.5) / 2000.0, t = i * 2.399963;
            const Vec3 d(std::sqrt(std::max(0.0, 1 - z * z)) * std::cos(t), std::sqrt(std::max(0.0, 1 - z * z)) * std::sin(t), z);
            const Vec3 local = pose.rotateInverse(d);
            Vec3 p;
            if (s.shape.kind == WorldShape::Kind::Box)
                p = s.shape.halfExtents.cwiseProduct(Vec3(local.x() >= 0 ? 1 : -1, local.y() >= 0 ? 1 : -1, local.z() >= 0 ? 1 : -1));
            else
                p = Vec3(0, s.shape.kind == WorldShape::Kind::Capsule ? (local.y() >= 0 ? s.shape.halfHeight : -s.shape.halfHeight) : 0, 0) +
                    s.shape.radius * local;
            const Vec3 w = pose.apply(p);
            lo = lo.cwiseMin(w);
            hi = hi.cwiseMax(w);
        }
        CAPTURE(nameOf(s.shape.kind));
        CHECK(((box.min - lo).array() <= 1e-12).all());
        CHECK(((hi - box.max).array() <= 1e-12).all());
        CHECK((box.min - lo).cwiseAbs().maxCoeff() < 0.01);
        CHECK((hi - box.max).cwiseAbs().maxCoeff() < 0.01);
    }
}
