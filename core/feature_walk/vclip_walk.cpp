// The V-Clip feature walk: the five states, clipEdge, the derivative checks and handleLocalMin.
// B. Mirtich, "V-Clip: Fast and Robust Polyhedral Collision Detection", ACM TOG 17(3) 1998
// (MERL TR-97-05), §4 (clipping, derivative checks) and §5 (state update rules).
//
// Conventions. Body 0 is A, body 1 is B; X[i] is the current feature of body i. A point of body o
// is tested against a region of body r after mapping it into r's frame (toFrame), as in the
// paper, so world offsets never enter a plane test. Region distances are positive INSIDE the
// region. An edge is e(l) = tail + l (head - tail), l in [0, 1].
//
// Numerics: every branch takes the sign of a plane distance or of a derivative computed in double;
// plane tests use no tolerance, derivatives and distances a rounding floor only (kRound below: a
// value below the rounding of its coordinates has no sign). Regions are closed (distance 0 =
// inside), so every point is in at least one region and ties go to the current feature (no update). Distances that are
// exactly 0 at a clip point or a DONE pair are reported as touching (Penetrating). The walk is
// kept monotone (see below), which makes it terminate in exact arithmetic; the repeated-pair
// detector and the step bound only guard against rounding and never fire in the test suite.
//
// Where cdlab departs from the paper's text (to keep "distance never increases" exact):
//   - V-F with V outside a side plane, E-F with E excluded from VR(F), and E-F with the distance
//     increasing at a clipped end inside VR(F): the face is replaced by its boundary feature
//     nearest to V (resp. E), an edge or, when the nearest point is a corner, a vertex, found by
//     an O(|F|) scan. The paper picks the most violated plane / Nmin, which can be an edge
//     farther than the nearest one (the distance would rise). Taking the corner vertex rather than
//     one of its two edges matters: E-E may raise an edge E' to a face F whose closest point to E
//     is E''s endpoint (distance equal, not smaller), and going back to E' from F repeats the pair
//     (642-vertex sphere test, before this rule).
//   - E-E compound exclusion: decided from the closest pair of the two segments (the endpoint
//     vertex if the closest point of E' is an endpoint, else the face whose FE plane the closest
//     point of E violates); the paper's implementation compares face-plane distances there.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/base/tolerances.h"
#include "core/closest/closest_point.h"
#include "core/feature_walk/feature_walk_pair.h"
#include "core/feature_walk/vclip.h"

namespace cdlab {
namespace {

using FT = VClipFeatureType;

// Rounding floor of a value computed in double from coordinates of magnitude m (max-norm): the
// point mapping between frames and one dot product make <= 6 roundings of size ulp(m), so
// 16 ulps of m (kRound * m) bound their error with margin. A derivative, a plane distance difference or
// a distance below its floor has no sign determined by the inputs (it depends on the order of
// operations) and is treated as 0: for a derivative that is the tie of two closed regions (the
// current feature stays), for a distance it is contact. Without this, a derivative of pure noise
// (an edge parallel to a face to rounding) can send E-E -> E-F -> E-E with equal distances
// (found by the 642-vertex sphere test). Plane tests need no floor: each plane is stored once,
// so both regions read the same double and can never both claim or both reject a point.
constexpr double kRound = 16.0 * kMachineEpsilon;

int signAbove(double x, double floor) { return x > floor ? 1 : (x < -floor ? -1 : 0); }
using feature_walk::finitePose;
using feature_walk::maxAbs;
using feature_walk::validFeature;

struct VClipOutcome {
    VClipStepKind kind = VClipStepKind::Done;
    int body = -1;
    VClipFeature to;
    const char* rule = "";
    bool localMin = false;
    VClipPenetration penetration = VClipPenetration::None;
    int pointBody = 0;  // penetration point (frame of pointBody)
    Vec3 point = Vec3::Zero();
};

VClipOutcome update(int body, VClipFeature to, const char* rule, bool localMin = false) {
    VClipOutcome o;
    o.kind = VClipStepKind::Update;
    o.body = body;
    o.to = to;
    o.rule = rule;
    o.localMin = localMin;
    return o;
}

VClipOutcome penetration(VClipPenetration how, int body, const Vec3& point, const char* rule) {
    VClipOutcome o;
    o.kind = VClipStepKind::Penetration;
    o.penetration = how;
    o.pointBody = body;
    o.point = point;
    o.rule = rule;
    return o;
}

VClipOutcome done(const char* rule) {
    VClipOutcome o;
    o.rule = rule;
    return o;
}

/// Result of clipEdge (Mirtich §4.2): the interval [lmin, lmax] of the edge inside the planes
/// seen so far, the neighbours across the planes that set each end, and exclusion flags.
struct Clip {
    double lmin = 0.0, lmax = 1.0;
    VClipFeature nmin, nmax;
    int pmin = -1, pmax = -1;  // plane indices of nmin / nmax
    bool simple = false, compound = false;
    VClipFeature excluder;
    int excluderPlane = -1;
};

/// Closest points of two features in the frame of body `frame`.
struct PairClosest {
    Vec3 p[2];  // p[i]: point of feature i
    double distance = 0.0;
};

struct VClipWalk : feature_walk::WalkPair {
    VClipTraceStep* ts = nullptr;

    Vec3 world(int i, const Vec3& x) const { return Rw[i] * x + pose[i].position; }
    VClipFeature neighborOf(int r, int plane, const VClipFeature& owner) const {
        const VClipPlane& pl = P[r]->plane(plane);
        return owner.type == FT::Edge ? pl.other : pl.edge;
    }

    // --- trace recording (no-ops without a trace) ------------------------------------------
    void recordPlane(int r, const VClipFeature& owner, int plane, double d, const Vec3& tested, bool maximal = false) {
        if (!ts) return;
        const VClipPlane& pl = P[r]->plane(plane);
        VClipPlaneTest t;
        t.regionBody = r;
        t.owner = owner;
        t.neighbor = neighborOf(r, plane, owner);
        t.plane = plane;
        t.signedDistance = d;
        t.violated = d < 0.0;
        t.maximal = maximal;
        // A point of the plane near the features: its vertex (VE) or its edge's tail (FE).
        const Vec3 on = pl.other.type == FT::Vertex ? pos(r, pl.other.index) : pos(r, P[r]->edgeTail(pl.edge.index));
        t.planePoint = world(r, on);
        t.planeNormal = pose[r].rotate(owner.type == FT::Edge ? pl.normal : Vec3(-pl.normal));
        t.testedPoint = world(r, tested);
        ts->planes.push_back(t);
    }
    void recordClip(int r, const VClipFeature& region, const VClipFeature& edge, const Vec3& t, const Vec3& h,
                    const Clip& c, int dmin = 2, int dmax = 2) {
        if (!ts) return;
        VClipClip k;
        k.edgeBody = 1 - r;
        k.edge = edge;
        k.region = region;
        k.lambdaMin = c.lmin;
        k.lambdaMax = c.lmax;
        k.neighborMin = c.nmin;
        k.neighborMax = c.nmax;
        k.simplyExcluded = c.simple;
        k.compoundExcluded = c.compound;
        k.excludedBy = c.excluder;
        k.derivativeMin = dmin;
        k.derivativeMax = dmax;
        k.tail = world(r, t);
        k.head = world(r, h);
        const double a = std::clamp(c.lmin, 0.0, 1.0), b = std::clamp(c.lmax, 0.0, 1.0);
        k.clippedTail = world(r, t + a * (h - t));
        k.clippedHead = world(r, t + b * (h - t));
        ts->clips.push_back(k);
    }
    void setDerivatives(int dmin, int dmax) {
        if (!ts || ts->clips.empty()) return;
        ts->clips.back().derivativeMin = dmin;
        ts->clips.back().derivativeMax = dmax;
    }

    // --- clipEdge (Mirtich §4.2, Fig. 5) ----------------------------------------------------
    // Clips the segment t-h (frame of body r) against the given planes of VR(owner), continuing
    // from `c`. Returns false on exclusion: simple (both ends outside one plane) or compound
    // (the interval became empty).
    template <class Planes>
    bool clipEdge(int r, const VClipFeature& owner, const Planes& planes, const Vec3& t, const Vec3& h, Clip& c) {
        for (int i : planes) {
            const double dt = P[r]->regionDistance(i, owner, t);
            const double dh = P[r]->regionDistance(i, owner, h);
            recordPlane(r, owner, i, dt, t);
            recordPlane(r, owner, i, dh, h);
            const VClipFeature n = neighborOf(r, i, owner);
            if (dt < 0.0 && dh < 0.0) {
                c.simple = true;
                c.excluder = n;
                c.excluderPlane = i;
                return false;
            }
            if (dt < 0.0) {  // entering: dh >= 0 > dt, so l = dt / (dt - dh) lies in (0, 1]
                const double l = dt / (dt - dh);
                if (l > c.lmin) {
                    c.lmin = l;
                    c.nmin = n;
                    c.pmin = i;
                    if (c.lmin > c.lmax) {
                        c.compound = true;
                        return false;
                    }
                }
            } else if (dh < 0.0) {  // leaving: dt >= 0 > dh
                const double l = dt / (dt - dh);
                if (l < c.lmax) {
                    c.lmax = l;
                    c.nmax = n;
                    c.pmax = i;
                    if (c.lmax < c.lmin) {
                        c.compound = true;
                        return false;
                    }
                }
            }
        }
        return true;
    }

    // --- derivative check (Mirtich §4.3) ----------------------------------------------------
    // Sign of d/dl of the distance from e(l) to the features on both sides of `plane` (they are
    // equal on the plane): VE plane of vertex V: sign(u · (e - V)); FE plane of face F:
    // sign(h_F(e) (u · n_F)). onFeature: e(l) lies on V, or on F's plane (then on the edge line):
    // the distance is 0 there.
    int derivativeSign(int r, int plane, const Vec3& t, const Vec3& h, double l, bool& onFeature) const {
        const Vec3 u = h - t;
        const Vec3 e = t + l * u;
        const VClipPlane& pl = P[r]->plane(plane);
        if (pl.other.type == FT::Vertex) {
            const Vec3& v = pos(r, pl.other.index);
            const Vec3 d = e - v;
            const double m = maxAbs(e) + maxAbs(v);
            onFeature = maxAbs(d) <= kRound * m;
            return signAbove(u.dot(d), 3.0 * kRound * maxAbs(u) * m);
        }
        const int f = pl.other.index;
        const double hf = M[r]->planeDistance(f, e);
        const double floorH = kRound * (maxAbs(e) + std::abs(M[r]->face(f).offset));
        onFeature = std::abs(hf) <= floorH;
        return signAbove(hf, floorH) * signAbove(u.dot(M[r]->face(f).normal), 3.0 * kRound * maxAbs(u));
    }

    // --- nearest boundary feature of a face (O(|F|)) ---------------------------------------
    // The boundary edge or vertex of face f (body r) holding the point of f's boundary nearest to
    // the point a (b == nullptr) or to the segment a-b, all in r's frame. A vertex when the
    // nearest point is an edge's endpoint: then no incident edge is preferred over the other,
    // which would let E-E -> E-F -> E-E repeat at equal distance.
    VClipFeature nearestBoundaryFeature(int r, int f, const Vec3& a, const Vec3* b) const {
        double best = std::numeric_limits<double>::infinity();
        VClipFeature bestFeature;
        M[r]->forEachFaceHalfEdge(f, [&](int he) {
            const int e = M[r]->halfEdge(he).edge;
            const Segment s{pos(r, P[r]->edgeTail(e)), pos(r, P[r]->edgeHead(e))};
            double d2, t;
            if (b) {
                const SegmentSegmentResult ss = closestPointsSegmentSegment(Segment{a, *b}, s);
                d2 = ss.distanceSquared;
                t = ss.t;
            } else {
                const ClosestPointOnSegmentResult c = closestPointOnSegment(a, s);
                d2 = c.distanceSquared;
                t = c.t;
            }
            const VClipFeature x = t <= 0.0   ? VClipFeature::vertex(P[r]->edgeTail(e))
                                   : t >= 1.0 ? VClipFeature::vertex(P[r]->edgeHead(e))
                                              : VClipFeature::edge(e);
            if (d2 < best || !bestFeature.valid() || (d2 == best && x.type == FT::Vertex)) {
                best = d2;
                bestFeature = x;
            }
        });
        return bestFeature;
    }

    // --- states (Mirtich §5) ----------------------------------------------------------------

    // V-V: each vertex must lie in the other's region; a violated VE plane names the edge of the
    // other vertex that leads towards it (strict decrease).
    VClipOutcome vertexVertex() {
        for (int r : {0, 1}) {
            const int o = 1 - r;
            const Vec3 p = toFrame(o, pos(o, X[o].index));
            int worst = -1;
            double wd = 0.0;
            for (int i : P[r]->vertexPlanes(X[r].index)) {
                const double d = P[r]->regionDistance(i, X[r], p);
                recordPlane(r, X[r], i, d, p);
                if (d < wd) {
                    wd = d;
                    worst = i;
                }
            }
            if (worst >= 0)
                return update(r, neighborOf(r, worst, X[r]),
                              "vertex outside VR(V): V -> edge of the most violated VE plane");
        }
        return done("V-V: each vertex in the other's region");
    }

    // V-E (vertex on body vb, edge on the other).
    VClipOutcome vertexEdge(int vb) {
        const int eb = 1 - vb, e = X[eb].index;
        const Vec3 p = toFrame(vb, pos(vb, X[vb].index));  // V in E's frame
        // V against VR(E): the VE planes first (neighbour: an endpoint, distance unchanged) ...
        const double d0 = P[eb]->regionDistance(4 * e, X[eb], p), d1 = P[eb]->regionDistance(4 * e + 1, X[eb], p);
        recordPlane(eb, X[eb], 4 * e, d0, p);
        recordPlane(eb, X[eb], 4 * e + 1, d1, p);
        if (d0 < 0.0 || d1 < 0.0) {
            const int i = d0 <= d1 ? 4 * e : 4 * e + 1;
            return update(eb, P[eb]->plane(i).other, "V outside a VE plane of VR(E): E -> that endpoint");
        }
        // ... then the FE planes (neighbour: a face, distance decreases).
        const double d2 = P[eb]->regionDistance(4 * e + 2, X[eb], p), d3 = P[eb]->regionDistance(4 * e + 3, X[eb], p);
        recordPlane(eb, X[eb], 4 * e + 2, d2, p);
        recordPlane(eb, X[eb], 4 * e + 3, d3, p);
        if (d2 < 0.0 || d3 < 0.0) {
            const int i = d2 <= d3 ? 4 * e + 2 : 4 * e + 3;
            return update(eb, P[eb]->plane(i).other, "V outside an FE plane of VR(E): E -> that face");
        }
        // E against VR(V): clip, then the derivative checks.
        const Vec3 t = toFrame(eb, pos(eb, P[eb]->edgeTail(e))), h = toFrame(eb, pos(eb, P[eb]->edgeHead(e)));
        Clip c;
        clipEdge(vb, X[vb], P[vb]->vertexPlanes(X[vb].index), t, h, c);
        recordClip(vb, X[vb], X[eb], t, h, c);
        if (c.simple) return update(vb, c.excluder, "E simply excluded from VR(V): V -> edge of that plane");
        // D'(l) = u · (e(l) - V) / |e(l) - V| increases with l, so one of the two checks fires
        // under compound exclusion too.
        int smin = 2, smax = 2;
        bool on = false;
        if (c.nmin.valid()) {
            smin = derivativeSign(vb, c.pmin, t, h, c.lmin, on);
            setDerivatives(smin, smax);
            if (on) return penetration(VClipPenetration::Touching, vb, t + c.lmin * (h - t), "E passes through V");
            if (smin > 0) return update(vb, c.nmin, "D'(lambdaMin) > 0: V -> Nmin");
        }
        if (c.nmax.valid()) {
            smax = derivativeSign(vb, c.pmax, t, h, c.lmax, on);
            setDerivatives(smin, smax);
            if (on) return penetration(VClipPenetration::Touching, vb, t + c.lmax * (h - t), "E passes through V");
            if (smax < 0) return update(vb, c.nmax, "D'(lambdaMax) < 0: V -> Nmax");
        }
        if (c.compound) return update(vb, c.nmin, "compound exclusion (rounding): V -> Nmin");
        return done("V-E: V in VR(E) and E's closest point in VR(V)");
    }

    // V-F (vertex on body vb, face on the other).
    VClipOutcome vertexFace(int vb) {
        const int fb = 1 - vb, f = X[fb].index, v = X[vb].index;
        const Vec3 p = toFrame(vb, pos(vb, v));  // V in F's frame
        // V against the side planes of VR(F).
        int worst = -1;
        double wd = 0.0;
        const auto planes = P[fb]->facePlanes(f);
        for (int i : planes) {
            const double d = P[fb]->regionDistance(i, X[fb], p);
            if (d < wd) {
                wd = d;
                worst = i;
            }
        }
        if (ts)
            for (int i : planes) recordPlane(fb, X[fb], i, P[fb]->regionDistance(i, X[fb], p), p, i == worst);
        if (worst >= 0)
            return update(fb, nearestBoundaryFeature(fb, f, p, nullptr),
                          "V outside VR(F): F -> its boundary feature nearest to V");
        const double hv = M[fb]->planeDistance(f, p);
        const double floorV = kRound * (maxAbs(p) + std::abs(M[fb]->face(f).offset));
        if (std::abs(hv) <= floorV) return penetration(VClipPenetration::Touching, fb, p, "V lies on F");
        // An edge of V leading towards F's plane (|h| decreases along it) is closer: V -> edge.
        const int start = M[vb]->vertex(v).halfEdge;
        int he = start;
        do {
            const int w = M[vb]->halfEdgeDestination(he);
            const Vec3 pw = toFrame(vb, pos(vb, w));
            const double hw = M[fb]->planeDistance(f, pw);
            // |h| must drop by more than the rounding of the two plane distances.
            const double floorW = 2.0 * floorV + kRound * maxAbs(pw);
            if ((hv > 0.0 && hw < hv - floorW) || (hv < 0.0 && hw > hv + floorW))
                return update(vb, VClipFeature::edge(M[vb]->halfEdge(he).edge),
                              "an edge of V points towards F: V -> that edge");
            he = M[vb]->halfEdge(M[vb]->halfEdge(he).prev).twin;
        } while (he != start);
        if (hv > 0.0) return done("V-F: V in VR(F) above F, no edge of V leads closer");
        // handleLocalMin (Mirtich §5.4): V is below F's plane with every edge leading away.
        int best = -1;
        double dmax = -std::numeric_limits<double>::infinity();
        for (int g = 0; g < M[fb]->faceCount(); ++g) {
            const double d = M[fb]->planeDistance(g, p);
            if (d > dmax) {
                dmax = d;
                best = g;
            }
        }
        if (ts) {
            VClipPlaneTest t;
            t.regionBody = fb;
            t.owner = VClipFeature::face(best);
            t.signedDistance = dmax;
            t.violated = dmax > 0.0;
            t.maximal = true;
            t.planePoint = world(fb, pos(fb, M[fb]->faceVertices(best)[0]));
            t.planeNormal = pose[fb].rotate(M[fb]->face(best).normal);
            t.testedPoint = world(fb, p);
            ts->planes.push_back(t);
        }
        if (dmax <= kRound * (maxAbs(p) + std::abs(M[fb]->face(best).offset)))
            return penetration(VClipPenetration::LocalMinimum, fb, p, "local minimum with dmax <= 0: V inside");
        return update(fb, VClipFeature::face(best), "local minimum: F -> the face V is farthest above", true);
    }

    // E-E, one direction: the edge X[1 - r] against VR(X[r]). Returns true with `out` on an update.
    bool edgeEdgeSubtest(int r, VClipOutcome& out) {
        const int o = 1 - r, x = X[r].index, e = X[o].index;
        const Vec3 t = toFrame(o, pos(o, P[o]->edgeTail(e))), h = toFrame(o, pos(o, P[o]->edgeHead(e)));
        Clip c;
        const std::array<int, 2> ve{4 * x, 4 * x + 1}, fe{4 * x + 2, 4 * x + 3};
        // The VE planes first: exclusion by one means E' -> that endpoint (distance unchanged).
        clipEdge(r, X[r], ve, t, h, c);
        if (c.simple) {
            recordClip(r, X[r], X[o], t, h, c);
            out = update(r, c.excluder, "E simply excluded by a VE plane of VR(E'): E' -> that endpoint");
            return true;
        }
        const Clip cv = c;  // interval inside the VE slab
        clipEdge(r, X[r], fe, t, h, c);
        recordClip(r, X[r], X[o], t, h, c);
        bool on = false;
        if (c.simple) {
            // E is beyond an FE plane; the vertex derivatives decide whether its closest point
            // on E' is an endpoint (E' -> vertex) or interior (E' -> the face: closer).
            if (cv.nmin.valid()) {
                const int s = derivativeSign(r, cv.pmin, t, h, cv.lmin, on);
                if (on) {
                    out = penetration(VClipPenetration::Touching, r, t + cv.lmin * (h - t), "E touches E'");
                    return true;
                }
                if (s > 0) {
                    out = update(r, cv.nmin, "E excluded by an FE plane, D'(vertex lambdaMin) > 0: E' -> Nmin");
                    return true;
                }
            }
            if (cv.nmax.valid()) {
                const int s = derivativeSign(r, cv.pmax, t, h, cv.lmax, on);
                if (on) {
                    out = penetration(VClipPenetration::Touching, r, t + cv.lmax * (h - t), "E touches E'");
                    return true;
                }
                if (s < 0) {
                    out = update(r, cv.nmax, "E excluded by an FE plane, D'(vertex lambdaMax) < 0: E' -> Nmax");
                    return true;
                }
            }
            out = update(r, c.excluder, "E simply excluded by an FE plane of VR(E'): E' -> that face");
            return true;
        }
        if (c.compound) {
            // Decide from the closest pair of the two segments (see the file comment).
            const Segment sx{pos(r, P[r]->edgeTail(x)), pos(r, P[r]->edgeHead(x))};
            const SegmentSegmentResult ss = closestPointsSegmentSegment(Segment{t, h}, sx);
            if (ss.t <= 0.0) {
                out = update(r, VClipFeature::vertex(P[r]->edgeTail(x)),
                             "compound exclusion, closest point of E' is its tail: E' -> tail");
                return true;
            }
            if (ss.t >= 1.0) {
                out = update(r, VClipFeature::vertex(P[r]->edgeHead(x)),
                             "compound exclusion, closest point of E' is its head: E' -> head");
                return true;
            }
            const double d2 = P[r]->regionDistance(4 * x + 2, X[r], ss.pointOnFirst);
            const double d3 = P[r]->regionDistance(4 * x + 3, X[r], ss.pointOnFirst);
            out = update(r, P[r]->plane(d2 <= d3 ? 4 * x + 2 : 4 * x + 3).other,
                         "compound exclusion, closest point of E beyond an FE plane: E' -> that face");
            return true;
        }
        // Post-clip derivative checks (Mirtich Fig. 6).
        int smin = 2, smax = 2;
        if (c.nmin.valid()) {
            smin = derivativeSign(r, c.pmin, t, h, c.lmin, on);
            setDerivatives(smin, smax);
            if (on) {
                out = penetration(VClipPenetration::Touching, r, t + c.lmin * (h - t), "E touches E'");
                return true;
            }
            if (smin > 0) {
                out = update(r, c.nmin, "D'(lambdaMin) > 0: E' -> Nmin");
                return true;
            }
        }
        if (c.nmax.valid()) {
            smax = derivativeSign(r, c.pmax, t, h, c.lmax, on);
            setDerivatives(smin, smax);
            if (on) {
                out = penetration(VClipPenetration::Touching, r, t + c.lmax * (h - t), "E touches E'");
                return true;
            }
            if (smax < 0) {
                out = update(r, c.nmax, "D'(lambdaMax) < 0: E' -> Nmax");
                return true;
            }
        }
        return false;
    }

    VClipOutcome edgeEdge() {
        VClipOutcome out;
        // E_A against VR(E_B) first, then E_B against VR(E_A) (Mirtich Fig. 9).
        if (edgeEdgeSubtest(1, out)) return out;
        if (edgeEdgeSubtest(0, out)) return out;
        return done("E-E: each edge's closest point in the other's region");
    }

    // E-F (edge on body eb, face on the other). Never DONE: either an update or a penetration.
    VClipOutcome edgeFace(int eb) {
        const int fb = 1 - eb, e = X[eb].index, f = X[fb].index;
        const Vec3 t = toFrame(eb, pos(eb, P[eb]->edgeTail(e))), h = toFrame(eb, pos(eb, P[eb]->edgeHead(e)));
        Clip c;
        clipEdge(fb, X[fb], P[fb]->facePlanes(f), t, h, c);
        recordClip(fb, X[fb], X[eb], t, h, c);
        if (c.simple || c.compound)
            return update(fb, nearestBoundaryFeature(fb, f, t, &h),
                          "E excluded from VR(F): F -> its boundary feature nearest to E");
        const Vec3 u = h - t;
        const Vec3 emin = t + c.lmin * u, emax = t + c.lmax * u;
        const double hmin = M[fb]->planeDistance(f, emin), hmax = M[fb]->planeDistance(f, emax);
        const double floorH = kRound * (std::max(maxAbs(emin), maxAbs(emax)) + std::abs(M[fb]->face(f).offset));
        if (std::abs(hmin) <= floorH || std::abs(hmax) <= floorH || (hmin > 0.0) != (hmax > 0.0)) {
            // The clipped edge crosses (or touches) F's plane inside VR(F): it meets F.
            const double w = hmin == hmax ? 0.0 : hmin / (hmin - hmax);
            return penetration(VClipPenetration::EdgePiercesFace, fb, emin + w * (emax - emin), "E pierces F");
        }
        // Both clipped ends on one side: the distance to F is |h| there, linear in l.
        const int s = signAbove(hmin, floorH) * signAbove(u.dot(M[fb]->face(f).normal), 3.0 * kRound * maxAbs(u));
        setDerivatives(s, s);
        if (s > 0) {
            if (c.nmin.valid())
                return update(fb, nearestBoundaryFeature(fb, f, t, &h),
                              "D'(lambdaMin) > 0 at a side plane: F -> its boundary feature nearest to E");
            return update(eb, VClipFeature::vertex(P[eb]->edgeTail(e)), "D'(0) > 0 inside VR(F): E -> tail");
        }
        if (s < 0) {
            if (c.nmax.valid())
                return update(fb, nearestBoundaryFeature(fb, f, t, &h),
                              "D'(lambdaMax) < 0 at a side plane: F -> its boundary feature nearest to E");
            return update(eb, VClipFeature::vertex(P[eb]->edgeHead(e)), "D'(1) < 0 inside VR(F): E -> head");
        }
        // E parallel to F: every point of the clipped part is at the same distance.
        if (!c.nmin.valid())
            return update(eb, VClipFeature::vertex(P[eb]->edgeTail(e)), "E parallel to F, tail in VR(F): E -> tail");
        if (!c.nmax.valid())
            return update(eb, VClipFeature::vertex(P[eb]->edgeHead(e)), "E parallel to F, head in VR(F): E -> head");
        return update(fb, c.nmin, "E parallel to F: F -> Nmin");
    }

    VClipOutcome step() {
        const FT a = X[0].type, b = X[1].type;
        if (a == FT::Vertex && b == FT::Vertex) return vertexVertex();
        if (a == FT::Vertex && b == FT::Edge) return vertexEdge(0);
        if (a == FT::Edge && b == FT::Vertex) return vertexEdge(1);
        if (a == FT::Vertex && b == FT::Face) return vertexFace(0);
        if (a == FT::Face && b == FT::Vertex) return vertexFace(1);
        if (a == FT::Edge && b == FT::Edge) return edgeEdge();
        if (a == FT::Edge && b == FT::Face) return edgeFace(0);
        return edgeFace(1);  // F-E (F-F is never entered: seeds are sanitised)
    }

    // --- geometry of a feature pair (DONE answers and trace distances) ---------------------

    // Closest point of face f (body r) to point p (r's frame) and the distance.
    Vec3 closestOnFace(int r, int f, const Vec3& p) const {
        bool inside = true;
        for (int i : P[r]->facePlanes(f))
            if (P[r]->regionDistance(i, VClipFeature::face(f), p) < 0.0) inside = false;
        if (inside) return p - M[r]->planeDistance(f, p) * M[r]->face(f).normal;
        double best = std::numeric_limits<double>::infinity();
        Vec3 q = p;
        M[r]->forEachFaceHalfEdge(f, [&](int he) {
            const int e = M[r]->halfEdge(he).edge;
            const ClosestPointOnSegmentResult c =
                closestPointOnSegment(p, Segment{pos(r, P[r]->edgeTail(e)), pos(r, P[r]->edgeHead(e))});
            if (c.distanceSquared < best) {
                best = c.distanceSquared;
                q = c.point;
            }
        });
        return q;
    }

    // Closest points of features f0 (body 0) and f1 (body 1), in the frame `frame` it returns
    // (the face's body if there is a face, else A's). F-F is never a state and not supported:
    // body 0's face then stands for its first vertex.
    PairClosest closest(const VClipFeature& f0, const VClipFeature& f1, int& frame) const {
        const VClipFeature f[2] = {f0, f1};
        // Work in the frame of the face's body if there is a face, else A's.
        frame = f1.type == FT::Face ? 1 : 0;
        const int r = frame, o = 1 - r;
        auto pts = [&](int i, Vec3* out) -> int {
            auto map = [&](const Vec3& x) { return i == r ? x : toFrame(i, x); };
            if (f[i].type == FT::Vertex) {
                out[0] = map(pos(i, f[i].index));
                return 1;
            }
            if (f[i].type == FT::Edge) {
                out[0] = map(pos(i, P[i]->edgeTail(f[i].index)));
                out[1] = map(pos(i, P[i]->edgeHead(f[i].index)));
                return 2;
            }
            out[0] = map(pos(i, M[i]->halfEdge(M[i]->face(f[i].index).halfEdge).origin));
            return 1;
        };
        PairClosest pc;
        Vec3 a[2] = {Vec3::Zero(), Vec3::Zero()}, b[2] = {Vec3::Zero(), Vec3::Zero()};
        const int na = pts(r, a), nb = pts(o, b);
        Vec3 qr = Vec3::Zero(), qo = Vec3::Zero();  // points of f[r], f[o] in frame r
        if (f[r].type == FT::Face) {
            const int face = f[r].index;
            if (nb == 1) {
                qo = b[0];
                qr = closestOnFace(r, face, qo);
            } else {
                // Segment vs convex polygon: 0 if it crosses the face inside; else the best of
                // the endpoints vs the face and the segment vs each boundary edge.
                const double ht = M[r]->planeDistance(face, b[0]), hh = M[r]->planeDistance(face, b[1]);
                bool hit = false;
                if ((ht <= 0.0 && hh >= 0.0) || (ht >= 0.0 && hh <= 0.0)) {
                    const double w = ht == hh ? 0.0 : ht / (ht - hh);
                    const Vec3 x = b[0] + w * (b[1] - b[0]);
                    hit = std::all_of(P[r]->facePlanes(face).begin(), P[r]->facePlanes(face).end(),
                                      [&](int i) { return P[r]->regionDistance(i, f[r], x) >= 0.0; });
                    if (hit) qr = qo = x;
                }
                if (!hit) {
                    double best = std::numeric_limits<double>::infinity();
                    for (int k = 0; k < 2; ++k) {
                        const Vec3 q = closestOnFace(r, face, b[k]);
                        const double d2 = (q - b[k]).squaredNorm();
                        if (d2 < best) {
                            best = d2;
                            qr = q;
                            qo = b[k];
                        }
                    }
                    M[r]->forEachFaceHalfEdge(face, [&](int he) {
                        const int e = M[r]->halfEdge(he).edge;
                        const SegmentSegmentResult ss = closestPointsSegmentSegment(
                            Segment{b[0], b[1]}, Segment{pos(r, P[r]->edgeTail(e)), pos(r, P[r]->edgeHead(e))});
                        if (ss.distanceSquared < best) {
                            best = ss.distanceSquared;
                            qo = ss.pointOnFirst;
                            qr = ss.pointOnSecond;
                        }
                    });
                }
            }
        } else if (na == 1 && nb == 1) {
            qr = a[0];
            qo = b[0];
        } else if (na == 1) {
            qr = a[0];
            qo = closestPointOnSegment(a[0], Segment{b[0], b[1]}).point;
        } else if (nb == 1) {
            qo = b[0];
            qr = closestPointOnSegment(b[0], Segment{a[0], a[1]}).point;
        } else {
            const SegmentSegmentResult ss = closestPointsSegmentSegment(Segment{a[0], a[1]}, Segment{b[0], b[1]});
            qr = ss.pointOnFirst;
            qo = ss.pointOnSecond;
        }
        pc.p[r] = qr;
        pc.p[o] = qo;
        pc.distance = (qr - qo).norm();
        return pc;
    }
};

}  // namespace

namespace {

// The trace step of the pair before it moves: the state, the features and their closest points.
VClipTraceStep* beginTraceStep(VClipTrace* trace, const VClipWalk& w, int step) {
    if (!trace) return nullptr;
    VClipTraceStep* ts = &trace->steps.emplace_back();
    ts->step = step;
    const FT ta = w.X[0].type, tb = w.X[1].type;
    const int lo = std::min(static_cast<int>(ta), static_cast<int>(tb)),
              hi = std::max(static_cast<int>(ta), static_cast<int>(tb));
    ts->state = lo == 1 ? (hi == 1   ? VClipState::VertexVertex
                           : hi == 2 ? VClipState::VertexEdge
                                     : VClipState::VertexFace)
                        : (hi == 2 ? VClipState::EdgeEdge : VClipState::EdgeFace);
    ts->featureA = w.X[0];
    ts->featureB = w.X[1];
    ts->featureAWorld = featureGeometry(*w.P[0], w.pose[0], w.X[0]);
    ts->featureBWorld = featureGeometry(*w.P[1], w.pose[1], w.X[1]);
    int frame = 0;
    const PairClosest pc = w.closest(w.X[0], w.X[1], frame);
    ts->closestA = w.world(frame, pc.p[0]);
    ts->closestB = w.world(frame, pc.p[1]);
    ts->distanceBefore = ts->distanceAfter = pc.distance;
    return ts;
}

// The distance after an update and its sign of change. Equal in exact arithmetic, computed by
// different formulas: allow rounding of ~1e-12 of the size of the bodies (formula errors are
// ~1e-15 of it).
void recordUpdate(VClipTraceStep* ts, const VClipWalk& w, const VClipOutcome& out, const VClipFeature& from, double extent) {
    if (!ts) return;
    ts->updatedBody = out.body;
    ts->from = from;
    ts->to = out.to;
    int frame = 0;
    ts->distanceAfter = w.closest(w.X[0], w.X[1], frame).distance;
    const double tol = 1e-12 * (extent + ts->distanceBefore);
    const double diff = ts->distanceAfter - ts->distanceBefore;
    ts->distanceChange = diff > tol ? 1 : diff < -tol ? -1 : 0;
}

// The answer when the walk stops: penetrating, touching (DONE at a distance below the rounding of
// the features' coordinates) or separated at the closest points.
void finalAnswer(const VClipWalk& w, const VClipOutcome& out, VClipTraceStep* ts, VClipResult& res) {
    if (out.kind == VClipStepKind::Penetration) {
        res.status = VClipStatus::Penetrating;
        res.penetration = out.penetration;
        res.intersect = true;
        res.distance = 0.0;
        res.pointA = res.pointB = w.world(out.pointBody, out.point);
        return;
    }
    int frame = 0;
    const PairClosest pc = w.closest(w.X[0], w.X[1], frame);
    if (pc.distance <= kRound * (maxAbs(pc.p[0]) + maxAbs(pc.p[1]))) {
        res.status = VClipStatus::Penetrating;
        res.penetration = VClipPenetration::Touching;
        res.intersect = true;
        res.pointA = res.pointB = w.world(frame, pc.p[0]);
        if (ts) ts->kind = VClipStepKind::Penetration;
    } else {
        res.status = VClipStatus::Separated;
        res.distance = pc.distance;
        res.pointA = w.world(frame, pc.p[0]);
        res.pointB = w.world(frame, pc.p[1]);
        res.normal = w.Rw[frame] * ((pc.p[1] - pc.p[0]) / pc.distance);
    }
}

}  // namespace

// Mirtich 1998 (see the top of this file): from the seed pair, apply the state's update rule
// until it reports DONE or penetration; a repeated pair or the step bound stops a rounding loop.
VClipResult vclip(const VClipPolyhedron& a, const Transform& poseA, const VClipPolyhedron& b, const Transform& poseB,
                  VClipCache* cache, const VClipOptions& options, VClipTrace* trace) {
    VClipResult res;
    if (trace) *trace = VClipTrace{};
    auto fail = [&](VClipStatus status, std::string message) {
        res.status = status;
        res.message = std::move(message);
        if (trace) trace->status = status;
        return res;
    };
    if (a.empty() || b.empty()) return fail(VClipStatus::InvalidInput, "vclip: empty polyhedron");
    if (!finitePose(poseA) || !finitePose(poseB)) return fail(VClipStatus::InvalidInput, "vclip: non-finite pose");

    VClipWalk w;
    w.setup(a, poseA, b, poseB);
    // Seed: the cached pair if valid, else vertex 0 of each. F-F is never a state: B's face is
    // replaced by one of its vertices.
    if (cache && validFeature(a, cache->a) && validFeature(b, cache->b)) {
        w.X[0] = cache->a;
        w.X[1] = cache->b;
        if (w.X[0].type == FT::Face && w.X[1].type == FT::Face)
            w.X[1] = VClipFeature::vertex(b.mesh().halfEdge(b.mesh().face(w.X[1].index).halfEdge).origin);
    }

    const long long bound = static_cast<long long>(a.featureCount()) * b.featureCount();
    const long long maxSteps = options.maxSteps > 0 ? options.maxSteps : bound;
    feature_walk::FeaturePairCycle cycle(w.X[0], w.X[1]);
    double extent = 0.0;  // trace only: scale for "equal" distances
    if (trace)
        extent = std::max((a.mesh().boundsMax() - a.mesh().boundsMin()).norm(),
                          (b.mesh().boundsMax() - b.mesh().boundsMin()).norm());

    for (int steps = 0;; ++steps) {
        res.steps = steps;
        res.featureA = w.X[0];
        res.featureB = w.X[1];
        if (options.detectCycles && steps > 0 && cycle.repeats(w.X[0], w.X[1])) {
            if (cache) *cache = VClipCache{w.X[0], w.X[1]};
            if (trace && !trace->steps.empty()) trace->steps.back().kind = VClipStepKind::Aborted;
            return fail(VClipStatus::CycleDetected,
                        "vclip: feature pair " + nameOf(w.X[0]) + "/" + nameOf(w.X[1]) + " repeated");
        }
        if (steps >= maxSteps) {
            if (cache) *cache = VClipCache{w.X[0], w.X[1]};
            return fail(VClipStatus::StepLimit, "vclip: step limit " + std::to_string(maxSteps) + " reached");
        }
        VClipTraceStep* ts = beginTraceStep(trace, w, steps);
        w.ts = ts;
        const VClipOutcome out = w.step();
        if (ts) {
            ts->kind = out.kind;
            ts->rule = out.rule;
            ts->localMinimum = out.localMin;
        }
        if (out.kind == VClipStepKind::Update) {
            const VClipFeature from = w.X[out.body];
            w.X[out.body] = out.to;
            recordUpdate(ts, w, out, from, extent);
            continue;
        }
        if (cache) *cache = VClipCache{w.X[0], w.X[1]};
        finalAnswer(w, out, ts, res);
        if (trace) trace->status = res.status;
        return res;
    }
}

}  // namespace cdlab
