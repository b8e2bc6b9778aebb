// Plain operations on axis-aligned boxes shared by the hierarchies, broad phases and primitive
// tests (core/bvh, core/broadphase, core/overlap): validity, union, containment, closed overlap and
// surface area. Exact comparisons (no centre subtraction); all but isValidBox and aabbOverlapClosed
// assume valid boxes (finite, min <= max).
#pragma once

#include "core/base/primitives.h"

namespace cdlab {

/// Finite bounds with min <= max on every axis (NaN bounds fail the comparison: invalid).
inline bool isValidBox(const Aabb& box) {
    return box.min.allFinite() && box.max.allFinite() && (box.min.array() <= box.max.array()).all();
}
/// The smallest box holding both.
inline Aabb unionOf(const Aabb& a, const Aabb& b) { return Aabb{a.min.cwiseMin(b.min), a.max.cwiseMax(b.max)}; }
/// a holds b (closed).
inline bool contains(const Aabb& a, const Aabb& b) {
    return (a.min.array() <= b.min.array()).all() && (b.max.array() <= a.max.array()).all();
}
/// Closed overlap on all three axes (touching counts), as testAabbAabb of core/overlap/sat_tests.h.
inline bool overlaps(const Aabb& a, const Aabb& b) {
    return a.min.x() <= b.max.x() && b.min.x() <= a.max.x() && a.min.y() <= b.max.y() && b.min.y() <= a.max.y() &&
           a.min.z() <= b.max.z() && b.min.z() <= a.max.z();
}
/// Closed overlap of boxes that may be invalid: both valid (isValidBox) and overlapping (touching
/// counts). Invalid boxes never overlap.
inline bool aabbOverlapClosed(const Aabb& a, const Aabb& b) { return isValidBox(a) && isValidBox(b) && overlaps(a, b); }
/// Surface area of a box, 2 (dx dy + dy dz + dz dx): the SAH cost (Goldsmith and Salmon 1987,
/// MacDonald and Booth 1990) of a node is proportional to it.
inline double surfaceArea(const Aabb& box) {
    const Vec3 d = box.max - box.min;
    return 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
}

}  // namespace cdlab
