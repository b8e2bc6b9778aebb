// Test-only helpers for the bounding-volume tests (bounding_volume_fit, bounding_sphere, kdop,
// swept_sphere). Shares no code with core/: long double arithmetic, brute force.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "core/base/types.h"
#include "verification/intersection_oracles.h"

namespace bvoracle {

// The long double vector kit (V3, dot, cross, norm, distPointSegment) is the intersection oracles'.
using oracle::LD;
using V = oracle::V3;
using cdlab::Mat3;
using cdlab::Triangle;
using cdlab::Vec3;
using oracle::cross;
using oracle::distPointSegment;
using oracle::dot;
using oracle::norm;

/// Random unit quaternion (uniform enough for tests).
inline Eigen::Quaterniond randomRotation(std::mt19937& rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    return q;
}

/// Points uniform in [-1, 1]^3 times scale, rotated, plus offset.
inline std::vector<Vec3> randomCloud(std::mt19937& rng, int n, const Vec3& stretch, double scale, const Vec3& offset) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Eigen::Quaterniond q = randomRotation(rng);
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i) {
        const Vec3 local(u(rng) * stretch.x(), u(rng) * stretch.y(), u(rng) * stretch.z());
        pts.push_back(offset + scale * (q * local));
    }
    return pts;
}

/// Closed box mesh [-h, h] (12 triangles; the +x face split into 2 * k * k triangles when k > 1
/// to test tessellation independence), rotated by q, translated by offset.
inline std::vector<Triangle> boxMesh(const Vec3& h, const Eigen::Quaterniond& q, const Vec3& offset, int k = 1) {
    std::vector<Triangle> tris;
    auto map = [&](const Vec3& p) { return Vec3(offset + q * p.cwiseProduct(h)); };
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = -1; side <= 1; side += 2) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const int n = (axis == 0 && side == 1) ? k : 1;
            for (int i = 0; i < n; ++i) {
                for (int j = 0; j < n; ++j) {
                    auto corner = [&](int a, int b) {
                        Vec3 p;
                        p[axis] = side;
                        p[u] = -1.0 + 2.0 * (i + a) / n;
                        p[v] = -1.0 + 2.0 * (j + b) / n;
                        return map(p);
                    };
                    tris.push_back({corner(0, 0), corner(1, 0), corner(1, 1)});
                    tris.push_back({corner(0, 0), corner(1, 1), corner(0, 1)});
                }
            }
        }
    }
    return tris;
}

/// Vertices of a triangle list (with repeats).
inline std::vector<Vec3> vertices(const std::vector<Triangle>& tris) {
    std::vector<Vec3> v;
    for (const Triangle& t : tris) {
        v.push_back(t.a);
        v.push_back(t.b);
        v.push_back(t.c);
    }
    return v;
}

/// Largest |coordinate| over points (for tolerances relative to the magnitude of the input).
inline double magnitude(const std::vector<Vec3>& pts) {
    double m = 0.0;
    for (const Vec3& p : pts) m = std::max(m, p.cwiseAbs().maxCoeff());
    return m;
}

}  // namespace bvoracle
