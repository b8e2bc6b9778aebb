#include "core/closest/closest_point_box.h"

#include <algorithm>
#include <cmath>

namespace cdlab {

std::string regionName(const BoxRegionResult& r) {
    if (!r.valid) return "invalid";
    if (r.dimension == 3) return "inside";
    static const char* kNames[3] = {"vertex ", "edge ", "face "};
    std::string name = kNames[r.dimension];
    const char* axes = "xyz";
    for (int i = 0; i < 3; ++i)
        if (r.tests[std::size_t(i)].side != 0) name += std::string(r.tests[std::size_t(i)].side > 0 ? "+" : "−") + axes[i];
    return name;
}

BoxRegionResult closestPointOnBox(const Vec3& p, const Obb& box) {
    BoxRegionResult r;
    if (!p.allFinite() || !box.center.allFinite() || !box.axes.allFinite() || !box.halfExtents.allFinite() ||
        (box.halfExtents.array() < 0.0).any())
        return r;
    r.valid = true;
    const Vec3 d = p - box.center;
    Vec3 local;
    int outside = 0;
    for (int i = 0; i < 3; ++i) {
        BoxAxisTest& t = r.tests[std::size_t(i)];
        t.coordinate = d.dot(box.axes.col(i));
        t.halfExtent = box.halfExtents[i];
        t.side = t.coordinate > t.halfExtent ? 1 : t.coordinate < -t.halfExtent ? -1 : 0;
        outside += t.side != 0;
        local[i] = std::clamp(t.coordinate, -t.halfExtent, t.halfExtent);
    }
    r.dimension = 3 - outside;
    r.point = outside == 0 ? p : Vec3(box.center + box.axes * local);
    r.distance = outside == 0 ? 0.0 : (p - r.point).norm();
    // The feature's corners: the fixed sides on the outside axes, both sides on the others.
    if (outside > 0)
        for (int k = 0; k < 8; ++k) {
            bool on = true;
            for (int i = 0; i < 3; ++i) {
                const int side = r.tests[std::size_t(i)].side;
                if (side != 0 && ((k >> i) & 1) != (side > 0 ? 1 : 0)) on = false;
            }
            if (on) r.corners.push_back(k);
        }
    return r;
}

}  // namespace cdlab
