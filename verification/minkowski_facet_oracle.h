// Test-only support mappings and brute-force oracles for the GJK / EPA tests.
// The oracles share NO code with core/gjk_epa/gjk.h, core/gjk_epa/epa.h or core/gjk_epa/simplex_solver.h: they
// enumerate the facets of the Minkowski difference {a_i - b_j} by triples in long double.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/base/types.h"
#include "verification/long_double_geometry.h"

namespace cdlab::test {

// ---- Tiny support mappings (world frame) ------------------------------------------------------

/// Convex hull of a vertex list; linear-scan support, first maximum wins on ties.
struct SupportPolytope {
    std::vector<Vec3> vertices;
    Vec3 support(const Vec3& d) const {
        int best = 0;
        double bestDot = vertices[0].dot(d);
        for (int i = 1; i < static_cast<int>(vertices.size()); ++i) {
            const double s = vertices[i].dot(d);
            if (s > bestDot) {
                bestDot = s;
                best = i;
            }
        }
        return vertices[best];
    }
};

struct SupportSphere {
    Vec3 center;
    double radius;
    Vec3 support(const Vec3& d) const {
        const double n = d.norm();
        return n > 0.0 ? Vec3(center + (radius / n) * d) : center;
    }
};

/// Axis-aligned box; ties (d_k = 0) go to the + side, so supports return corners only.
struct SupportBox {
    Vec3 center;
    Vec3 half;
    Vec3 support(const Vec3& d) const {
        return Vec3(center.x() + (d.x() >= 0.0 ? half.x() : -half.x()),
                    center.y() + (d.y() >= 0.0 ? half.y() : -half.y()),
                    center.z() + (d.z() >= 0.0 ? half.z() : -half.z()));
    }
    std::vector<Vec3> corners() const {
        std::vector<Vec3> c;
        for (int i = 0; i < 8; ++i)
            c.push_back(center + Vec3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                                      (i & 4) ? half.z() : -half.z()));
        return c;
    }
};

struct SupportPoint {
    Vec3 p;
    Vec3 support(const Vec3&) const { return p; }
};

struct SupportSegment {
    Vec3 a, b;
    Vec3 support(const Vec3& d) const { return d.dot(b - a) > 0.0 ? b : a; }
};

// ---- Random polytopes -------------------------------------------------------------------------

/// n points on a randomly rotated ellipsoid with radii size * (0.3..1), centered at `center`.
inline std::vector<Vec3> randomPolytope(std::mt19937_64& rng, int n, double size, const Vec3& center) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::uniform_real_distribution<double> radius(0.3, 1.0);
    const Vec3 radii(radius(rng), radius(rng), radius(rng));
    Quat q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    q.normalize();
    std::vector<Vec3> v;
    for (int i = 0; i < n; ++i) {
        Vec3 u(gauss(rng), gauss(rng), gauss(rng));
        u.normalize();
        v.push_back(center + q * Vec3(size * radii.cwiseProduct(u)));
    }
    return v;
}

inline Vec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    Vec3 u(gauss(rng), gauss(rng), gauss(rng));
    return u.normalized();
}

// ---- Long double brute-force oracle -----------------------------------------------------------

using long_double::LVec;
using long_double::toL;
using long_double::triangleDistanceL;

struct HullOracle {
    bool inside = false;         ///< origin strictly inside conv{a_i - b_j}
    long double distance = 0;    ///< origin to hull when outside
    long double depth = 0;       ///< origin to hull boundary when inside
    LVec normal = LVec::Zero();  ///< outward unit normal of the nearest facet when inside
    int facets = 0;
};

/// Facet enumeration by triples: (i, j, k) spans a facet plane iff every point lies on one side.
inline HullOracle hullOracle(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    std::vector<LVec> p;
    long double scale = 0;
    for (const Vec3& x : a)
        for (const Vec3& y : b) {
            p.push_back(toL(x) - toL(y));
            scale = std::max(scale, p.back().norm());
        }
    const int n = static_cast<int>(p.size());
    HullOracle o;
    o.inside = true;
    long double minOffset = INFINITY;
    long double minDistance = INFINITY;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            for (int k = j + 1; k < n; ++k) {
                LVec nrm = (p[j] - p[i]).cross(p[k] - p[i]);
                const long double len = nrm.norm();
                if (!(len > 1e-15L * scale * scale)) continue;
                nrm /= len;
                const long double off = nrm.dot(p[i]);
                // coplanar points within 1e-15 scale count as on the plane
                const long double tol = 1e-15L * scale;
                bool pos = false, neg = false;
                for (int m = 0; m < n && !(pos && neg); ++m) {
                    const long double s = nrm.dot(p[m]) - off;
                    if (s > tol) pos = true;
                    if (s < -tol) neg = true;
                }
                if (pos && neg) continue;
                if (pos) nrm = -nrm;  // outward: all points behind the plane
                const long double offset = nrm.dot(p[i]);
                ++o.facets;
                if (offset <= 0) o.inside = false;
                if (offset < minOffset) {
                    minOffset = offset;
                    o.normal = nrm;
                }
                minDistance = std::min(minDistance, triangleDistanceL(p[i], p[j], p[k]));
            }
    o.depth = o.inside ? minOffset : 0;
    o.distance = o.inside ? 0 : minDistance;
    return o;
}

/// Support function of A - B, h(n) = max_i a_i·n - min_j b_j·n, in long double. Both sides are
/// taken relative to a_0 so that a 1e6 offset does not swamp a 1e-3 shape.
inline long double supportValueL(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const Vec3& n) {
    const LVec nl = toL(n);
    const LVec ref = toL(a[0]);
    long double ha = -INFINITY, hb = INFINITY;
    for (const Vec3& x : a) ha = std::max(ha, (toL(x) - ref).dot(nl));
    for (const Vec3& y : b) hb = std::min(hb, (toL(y) - ref).dot(nl));
    return ha - hb;
}

}  // namespace cdlab::test
