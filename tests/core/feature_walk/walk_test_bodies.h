// What the V-Clip and Lin–Canny tests share: bodies built for the walks, random rotations, poses.
#pragma once

#include <doctest/doctest.h>

#include "core/feature_walk/vclip.h"
#include "core/geometry/polyhedron_presets.h"

namespace cdlab::test {

inline VClipPolyhedron build(const ConvexPolyhedron& p) {
    VClipBuild b = buildVClipPolyhedron(p);
    REQUIRE_MESSAGE(b.ok(), b.message);
    return b.polyhedron;
}

inline Quat randomRotation(presets::SplitMix64& rng) {
    Quat q(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (q.norm() < 1e-3) q = Quat::Identity();
    return q.normalized();
}

inline Transform pose(const Vec3& p, const Quat& q = Quat::Identity()) {
    Transform t;
    t.position = p;
    t.rotation = q;
    return t;
}

inline double extent(const ConvexPolyhedron& p) { return (p.boundsMax() - p.boundsMin()).norm(); }

}  // namespace cdlab::test
