// An engine developer's first program on cdlab's installed core (README, "Start here: engine
// developers"): a GJK distance, a box–box contact manifold and a ray cast. Built and run against a
// fresh `cmake --install` by tests/install/consumer_test.sh; it exits 1 if an answer is not the
// one printed in the comments.
#include <cdlab/core/cdlab.h>

#include <cmath>
#include <cstdio>

int main() {
    using cdlab::QueryShape, cdlab::Vec3;
    const QueryShape a = QueryShape::obb(Vec3(0, 0, 0), Vec3(0.5, 0.5, 0.5));  // unit cube at the origin
    const QueryShape b = QueryShape::sphere(Vec3(3, 0, 0), 1.0);
    const cdlab::PairResult gap = cdlab::pairQuery(a, b);  // GJK: distance 1.5, points (0.5,0,0), (2,0,0)
    std::printf("distance %g between (%g %g %g) and (%g %g %g)\n", gap.distance, gap.pointA.x(), gap.pointA.y(),
                gap.pointA.z(), gap.pointB.x(), gap.pointB.y(), gap.pointB.z());

    const QueryShape lid = QueryShape::obb(Vec3(0.2, 0.1, 0.9), Vec3(0.5, 0.5, 0.5));  // sunk 0.1 into a
    const cdlab::ContactResult contact = cdlab::contactQuery(a, lid);  // 4 points, depth 0.1, normal +z
    std::printf("contact: depth %g, normal (%g %g %g), %zu points\n", contact.depth, contact.normal.x(),
                contact.normal.y(), contact.normal.z(), contact.points.size());

    const cdlab::RayCastQueryResult ray = cdlab::rayCastQuery(Vec3(-5, 0, 0), Vec3(1, 0, 0), a, 100.0);  // t 4.5
    std::printf("ray: t %g at (%g %g %g)\n", ray.t, ray.point.x(), ray.point.y(), ray.point.z());
    const bool right = std::abs(gap.distance - 1.5) < 1e-12 && contact.colliding && contact.points.size() == 4 &&
                       std::abs(contact.depth - 0.1) < 1e-12 && ray.hit && std::abs(ray.t - 4.5) < 1e-12;
    return right ? 0 : 1;
}
