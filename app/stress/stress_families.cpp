// The families of `cdlab stress` (stress_families.h): hard inputs drawn from (seed, family, index).
#include "app/stress/stress_families.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "app/bench/bench_inputs.h"
#include "app/bench/bench_measure.h"
#include "app/measure/statistics.h"
#include "app/stress/stress_tolerances.h"
#include "verification/cast_oracle.h"

namespace cdlab::demos::stress_cases {

namespace {

double uniform(std::mt19937_64& rng, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}
double logUniform(std::mt19937_64& rng, double lo, double hi) {
    return std::pow(10.0, uniform(rng, std::log10(lo), std::log10(hi)));
}

std::vector<Vec3> scaled(std::vector<Vec3> v, double s, const Vec3& shift = Vec3::Zero()) {
    for (Vec3& x : v) x = s * x + shift;
    return v;
}

Vec3 perpendicular(const Vec3& u) {
    const Vec3 t = std::abs(u.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
    return u.cross(t).normalized();
}

int argExtreme(const std::vector<Vec3>& v, const Vec3& d) {
    int best = 0;
    for (int i = 1; i < static_cast<int>(v.size()); ++i)
        if (v[i].dot(d) > v[best].dot(d)) best = i;
    return best;
}

/// Places vb so that its extreme vertex along -u sits at `gap` along u from va's extreme vertex
/// along u: the distance is then exactly `gap` for gap >= 0 (that pair is at distance gap, and
/// the planes u·x = h_A(u) and u·x = h_A(u) + gap separate). gap == 0 copies the vertex bit for
/// bit: exact touching.
void placeAtGap(std::vector<Vec3>& va, std::vector<Vec3>& vb, const Vec3& u, double gap) {
    const int ia = argExtreme(va, u), ib = argExtreme(vb, -u);
    const Vec3 shift = va[ia] - vb[ib] + gap * u;
    for (Vec3& x : vb) x += shift;
    if (gap == 0.0) vb[ib] = va[ia];
}

// Polytope pairs: scale, offset, gap, penetration, slivers, parallel edges, duplicates, rotations,
// float rounding.
void addPolytopeFamilies(std::vector<Family>& f) {
    auto poly = [&](std::string name, std::string param, std::function<void(std::mt19937_64&, PolyCase&)> g) {
        f.push_back({std::move(name), std::move(param), Kind::Poly, std::move(g), {}, {}, {}});
    };
    poly("scale 1e-6..1e6", "size", [](std::mt19937_64& rng, PolyCase& c) {
        const double s = logUniform(rng, 1e-6, 1e6);
        c.va = scaled(ellipsoidPoints(rng, 8), s);
        c.vb = scaled(ellipsoidPoints(rng, 8), s, s * uniform(rng, 0.2, 2.6) * randomUnit(rng));
        c.param = s;
    });
    poly("offset 1e3..1e9", "offset / size", [](std::mt19937_64& rng, PolyCase& c) {
        const double o = logUniform(rng, 1e3, 1e9);
        const Vec3 at = o * randomUnit(rng);
        c.va = scaled(ellipsoidPoints(rng, 8), 1.0, at);
        c.vb = scaled(ellipsoidPoints(rng, 8), 1.0, at + uniform(rng, 0.2, 2.6) * randomUnit(rng));
        c.param = o;
    });
    poly("gap 1e-12..1e-3, touching", "|gap| / size", [](std::mt19937_64& rng, PolyCase& c) {
        c.va = ellipsoidPoints(rng, 12);
        c.vb = ellipsoidPoints(rng, 12);
        const Vec3 u = randomUnit(rng);
        const double g = logUniform(rng, 1e-12, 1e-3);
        const int mode = std::uniform_int_distribution<int>(0, 7)(rng);
        // 1 in 8 exactly touching, then half separated, half overlapping by |gap|.
        const double gap = mode == 0 ? 0.0 : (mode % 2 ? g : -g);
        placeAtGap(c.va, c.vb, u, gap);
        c.param = std::abs(gap);
    });
    poly("deep penetration", "centre distance / size", [](std::mt19937_64& rng, PolyCase& c) {
        const double d = logUniform(rng, 1e-6, 0.3);
        c.va = ellipsoidPoints(rng, 16);
        c.vb = scaled(ellipsoidPoints(rng, 16), 1.0, d * randomUnit(rng));
        c.param = d;
    });
    poly("slivers and needles", "thickness / size", [](std::mt19937_64& rng, PolyCase& c) {
        const double t = logUniform(rng, 1e-9, 1e-2);
        const bool needle = std::uniform_int_distribution<int>(0, 1)(rng);
        const Quat qa = randomRotation(rng), qb = randomRotation(rng);
        const Vec3 radii(1.0, needle ? t : 1.0, t);
        auto shape = [&](const Quat& q) {
            std::vector<Vec3> v;
            for (int i = 0; i < 10; ++i) v.push_back(q * radii.cwiseProduct(randomUnit(rng)));
            return v;
        };
        c.va = shape(qa);
        c.vb = scaled(shape(qb), 1.0, uniform(rng, 0.0, 1.5) * randomUnit(rng));
        c.param = t;
    });
    poly("nearly parallel edges", "angle (rad)", [](std::mt19937_64& rng, PolyCase& c) {
        // Two thin wedges whose ridges (edges of length 2) cross at an angle 1e-9..1e-1, the
        // ridges |gap| apart along n (separated or overlapping).
        const double angle = logUniform(rng, 1e-9, 1e-1);
        const double gap = logUniform(rng, 1e-9, 1e-2) * (rng() % 2 ? 1 : -1);
        const Vec3 e = randomUnit(rng), n = perpendicular(e), m = e.cross(n);
        const Vec3 e2 = Eigen::AngleAxisd(angle, n) * e, m2 = e2.cross(n);
        const Vec3 at = uniform(rng, -0.5, 0.5) * e;
        c.va = {-e, e, 0.2 * (-n + m), 0.2 * (-n - m)};
        c.vb = {at - e2 + gap * n, at + e2 + gap * n, at + 0.2 * (n + m2) + gap * n, at + 0.2 * (n - m2) + gap * n};
        c.param = angle;
    });
    poly("duplicate points", "copies", [](std::mt19937_64& rng, PolyCase& c) {
        // Raw vertex lists (no hull): every vertex 1..3 times, some copies 1 ulp off.
        auto dup = [&](std::vector<Vec3> v) {
            std::vector<Vec3> out;
            for (const Vec3& x : v) {
                const int copies = 1 + static_cast<int>(rng() % 3);
                for (int k = 0; k < copies; ++k) {
                    Vec3 y = x;
                    if (k > 0 && rng() % 2) y.x() = std::nextafter(y.x(), INFINITY);
                    out.push_back(y);
                }
            }
            std::shuffle(out.begin(), out.end(), rng);
            return out;
        };
        c.va = dup(ellipsoidPoints(rng, 6));
        c.vb = dup(scaled(ellipsoidPoints(rng, 6), 1.0, uniform(rng, 0.0, 2.4) * randomUnit(rng)));
        c.raw = true;
        c.param = static_cast<double>(c.va.size() + c.vb.size()) / 12.0;
    });
    poly("random rotations, 64 vertices", "centre distance / size", [](std::mt19937_64& rng, PolyCase& c) {
        const double d = uniform(rng, 0.05, 2.5);
        c.va = ellipsoidPoints(rng, 64);  // ellipsoidPoints rotates each shape at random
        c.vb = scaled(ellipsoidPoints(rng, 64), 1.0, d * randomUnit(rng));
        c.param = d;
    });
    poly("float-rounded input", "offset / size", [](std::mt19937_64& rng, PolyCase& c) {
        // No float variant of GJK / EPA exists in core (double only): this measures what storing
        // double geometry in float does to the answer, against the float rounding bound.
        const double s = logUniform(rng, 1e-3, 1e3), o = logUniform(rng, 1e-2, 1e6) * s;
        const Vec3 at = o * randomUnit(rng);
        c.va = scaled(ellipsoidPoints(rng, 8), s, at);
        c.vb = scaled(ellipsoidPoints(rng, 8), s, at + s * uniform(rng, 0.2, 2.6) * randomUnit(rng));
        c.floatRounded = true;
        c.param = o / s;
    });
}

// Box pairs: axis-aligned with support ties, and random rotations.
void addBoxFamilies(std::vector<Family>& f) {
    f.push_back({"axis-aligned boxes (support ties)",
                 "|gap| / size",
                 Kind::Box,
                 {},
                 [](std::mt19937_64& rng, BoxCase& c) {
                     // Face / edge / corner contact of axis-aligned boxes (all supports tie on whole faces),
                     // coplanar side faces where the extents match, gaps 0 or +-1e-12..1e-3.
                     const double s = logUniform(rng, 1e-3, 1e3);
                     const double ext[3] = {0.5, 1.0, 2.0};
                     auto pick = [&] { return s * ext[rng() % 3]; };
                     c.a.shape.halfExtents = Vec3(pick(), pick(), pick());
                     c.b.shape.halfExtents = Vec3(pick(), pick(), pick());
                     const int mode = std::uniform_int_distribution<int>(0, 5)(rng);
                     const double g = mode == 0 ? 0.0 : logUniform(rng, 1e-12, 1e-3) * (mode % 2 ? 1 : -1);
                     Vec3 centre;
                     const int contactAxes = 1 + static_cast<int>(rng() % 3);  // face, edge, corner
                     for (int i = 0; i < 3; ++i) {
                         const double sign = rng() % 2 ? 1.0 : -1.0;
                         const double touch = c.a.shape.halfExtents[i] + c.b.shape.halfExtents[i];
                         centre[i] = i < contactAxes ? sign * (touch + g * s) : (rng() % 2 ? 0.0 : sign * 0.25 * touch);
                     }
                     c.b.transform.position = centre;
                     c.param = std::abs(g);
                 },
                 {},
                 {}});
    f.push_back({"OBB random rotations",
                 "centre distance / size",
                 Kind::Box,
                 {},
                 [](std::mt19937_64& rng, BoxCase& c) {
                     const double s = logUniform(rng, 1e-3, 1e3);
                     c.a.shape.halfExtents = s * Vec3(uniform(rng, 0.1, 1), uniform(rng, 0.1, 1), uniform(rng, 0.1, 1));
                     c.b.shape.halfExtents = s * Vec3(uniform(rng, 0.1, 1), uniform(rng, 0.1, 1), uniform(rng, 0.1, 1));
                     c.a.transform.rotation = randomRotation(rng);
                     c.b.transform.rotation = randomRotation(rng);
                     const double d = uniform(rng, 0.0, 2.5);
                     c.b.transform.position = s * d * randomUnit(rng);
                     c.param = d;
                 },
                 {},
                 {}});
}

// Point vs triangle: near-boundary points, slivers and needles, far offsets.
void addTriangleFamilies(std::vector<Family>& f) {
    auto tri = [&](std::string name, std::string param, std::function<void(std::mt19937_64&, TriCase&)> g) {
        f.push_back({std::move(name), std::move(param), Kind::Tri, {}, {}, std::move(g), {}});
    };
    tri("triangle: near-boundary points", "distance off the feature / size", [](std::mt19937_64& rng, TriCase& c) {
        c.t = {randomUnit(rng), randomUnit(rng), randomUnit(rng)};
        const Vec3* v[3] = {&c.t.a, &c.t.b, &c.t.c};
        const int k = static_cast<int>(rng() % 3);
        const double s = rng() % 3 == 0 ? 0.0 : uniform(rng, 0.0, 1.0);  // 1 in 3 at a vertex
        const Vec3 onEdge = *v[k] + s * (*v[(k + 1) % 3] - *v[k]);
        const double off = logUniform(rng, 1e-15, 1e-3);
        c.p = onEdge + off * randomUnit(rng);
        c.param = off;
    });
    tri("triangle: slivers and needles", "thickness / size", [](std::mt19937_64& rng, TriCase& c) {
        const double t = logUniform(rng, 1e-12, 1e-2);
        const Vec3 a = randomUnit(rng), b = -a, u = perpendicular(a);
        c.t = rng() % 2 ? Triangle{a, b, uniform(rng, -0.9, 0.9) * a + t * u}         // sliver: c near ab
                        : Triangle{a, a + t * u, a + t * perpendicular(u.cross(a))};  // needle-ish: short ac, ab
        c.p = uniform(rng, 0.0, 1.5) * randomUnit(rng);
        c.param = t;
    });
    tri("triangle: offsets 1e3..1e9", "offset / size", [](std::mt19937_64& rng, TriCase& c) {
        const double o = logUniform(rng, 1e3, 1e9);
        const Vec3 at = o * randomUnit(rng);
        c.t = {at + randomUnit(rng), at + randomUnit(rng), at + randomUnit(rng)};
        c.p = at + uniform(rng, 0.0, 1.5) * randomUnit(rng);
        c.param = o;
    });
}

// Issue 41's families for the witness oracle: a tiny body against a huge one (witnesses judged
// against each body's own size), and boxes whose Minkowski difference has coplanar faces (tied
// least-overlap directions, face-face distances).
void addWitnessFamilies(std::vector<Family>& f) {
    auto poly = [&](std::string name, std::string param, std::function<void(std::mt19937_64&, PolyCase&)> g) {
        f.push_back({std::move(name), std::move(param), Kind::Poly, std::move(g), {}, {}, {}});
    };
    poly("tiny against huge (1e-6 vs 1e3)", "|gap| / tiny size", [](std::mt19937_64& rng, PolyCase& c) {
        // A 1e-6 body against a 1e3 one, at a vertex of the huge body (placeAtGap along a random
        // direction) or on the middle of a face of a huge box, touching, apart or overlapping by
        // up to the tiny body's size; which is A is drawn. Witnesses on the tiny body are judged
        // against its own size (stress_tolerances.h), depths and distances against the pair's.
        const double big = 1e3 * uniform(rng, 0.5, 2.0), tiny = 1e-6 * uniform(rng, 0.5, 2.0);
        std::vector<Vec3> small = scaled(ellipsoidPoints(rng, 8), tiny);
        const int mode = std::uniform_int_distribution<int>(0, 3)(rng);  // 0 touching, 1 apart, 2-3 overlapping
        const double g = tiny * logUniform(rng, 1e-3, 1.0);
        const double gap = mode == 0 ? 0.0 : (mode == 1 ? g : -g);
        std::vector<Vec3> huge;
        if (rng() % 2) {
            huge = scaled(ellipsoidPoints(rng, 12), big);
            placeAtGap(huge, small, randomUnit(rng), gap);
        } else {
            for (int i = 0; i < 8; ++i)
                huge.push_back(big * Vec3(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0));
            const Vec3 at(uniform(rng, -0.5, 0.5) * big, uniform(rng, -0.5, 0.5) * big, big + gap);
            const Vec3 low = small[argExtreme(small, -Vec3::UnitZ())];
            for (Vec3& x : small) x += at - low;
            const Quat q = randomRotation(rng);  // the whole pair, rounded
            for (Vec3& x : small) x = q * x;
            for (Vec3& x : huge) x = q * x;
        }
        const bool tinyFirst = rng() % 2;
        c.va = tinyFirst ? small : huge;
        c.vb = tinyFirst ? huge : small;
        c.param = std::abs(gap) / tiny;
        c.oracleSlack = stress_tolerances::kHullOracleSlack;
    });
    f.push_back({"coplanar faces of A - B (shared orientation)",
                 "depth / size",
                 Kind::Box,
                 {},
                 [](std::mt19937_64& rng, BoxCase& c) {
                     // Two boxes with one orientation (identity 1 in 3, else a random rotation shared
                     // by both), so A - B is a box whose faces are coplanar with faces of A and B and
                     // whose support ties on whole faces: overlapping by the same depth d along 1..3
                     // axes (tied least-overlap directions, any of them right) and more along the
                     // others; 1 in 3 apart by d along one axis (face-face distance, coplanar sides).
                     const double s = logUniform(rng, 1e-3, 1e3);
                     const double ext[3] = {0.5, 1.0, 2.0};
                     auto pick = [&] { return s * ext[rng() % 3]; };
                     c.a.shape.halfExtents = Vec3(pick(), pick(), pick());
                     c.b.shape.halfExtents = Vec3(pick(), pick(), pick());
                     const Quat q = rng() % 3 == 0 ? Quat::Identity() : randomRotation(rng);
                     c.a.transform.rotation = q;
                     c.b.transform.rotation = q;
                     c.a.transform.position = s * uniform(rng, 0.0, 3.0) * randomUnit(rng);
                     const double d = s * logUniform(rng, 1e-6, 0.5);
                     const int tied = 1 + static_cast<int>(rng() % 3);
                     const bool apart = rng() % 3 == 0;
                     int axis[3] = {0, 1, 2};
                     std::shuffle(axis, axis + 3, rng);
                     Vec3 local;
                     for (int k = 0; k < 3; ++k) {
                         const int i = axis[k];
                         const double sign = rng() % 2 ? 1.0 : -1.0;
                         const double touch = c.a.shape.halfExtents[i] + c.b.shape.halfExtents[i];
                         // overlap along i (<= s <= touch, so |centre_i| = touch - overlap)
                         double overlap = k < tied ? d : d + s * uniform(rng, 0.1, 0.5);
                         if (apart && k == 0) overlap = -d;
                         local[i] = sign * (touch - overlap);
                     }
                     c.b.transform.position = c.a.transform.position + q * local;
                     c.param = d / s;
                 },
                 {},
                 {}});
}

// Rays in the plane of a face of an axis-aligned box (exactly: the plane's coordinate is the
// origin's and the direction has no component across it), so the ray grazes the face and enters
// through the edge where it crosses the side face; or tilted by 1e-12..1e-3 rad into the box's slab
// (a hit on the side face just below the edge) or away from it (a miss by the tilt times the
// distance, judged when that is above the rounding band).
void addRayFamilies(std::vector<Family>& f) {
    Family ray{"rays in a face plane", "tilt (rad; 0 in the plane)", Kind::Ray, {}, {}, {}, {}};
    ray.ray = [](std::mt19937_64& rng, RayCase& c) {
        const double s = logUniform(rng, 1e-3, 1e3);
        const Vec3 half = s * Vec3(uniform(rng, 0.2, 1.0), uniform(rng, 0.2, 1.0), uniform(rng, 0.2, 1.0));
        const Vec3 centre = s * uniform(rng, 0.0, 2.0) * randomUnit(rng);
        const int axis = static_cast<int>(rng() % 3);  // the face's axis, +/- side
        const double side = rng() % 2 ? 1.0 : -1.0;
        for (int i = 0; i < 8; ++i)
            c.body.push_back(centre + Vec3(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(),
                                           i & 4 ? half.z() : -half.z()));
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        // origin in the face's plane, outside the face; target inside the face (or on its edge)
        Vec3 o = centre, target = centre;
        o[axis] = target[axis] = centre[axis] + side * half[axis];  // the corner's coordinate exactly
        const double angle = uniform(rng, 0.0, 6.283185307179586);
        o[u] += 2.0 * half.norm() * std::cos(angle);
        o[v] += 2.0 * half.norm() * std::sin(angle);
        const bool onEdge = rng() % 4 == 0;  // the target on the face's edge: a graze of a graze
        target[u] += (onEdge ? 1.0 : uniform(rng, -1.0, 1.0)) * half[u];
        target[v] += uniform(rng, -1.0, 1.0) * half[v];
        Vec3 d = target - o;  // d[axis] == 0 exactly
        const int mode = static_cast<int>(rng() % 3);  // 0 in the plane, 1 into the slab, 2 away
        const double tilt = mode == 0 ? 0.0 : logUniform(rng, 1e-12, 1e-3);
        d[axis] = (mode == 1 ? -side : side) * tilt * d.norm();
        c.ray = Ray{o, d};
        // A miss by tilt * |target - o| (~2 |half|): judged above the rounding band. A ray to an
        // edge point passes within the rounding of d = target - o of the edge: either verdict.
        c.judgeVerdict = !onEdge && (mode != 2 || tilt > 1e-10);
        c.param = tilt;
    };
    f.push_back(std::move(ray));
}

// ---- Times of impact on sliding and grazing paths ----------------------------------------------------
//
// A translated by x touches B iff x lies in the configuration-space body D = B − A = conv{b_j − a_i}:
// the relative path x(t) = (oA − oB) + t (motionA − motionB) is a ray against D. The path is aimed
// at a facet of D (a face of B minus A's vertex extreme the other way, or B's vertex minus a face
// of A), through a point p inside it and along its plane, tilted out of it by the parameter about
// p (the path then crosses D in a chord near the facet, entering through a side face or through
// the facet); or, 1 case in 4, along a supporting plane of an edge or vertex of D with a normal
// inside the feature's normal cone, tilted about the path's start (a miss or a clip by ~2 size(D)
// tilt). The path starts 2 size(D) before p. The construction only aims: the oracle recomputes D
// from the doubles handed to the query.

/// The points of v within 1e-12 of their size of the largest n·x.
std::vector<Vec3> supportSet(const std::vector<Vec3>& v, const Vec3& n, double size) {
    double h = -INFINITY;
    for (const Vec3& x : v) h = std::max(h, n.dot(x));
    std::vector<Vec3> out;
    for (const Vec3& x : v)
        if (n.dot(x) >= h - 1e-12 * size) out.push_back(x);
    return out;
}

/// A random unit vector perpendicular to the unit n.
Vec3 inPlane(std::mt19937_64& rng, const Vec3& n) {
    for (;;) {
        const Vec3 r = randomUnit(rng);
        const Vec3 u = r - r.dot(n) * n;
        if (u.norm() > 0.1) return u.normalized();
    }
}

/// A feature of D = B − A aimed at: a point p on it and the normal n of a supporting plane there
/// (unit, outward).
struct AimedFeature {
    Vec3 p = Vec3::Zero(), n = Vec3::UnitX();
};

/// A random point of conv(points) (random convex weights).
Vec3 pointOf(std::mt19937_64& rng, const std::vector<Vec3>& points) {
    Vec3 sum = Vec3::Zero();
    double total = 0;
    for (const Vec3& x : points) {
        const double w = uniform(rng, 0.05, 1.0);
        sum += w * x;
        total += w;
    }
    return sum / total;
}

/// A facet of D: a face of B (outward normal n) minus A's vertex extreme along −n (normal n), or
/// B's vertex extreme along −n minus a face of A with outward normal n (normal −n).
AimedFeature facetOfDifference(std::mt19937_64& rng, const std::vector<Vec3>& va, const std::vector<Vec3>& vb,
                               double size) {
    const bool ofB = rng() % 2;
    const std::vector<Vec3>& body = ofB ? vb : va;
    const std::vector<cast_oracle::FacetPlane> planes = cast_oracle::facetPlanes(body);
    const cast_oracle::FacetPlane& f = planes[rng() % planes.size()];
    const Vec3 n(static_cast<double>(f.n.x()), static_cast<double>(f.n.y()), static_cast<double>(f.n.z()));
    std::vector<Vec3> face = supportSet(body, n, size), facet;
    if (ofB) {
        const Vec3 a = va[argExtreme(va, -n)];
        for (const Vec3& b : face) facet.push_back(b - a);
        return {pointOf(rng, facet), n};
    }
    const Vec3 b = vb[argExtreme(vb, -n)];
    for (const Vec3& a : face) facet.push_back(b - a);
    return {pointOf(rng, facet), -n};
}

/// An edge or vertex of D with a normal inside its normal cone: D's support set along a direction
/// between two adjacent face normals of B (an edge of B minus a vertex of A), or along a random one
/// (a vertex of B minus a vertex of A).
AimedFeature edgeOrVertexOfDifference(std::mt19937_64& rng, const std::vector<Vec3>& va, const std::vector<Vec3>& vb,
                                      double size) {
    Vec3 r = randomUnit(rng);
    const std::vector<cast_oracle::FacetPlane> planes = cast_oracle::facetPlanes(vb);
    if (rng() % 2) {
        auto unit = [](const cast_oracle::FacetPlane& f) {
            return Vec3(static_cast<double>(f.n.x()), static_cast<double>(f.n.y()), static_cast<double>(f.n.z()));
        };
        const Vec3 n1 = unit(planes[rng() % planes.size()]);
        const std::vector<Vec3> face = supportSet(vb, n1, size);
        for (const cast_oracle::FacetPlane& g : planes) {  // a neighbouring face: two points shared
            const Vec3 n2 = unit(g);
            if (n2.dot(n1) > 1 - 1e-9) continue;
            int shared = 0;
            for (const Vec3& x : supportSet(vb, n2, size)) shared += std::count(face.begin(), face.end(), x) > 0;
            if (shared < 2) continue;
            r = (uniform(rng, 0.2, 1.0) * n1 + uniform(rng, 0.2, 1.0) * n2).normalized();
            break;
        }
    }
    const Vec3 a = va[argExtreme(va, -r)];
    std::vector<Vec3> feature;
    for (const Vec3& b : supportSet(vb, r, size)) feature.push_back(b - a);
    return {pointOf(rng, feature), r};
}

void toiSlidingPath(std::mt19937_64& rng, ToiCase& c) {
    const double s = logUniform(rng, 1e-2, 1e2);
    const std::vector<Vec3> a0 = scaled(ellipsoidPoints(rng, 4 + static_cast<int>(rng() % 5)), s);
    const std::vector<Vec3> b0 =
        scaled(ellipsoidPoints(rng, 4 + static_cast<int>(rng() % 5)), s * uniform(rng, 0.5, 2));
    std::vector<Vec3> d0;
    for (const Vec3& b : b0)
        for (const Vec3& a : a0) d0.push_back(b - a);
    const double size = 2.0 * centroidRadius(d0);  // at least D's diameter
    const bool graze = rng() % 4 == 0;
    const AimedFeature f = graze ? edgeOrVertexOfDifference(rng, a0, b0, size) : facetOfDifference(rng, a0, b0, size);
    const int mode = static_cast<int>(rng() % 3);  // 0 in the plane, 1 tilted out, 2 tilted in
    const double tilt = mode == 0 ? 0.0 : (mode == 1 ? 1.0 : -1.0) * logUniform(rng, 1e-15, 1e-6);
    const Vec3 u = inPlane(rng, f.n);
    const Vec3 w = (std::cos(tilt) * u + std::sin(tilt) * f.n).normalized();
    const double tp = uniform(rng, 0.3, 0.7), length = 2.0 * size / tp;  // p reached at t = tp
    const Vec3 m = length * w;
    // x(0): 2 size before p along the tilted path (a facet: the chord pivots about p), or along
    // the untilted one (a graze: the path passes p at 2 size tilt off its supporting plane).
    const Vec3 x0 = graze ? Vec3(f.p - 2.0 * size * u) : Vec3(f.p - tp * m);
    const Vec3 oB = rng() % 2 ? Vec3::Zero() : Vec3(logUniform(rng, 1.0, 1e3) * randomUnit(rng));
    c.va = scaled(a0, 1.0, oB + x0);
    c.vb = scaled(b0, 1.0, oB);
    c.motionB = rng() % 3 == 0 ? Vec3::Zero() : Vec3(length * uniform(rng, 0.0, 1.5) * randomUnit(rng));
    c.motionA = m + c.motionB;
    c.param = std::abs(tilt);
}

// ---- Spheres and capsules --------------------------------------------------------------------------

/// A sphere (kind 0), capsule (1) or polytope (2) of size s about the origin.
void roundedBody(std::mt19937_64& rng, int kind, double s, const Vec3& axis, std::vector<Vec3>& core, double& r) {
    if (kind == 0) {
        core = {Vec3::Zero()};
        r = s * uniform(rng, 0.3, 1.0);
    } else if (kind == 1) {
        const double h = s * uniform(rng, 0.2, 1.0);
        core = {-h * axis, h * axis};
        r = s * uniform(rng, 0.05, 0.6);
    } else {
        core = scaled(ellipsoidPoints(rng, 8), s);
        r = 0;
    }
}

/// The point of conv(core) ⊕ ball(r) extreme along u (the first extreme core point).
Vec3 roundedSupport(const std::vector<Vec3>& core, double r, const Vec3& u) {
    return core[argExtreme(core, u)] + r * u;
}

void roundedPair(std::mt19937_64& rng, RoundedCase& c) {
    // Kinds: 1 in 4 two nearly parallel capsules (1 in 4 of those exactly parallel) side by side,
    // else any pair but two polytopes. Sizes 1e-3..1e3 (B within 10x of A).
    const bool parallel = rng() % 4 == 0;
    int ka = parallel ? 1 : static_cast<int>(rng() % 3), kb = parallel ? 1 : static_cast<int>(rng() % 3);
    if (ka == 2 && kb == 2) kb = static_cast<int>(rng() % 2);
    const double sa = logUniform(rng, 1e-3, 1e3), sb = sa * logUniform(rng, 0.1, 10.0);
    const Vec3 ea = randomUnit(rng), side = perpendicular(ea);
    const double angle = parallel && rng() % 4 ? logUniform(rng, 1e-9, 1e-1) : 0.0;
    const Vec3 turn = rng() % 2 ? side : ea.cross(side);  // crossing in parallel planes, or converging
    const Vec3 eb = parallel ? Vec3(Eigen::AngleAxisd(angle, turn) * ea) : randomUnit(rng);
    roundedBody(rng, ka, sa, ea, c.ca, c.ra);
    roundedBody(rng, kb, sb, eb, c.cb, c.rb);
    // Gap along u (across the capsules when parallel): touching, apart or overlapping by g, or deep.
    const Vec3 u = parallel ? side : randomUnit(rng);
    const int mode = static_cast<int>(rng() % 6);
    const double g = std::min(sa, sb) * logUniform(rng, 1e-12, 1e-1);
    const double gap = mode == 0 ? 0.0 : (mode <= 2 ? g : -g);
    Vec3 shift = roundedSupport(c.ca, c.ra, u) - roundedSupport(c.cb, c.rb, -u) + gap * u;
    if (mode == 5) shift = std::min(sa, sb) * uniform(rng, 0.0, 0.5) * randomUnit(rng);  // deep
    if (parallel) shift += uniform(rng, -1.0, 1.0) * sa * ea;                            // slid along the axis
    const Vec3 o = rng() % 2 ? Vec3::Zero() : Vec3(logUniform(rng, 1.0, 1e6) * randomUnit(rng));
    c.ca = scaled(c.ca, 1.0, o);
    c.cb = scaled(c.cb, 1.0, o + shift);
    c.param = mode == 5 ? shift.norm() / std::max(sa, sb) : std::abs(gap) / std::max(sa, sb);
}

void addCastAndRoundedFamilies(std::vector<Family>& f) {
    Family toi{"time of impact, sliding paths", "tilt (rad; 0 in the plane)", Kind::Toi, {}, {}, {}, {}};
    toi.toi = toiSlidingPath;
    f.push_back(std::move(toi));
    Family rounded{"spheres and capsules", "|gap| / size", Kind::Rounded, {}, {}, {}, {}};
    rounded.rounded = roundedPair;
    f.push_back(std::move(rounded));
}


// ---- Contact manifolds -------------------------------------------------------------------------------
//
// Two polytopes for the contact op, 1 case in 5 each: random hulls of 4–10 vertices placed along a
// random direction (placeAtGap); boxes face to face (B turned about the common normal, 1 in 3 not
// at all); edge to edge, the ridges crossing at 0.2..1.4 rad; the same nearly parallel, 1e-12..1e-3
// rad; a vertex of B over a face of A. Sizes 1e-3..1e3 (B 0.5..2 times A), the pair rotated at
// random and, 1 case in 2, moved by 1e-0..1e6 (nearly parallel edges: no farther than keeps the
// coordinates' rounding 1e-3 of the angle). The gap along the contact's normal: 1 in 8 touching
// (a vertex copied bit for bit: random hulls), 3 in 8 apart by 1e-12..1e-3 of the size, 2 in 8
// overlapping by that much, 2 in 8 by 1e-3..0.3. The construction only aims: the oracle recomputes
// everything from the doubles handed to the query.

/// The corners of the box of half extents h turned by q about c (corner i: bit k the + side of axis k).
std::vector<Vec3> boxPoints(const Vec3& c, const Vec3& h, const Quat& q) {
    std::vector<Vec3> v;
    for (int i = 0; i < 8; ++i)
        v.push_back(c + q * Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()));
    return v;
}

double contactGap(std::mt19937_64& rng, double s) {
    const int mode = static_cast<int>(rng() % 8);
    if (mode == 0) return 0.0;
    if (mode <= 3) return s * logUniform(rng, 1e-12, 1e-3);
    if (mode <= 5) return -s * logUniform(rng, 1e-12, 1e-3);
    return -s * logUniform(rng, 1e-3, 0.3);
}

/// Boxes in A's frame (A at the origin, axis-aligned) with A's ridge along x at (y, z) = (hA.y, hA.z)
/// and B's ridge (its edge at local (y, z) = (−hB.y, −hB.z)) crossing it at P = (t0, hA.y, hA.z) at the
/// angle theta: B turned by phi about x (the arcs of the ridges' face normals on the Gauss map,
/// [0, 90°] for A, [phi, phi + 90°] for B reflected, overlap on [phi, 90°]), then by theta about
/// m = (0, cos gamma, sin gamma) inside that overlap. The edge-edge face of A − B then has the normal
/// m; B's ridge sits at P + gap m.
void crossedRidges(std::mt19937_64& rng, const Vec3& hA, const Vec3& hB, double theta, double gap,
                   std::vector<Vec3>& va, std::vector<Vec3>& vb) {
    const double phi = uniform(rng, 0.2, 1.37), span = 1.5707963267948966 - phi;
    const double gamma = phi + uniform(rng, 0.1, 0.9) * span;
    const Vec3 m(0.0, std::cos(gamma), std::sin(gamma));
    const Quat r = Quat(Eigen::AngleAxisd(theta, m)) * Quat(Eigen::AngleAxisd(phi, Vec3::UnitX()));
    const Vec3 p(uniform(rng, -0.5, 0.5) * hA.x(), hA.y(), hA.z());
    const Vec3 cB = p + gap * m - r * Vec3(0.0, -hB.y(), -hB.z());
    va = boxPoints(Vec3::Zero(), hA, Quat::Identity());
    vb = boxPoints(cB, hB, r);
}

void contactPair(std::mt19937_64& rng, ContactCase& c) {
    const double s = logUniform(rng, 1e-3, 1e3), gap = contactGap(rng, s);
    const int mode = static_cast<int>(rng() % 5);  // hulls, face-face, edge-edge, nearly parallel, vertex-face
    double offsetCap = 1e6;
    if (mode == 0) {
        c.va = scaled(ellipsoidPoints(rng, 4 + static_cast<int>(rng() % 7)), s);
        c.vb = scaled(ellipsoidPoints(rng, 4 + static_cast<int>(rng() % 7)), s * uniform(rng, 0.5, 2.0));
        placeAtGap(c.va, c.vb, randomUnit(rng), gap);
    } else {
        const Vec3 hA = s * Vec3(uniform(rng, 0.3, 1), uniform(rng, 0.3, 1), uniform(rng, 0.3, 1));
        const Vec3 hB = s * uniform(rng, 0.5, 2.0) * Vec3(uniform(rng, 0.3, 1), uniform(rng, 0.3, 1), uniform(rng, 0.3, 1));
        if (mode == 1) {  // B on A's +z face, turned about z
            const double psi = rng() % 3 == 0 ? 0.0 : uniform(rng, 0.0, 6.283185307179586);
            const Vec3 cB(uniform(rng, -0.8, 0.8) * hA.x(), uniform(rng, -0.8, 0.8) * hA.y(), hA.z() + hB.z() + gap);
            c.va = boxPoints(Vec3::Zero(), hA, Quat::Identity());
            c.vb = boxPoints(cB, hB, Quat(Eigen::AngleAxisd(psi, Vec3::UnitZ())));
        } else if (mode == 2 || mode == 3) {
            const double theta = mode == 2 ? uniform(rng, 0.2, 1.4) : logUniform(rng, 1e-12, 1e-3);
            crossedRidges(rng, hA, hB, rng() % 2 ? theta : -theta, gap, c.va, c.vb);
            if (mode == 3) offsetCap = std::min(offsetCap, s * theta * 1e13);  // rounding u·offset <= 1e-3 theta s
        } else {  // B's lowest vertex over a point of A's +z face
            c.va = boxPoints(Vec3::Zero(), hA, Quat::Identity());
            c.vb = boxPoints(Vec3::Zero(), hB, randomRotation(rng));
            const Vec3 p(uniform(rng, -0.8, 0.8) * hA.x(), uniform(rng, -0.8, 0.8) * hA.y(), hA.z() + gap);
            const Vec3 low = c.vb[argExtreme(c.vb, -Vec3::UnitZ())];
            for (Vec3& x : c.vb) x += p - low;
        }
        const Quat q = randomRotation(rng);  // the pair, turned
        for (Vec3& x : c.va) x = q * x;
        for (Vec3& x : c.vb) x = q * x;
    }
    if (rng() % 2) {
        const Vec3 o = std::min(offsetCap, logUniform(rng, 1.0, 1e6)) * randomUnit(rng);
        for (Vec3& x : c.va) x += o;
        for (Vec3& x : c.vb) x += o;
    }
    c.param = std::abs(gap) / s;
}

void addContactFamilies(std::vector<Family>& f) {
    Family contact{"contact manifolds", "|gap| / size", Kind::Contact, {}, {}, {}, {}};
    contact.contact = contactPair;
    f.push_back(std::move(contact));
}

}  // namespace

std::vector<Family> stressFamilies() {
    std::vector<Family> f;
    addPolytopeFamilies(f);
    addBoxFamilies(f);
    addWitnessFamilies(f);
    addRayFamilies(f);
    addCastAndRoundedFamilies(f);
    addTriangleFamilies(f);
    addContactFamilies(f);
    return f;
}

}  // namespace cdlab::demos::stress_cases
