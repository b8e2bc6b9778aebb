// Distance between two unit cubes 1 apart along x, by cdlab's GJK: prints it and exits 0 when right.
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/geometry/shapes.h"
#include "core/gjk_epa/gjk.h"

int main() {
    std::vector<cdlab::Vec3> a, b;
    for (int i = 0; i < 8; ++i) {
        const cdlab::Vec3 corner(i & 1, (i >> 1) & 1, (i >> 2) & 1);
        a.push_back(corner);
        b.push_back(corner + cdlab::Vec3(2, 0, 0));
    }
    const cdlab::GjkResult r = cdlab::gjkDistance(cdlab::PolytopeShape(a), cdlab::PolytopeShape(b));
    std::printf("distance %.17g\n", r.distance);
    return std::abs(r.distance - 1.0) < 1e-15 ? 0 : 1;
}
