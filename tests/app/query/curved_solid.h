// A cylinder, cone, sphere or box of the curved-shape query tests, described by the numbers
// written into the query, with its own closed forms (support value, membership), sharing no code
// with the query.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "core/base/types.h"
#include "app/scene/json_reader.h"

namespace cdlab::test {

// A shape of the test, described by the numbers written into the query.
struct Solid {
    enum Kind { Cylinder, Cone, Sphere, Box } kind = Cylinder;
    cdlab::Vec3 c = cdlab::Vec3::Zero();
    double q[4] = {1, 0, 0, 0};  // w, x, y, z (unit)
    double h = 0, r = 0;         // half height and radius (box: half extents e)
    cdlab::Vec3 e = cdlab::Vec3::Zero();

    // The body axes, from the quaternion's rotation matrix written out.
    cdlab::Vec3 axis(int i) const {
        const double w = q[0], x = q[1], y = q[2], z = q[3];
        if (i == 0) return cdlab::Vec3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y));
        if (i == 1) return cdlab::Vec3(2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x));
        return cdlab::Vec3(2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
    }

    std::string json() const {
        std::ostringstream s;
        s.precision(17);
        const auto v = [&](const cdlab::Vec3& p) { s << "[" << p.x() << "," << p.y() << "," << p.z() << "]"; };
        if (kind == Sphere) {
            s << R"({"sphere":{"center":)";
            v(c);
            s << R"(,"radius":)" << r << "}}";
            return s.str();
        }
        s << (kind == Cylinder ? R"({"cylinder":{)" : kind == Cone ? R"({"cone":{)" : R"({"box":{)");
        if (kind == Box) {
            s << R"("half_extents":)";
            v(e);
        } else {
            s << R"("radius":)" << r << R"(,"half_height":)" << h;
        }
        s << R"(,"position":)";
        v(c);
        s << R"(,"rotation":[)" << q[0] << "," << q[1] << "," << q[2] << "," << q[3] << "]}}";
        return s.str();
    }

    // max over the solid of n·x.
    double supportValue(const cdlab::Vec3& n) const {
        if (kind == Sphere) return n.dot(c) + r * n.norm();
        if (kind == Box) {
            double v = n.dot(c);
            for (int i = 0; i < 3; ++i) v += e[i] * std::abs(n.dot(axis(i)));
            return v;
        }
        const cdlab::Vec3 u = axis(1);
        const double along = n.dot(u);
        const double across = (n - along * u).norm();  // not sqrt(|n|² − along²): 1e-8 from rounding near the axis
        if (kind == Cylinder) return n.dot(c) + h * std::abs(along) + r * across;
        return n.dot(c) + std::max(h * along, -h * along + r * across);  // apex or base rim
    }

    // Distance of p outside the solid along its axis and across it (0 inside): a membership test.
    double outside(const cdlab::Vec3& p) const {
        if (kind == Sphere) return std::max(0.0, (p - c).norm() - r);
        if (kind == Box) {
            double m = 0;
            for (int i = 0; i < 3; ++i) m = std::max(m, std::abs((p - c).dot(axis(i))) - e[i]);
            return m;
        }
        const cdlab::Vec3 u = axis(1);
        const double y = (p - c).dot(u);
        const double radial = (p - c - y * u).norm();
        const double rAt = kind == Cylinder ? r : r * (h - y) / (2 * h);  // the cone narrows to its apex
        return std::max({0.0, std::abs(y) - h, radial - rAt});
    }
};

inline Solid randomSolid(std::mt19937_64& rng, Solid::Kind kind, const cdlab::Vec3& centre) {
    std::uniform_real_distribution<double> u(-1, 1), size(0.3, 1.5);
    Solid s;
    s.kind = kind;
    s.c = centre;
    Eigen::Vector4d q(u(rng), u(rng), u(rng), u(rng));
    q.normalize();
    for (int i = 0; i < 4; ++i) s.q[i] = q[i];
    s.h = size(rng);
    s.r = size(rng);
    s.e = cdlab::Vec3(size(rng), size(rng), size(rng));
    return s;
}

inline cdlab::Vec3 vecOf(const demos::Json& j) { return cdlab::Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }

}  // namespace cdlab::test
