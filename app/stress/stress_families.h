// The cases of `cdlab stress` (stress.h): a family draws case i from (seed, family, i) only, so a
// failing case is replayable on its own. Polytope pairs (vertex lists), box pairs (support
// mappings), point-triangle pairs, rays, times of impact, spheres and capsules, contact manifolds;
// stress.cpp, stress_witness_runs.cpp and stress_contact_runs.cpp run every check of its kind on
// each case.
#pragma once

#include <functional>
#include <random>
#include <string>
#include <vector>

#include "core/base/primitives.h"
#include "core/base/types.h"
#include "core/geometry/shapes.h"

namespace cdlab::demos::stress_cases {

// ---- Cases ---------------------------------------------------------------------------------------

struct PolyCase {
    std::vector<Vec3> va, vb;   // world frame
    bool raw = false;           // PolytopeShape over the raw list (duplicates kept), no hull
    bool floatRounded = false;  // the algorithms see the vertices rounded to float
    /// The judge's own error, relative to the pair's size L, added to the verdict, distance and
    /// depth tolerances: the hull of the rounded differences a_i − b_j merges features below its
    /// tolerance (~4096 ulps of the differences' magnitude), so a 1e-6 body beside a 1e3 one is
    /// resolved only to ~1e-10 L (its "hull oracle = brute force" row measures it).
    double oracleSlack = 0;
    double param = 0;
};

struct BoxCase {
    Transformed<BoxShape> a, b;
    double param = 0;
};

struct TriCase {
    Vec3 p = Vec3::Zero();
    Triangle t;
    double param = 0;
};

/// A ray o + t d, t >= 0, against the convex hull of `body` (world frame).
struct RayCase {
    std::vector<Vec3> body;
    Ray ray{Vec3::Zero(), Vec3::UnitX()};
    bool judgeVerdict = true;  // false: the ray passes within rounding of the body (either verdict)
    double param = 0;
};

/// Two polytopes translating over t in [0, 1] (A by motionA, B by motionB) along a relative path
/// that slides along a facet of the configuration-space body B − A, or grazes one of its edges or
/// vertices, tilted by `param` (rad).
struct ToiCase {
    std::vector<Vec3> va, vb;  // world frame, at t = 0
    Vec3 motionA = Vec3::Zero(), motionB = Vec3::Zero();
    double param = 0;
};

/// Two bodies conv(core) ⊕ ball(radius): one core point a sphere, two a capsule, more a polytope
/// (radius 0; never two polytopes).
struct RoundedCase {
    std::vector<Vec3> ca, cb;  // world frame
    double ra = 0, rb = 0;
    double param = 0;
};

/// Two polytopes (world-frame vertex lists) for the contact op: random hulls, or boxes face to
/// face, edge to edge (also nearly parallel), vertex to face; touching, apart or overlapping.
struct ContactCase {
    std::vector<Vec3> va, vb;
    double param = 0;
};

enum class Kind { Poly, Box, Tri, Ray, Toi, Rounded, Contact };

struct Family {
    std::string name, parameter;
    Kind kind;
    std::function<void(std::mt19937_64&, PolyCase&)> poly;
    std::function<void(std::mt19937_64&, BoxCase&)> box;
    std::function<void(std::mt19937_64&, TriCase&)> tri;
    std::function<void(std::mt19937_64&, RayCase&)> ray;
    std::function<void(std::mt19937_64&, ToiCase&)> toi = {};
    std::function<void(std::mt19937_64&, RoundedCase&)> rounded = {};
    std::function<void(std::mt19937_64&, ContactCase&)> contact = {};
};

/// Every family, in report order: polytope pairs (scale, offset, gap, penetration, slivers,
/// parallel edges, duplicates, rotations, float rounding), box pairs (axis-aligned, rotated), the
/// witness oracle's (tiny against huge, coplanar faces of A - B, rays in a face plane, times of
/// impact on sliding paths, spheres and capsules), point vs triangle, contact manifolds.
std::vector<Family> stressFamilies();

}  // namespace cdlab::demos::stress_cases
