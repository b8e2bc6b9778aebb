#include "core/overlap/sat_tests.h"

#include <algorithm>
#include <cmath>

#include "core/base/aabb_ops.h"

namespace cdlab {

namespace {

// Epsilon added to |R_ij| (OBB-OBB, Ericson §4.4.1) and to |d_i| (segment-AABB, Ericson
// §5.3.3), relative to unit cosines / the segment length. WHY: when an edge of A is parallel
// to an edge of B (or the segment to a box axis), L = A_i x B_j is (nearly) the zero vector.
// Then both sides of |T . L| > rA + rB are tiny, and rounding noise in R (about 1e-16 per
// entry, times |T|) can exceed rA + rB and report a separation that does not exist. Adding
// eps to every |R_ij| raises the right-hand side by eps * (sum of extents), which dominates
// that noise for |T| up to ~1e6 times the extents, while a nondegenerate axis is widened by a
// relative 1e-9 only. Such an axis is never needed: with parallel edges the face axes decide.
constexpr double kSatParallelEpsilon = 1e-9;

bool validObb(const Obb& box) {
    return box.center.allFinite() && box.axes.allFinite() && box.halfExtents.allFinite() &&
           (box.halfExtents.array() >= 0.0).all();
}

// Records a step and says whether it separates: intervals [minA, maxA] and [minB, maxB] are
// disjoint (strictly: touching does not separate).
bool axisStep(SatAxisKind kind, int ia, int ib, const Vec3& axis, double minA, double maxA, double minB, double maxB,
              SatTrace* trace, SatResult& result) {
    SatAxisStep step;
    step.kind = kind;
    step.indexA = ia;
    step.indexB = ib;
    step.axis = axis;
    step.minA = minA;
    step.maxA = maxA;
    step.minB = minB;
    step.maxB = maxB;
    step.separating = minB > maxA || maxB < minA;
    if (trace) trace->steps.push_back(step);
    if (step.separating) result.separatingAxis = step;
    return step.separating;
}

// Segment p0p1 against the box [-e, e] (box frame). toWorld maps box-frame axes to world.
SatResult segmentBoxLocal(const Vec3& p0, const Vec3& p1, const Vec3& e, const Mat3& toWorld, SatTrace* trace) {
    SatResult result;
    // Ericson §5.3.3: segment midpoint m and half-length vector d.
    const Vec3 m = 0.5 * (p0 + p1);
    const Vec3 d = p1 - m;
    Vec3 ad = d.cwiseAbs();
    // Box face axes: |m_i| > e_i + |d_i| separates.
    for (int i = 0; i < 3; ++i)
        if (axisStep(SatAxisKind::FaceA, i, -1, toWorld.col(i), -e[i], e[i], m[i] - ad[i], m[i] + ad[i], trace, result))
            return result;
    // Cross axes e_i x d: the epsilon guards the near-parallel case (see kSatParallelEpsilon).
    ad.array() += kSatParallelEpsilon * ad.maxCoeff();
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        // L = e_i x d, with L_j = -d_k, L_k = d_j: m . L = m_k d_j - m_j d_k;
        // the box radius is e_j |d_k| + e_k |d_j|; the segment projects to one point (d . L = 0).
        const double c = m[k] * d[j] - m[j] * d[k];
        const double r = e[j] * ad[k] + e[k] * ad[j];
        Vec3 local = Vec3::Zero();
        local[i] = 1.0;
        if (axisStep(SatAxisKind::EdgeEdge, i, 0, toWorld * local.cross(d), -r, r, c, c, trace, result)) return result;
    }
    result.hit = true;
    return result;
}

// Projection interval of triangle vertices (relative to the box center) on axis.
void projectTriangle(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& axis, double& lo, double& hi) {
    const double p0 = v0.dot(axis), p1 = v1.dot(axis), p2 = v2.dot(axis);
    lo = std::min({p0, p1, p2});
    hi = std::max({p0, p1, p2});
}

}  // namespace

SatResult testAabbAabb(const Aabb& a, const Aabb& b, SatTrace* trace) {
    SatResult result;
    if (!isValidBox(a) || !isValidBox(b)) return result;
    const Vec3 c = 0.5 * (a.min + a.max);
    for (int i = 0; i < 3; ++i)
        if (axisStep(SatAxisKind::FaceA, i, -1, Vec3::Unit(i), a.min[i] - c[i], a.max[i] - c[i], b.min[i] - c[i],
                     b.max[i] - c[i], trace, result))
            return result;
    result.hit = true;
    return result;
}

SatResult testSegmentAabb(const Segment& segment, const Aabb& box, SatTrace* trace) {
    if (!isValidBox(box) || !segment.a.allFinite() || !segment.b.allFinite()) return {};
    const Vec3 c = 0.5 * (box.min + box.max);
    const Vec3 e = box.max - c;
    return segmentBoxLocal(segment.a - c, segment.b - c, e, Mat3::Identity(), trace);
}

SatResult testSegmentObb(const Segment& segment, const Obb& box, SatTrace* trace) {
    if (!validObb(box) || !segment.a.allFinite() || !segment.b.allFinite()) return {};
    const Mat3 toLocal = box.axes.transpose();
    return segmentBoxLocal(toLocal * (segment.a - box.center), toLocal * (segment.b - box.center), box.halfExtents,
                           box.axes, trace);
}

SatResult testTriangleAabb(const Triangle& tri, const Aabb& box, SatTrace* trace) {
    SatResult result;
    if (!isValidBox(box) || !tri.a.allFinite() || !tri.b.allFinite() || !tri.c.allFinite()) return result;
    // Ericson §5.2.9: move the box to the origin.
    const Vec3 c = 0.5 * (box.min + box.max);
    const Vec3 e = box.max - c;
    const Vec3 v0 = tri.a - c, v1 = tri.b - c, v2 = tri.c - c;
    const Vec3 f[3] = {v1 - v0, v2 - v1, v0 - v2};
    // Box radius on axis L: e . |L|.
    auto radius = [&](const Vec3& L) { return e.dot(L.cwiseAbs()); };
    double lo, hi;
    // Category 3: the 9 axes u_i x f_j. u_i x f_j has exact components (u_i is a unit
    // coordinate vector), so a parallel pair gives exactly the zero axis, which never
    // separates (all projections are 0).
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            const Vec3 L = Vec3::Unit(i).cross(f[j]);
            projectTriangle(v0, v1, v2, L, lo, hi);
            const double r = radius(L);
            if (axisStep(SatAxisKind::EdgeEdge, i, j, L, -r, r, lo, hi, trace, result)) return result;
        }
    }
    // Category 1: the box face normals (the triangle's bounding box against the box).
    for (int i = 0; i < 3; ++i) {
        projectTriangle(v0, v1, v2, Vec3::Unit(i), lo, hi);
        if (axisStep(SatAxisKind::FaceA, i, -1, Vec3::Unit(i), -e[i], e[i], lo, hi, trace, result)) return result;
    }
    // Category 2: the triangle normal (plane-box test, Ericson §5.2.3). All three vertices
    // project to n . v0 up to rounding; use the interval of all three to stay conservative.
    const Vec3 n = f[0].cross(f[1]);
    projectTriangle(v0, v1, v2, n, lo, hi);
    const double r = radius(n);
    if (axisStep(SatAxisKind::Normal, -1, -1, n, -r, r, lo, hi, trace, result)) return result;
    result.hit = true;
    return result;
}

SatResult testObbObb(const Obb& a, const Obb& b, SatTrace* trace) {
    SatResult result;
    if (!validObb(a) || !validObb(b)) return result;
    const Vec3& ea = a.halfExtents;
    const Vec3& eb = b.halfExtents;
    // Ericson §4.4.1: R expresses b's axes in a's frame, R_ij = A_i . B_j.
    const Mat3 R = a.axes.transpose() * b.axes;
    // Translation in a's frame.
    const Vec3 t = a.axes.transpose() * (b.center - a.center);
    // |R| plus epsilon: see kSatParallelEpsilon for why.
    const Mat3 absR = R.cwiseAbs().array() + kSatParallelEpsilon;

    // Axes A_i: ra = ea_i, rb = sum_j eb_j |R_ij|, distance t_i.
    for (int i = 0; i < 3; ++i) {
        const double rb = eb.dot(absR.row(i));
        if (axisStep(SatAxisKind::FaceA, i, -1, a.axes.col(i), -ea[i], ea[i], t[i] - rb, t[i] + rb, trace, result))
            return result;
    }
    // Axes B_j: ra = sum_i ea_i |R_ij|, rb = eb_j, distance t . R_col_j.
    for (int j = 0; j < 3; ++j) {
        const double ra = ea.dot(absR.col(j));
        const double s = t.dot(R.col(j));
        if (axisStep(SatAxisKind::FaceB, -1, j, b.axes.col(j), -ra, ra, s - eb[j], s + eb[j], trace, result))
            return result;
    }
    // Axes A_i x B_j (in a's frame L = e_i x R_col_j):
    //   ra = ea_i1 |R_i2j| + ea_i2 |R_i1j|,  rb = eb_j1 |R_ij2| + eb_j2 |R_ij1|,
    //   distance = t_i2 R_i1j - t_i1 R_i2j,  with i1, i2 and j1, j2 the other two indices.
    for (int i = 0; i < 3; ++i) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; ++j) {
            const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            const double ra = ea[i1] * absR(i2, j) + ea[i2] * absR(i1, j);
            const double rb = eb[j1] * absR(i, j2) + eb[j2] * absR(i, j1);
            const double s = t[i2] * R(i1, j) - t[i1] * R(i2, j);
            const Vec3 axis = a.axes.col(i).cross(b.axes.col(j));
            if (axisStep(SatAxisKind::EdgeEdge, i, j, axis, -ra, ra, s - rb, s + rb, trace, result)) return result;
        }
    }
    result.hit = true;
    return result;
}

}  // namespace cdlab
