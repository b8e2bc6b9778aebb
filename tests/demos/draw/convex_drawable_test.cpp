// Drawing geometry helpers of demos/draw/convex_drawable.h that decide what a figure shows:
// whether a point is seen through a body (contact markers drawn faded in the drop figures).
#include <doctest/doctest.h>

#include "demos/draw/convex_drawable.h"

using namespace cdlab;
using namespace cdlab::demos;

namespace {

// The cube [-1, 1]^3 as face planes.
std::vector<Plane> cube() {
    std::vector<Plane> faces;
    for (int k = 0; k < 3; ++k)
        for (double s : {-1.0, 1.0}) faces.push_back({s * Vec3::Unit(k), 1.0});
    return faces;
}

}  // namespace

TEST_CASE("behindBody: a point on the far side of a body is behind it, on the near side or the silhouette it is not") {
    for (const auto projection : {render::Camera::Projection::Orthographic, render::Camera::Projection::Perspective}) {
        render::Camera cam;
        cam.projection = projection;
        cam.eye = Vec3(0.3, 0.2, 10.0);  // above the cube, looking down
        cam.target = Vec3(0.3, 0.2, 0.0);
        const double tol = 1e-6;
        CHECK_FALSE(behindBody(cam, Vec3(0.3, 0.2, 1.0), cube(), tol));  // top face, towards the eye
        CHECK(behindBody(cam, Vec3(0.3, 0.2, -1.0), cube(), tol));       // bottom face: 2 units of cube above
        CHECK(behindBody(cam, Vec3(0.3, 0.2, -1.5), cube(), tol));       // below the cube, outside it
        CHECK_FALSE(behindBody(cam, Vec3(3.0, 0.2, -1.0), cube(), tol));  // beside the cube
        CHECK_FALSE(behindBody(cam, Vec3(0.3, 0.2, 2.0), cube(), tol));   // between the cube and the eye
    }
    // A corner on the silhouette of a cube seen along its diagonal is seen; the opposite corner is not.
    render::Camera diagonal;
    diagonal.projection = render::Camera::Projection::Orthographic;
    diagonal.eye = Vec3(5, 5, 5);
    CHECK_FALSE(behindBody(diagonal, Vec3(1, 1, 1), cube(), 1e-9));
    CHECK_FALSE(behindBody(diagonal, Vec3(1, -1, 1), cube(), 1e-9));  // silhouette corner: the ray grazes
    CHECK(behindBody(diagonal, Vec3(-1, -1, -1), cube(), 1e-9));
    // A 2D camera has no depth: nothing is behind.
    CHECK_FALSE(behindBody(render::Camera::twoD(0, 0, 4), Vec3(0, 0, -1), cube(), 1e-9));
}
