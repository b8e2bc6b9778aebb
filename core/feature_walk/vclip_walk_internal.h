// Internal to core/feature_walk's V-Clip (conventions and numerics: the top of vclip_walk.cpp):
// the walk's outcome and clip records, the rounding floor, and VClipWalk, whose state rules
// (Mirtich §5) are defined in vclip_walk_states.cpp and whose driver, vclip(), is in vclip_walk.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/base/tolerances.h"
#include "core/closest/closest_point.h"
#include "core/feature_walk/feature_walk_pair.h"
#include "core/feature_walk/vclip.h"

namespace cdlab::vclip_internal {

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

inline int signAbove(double x, double floor) { return x > floor ? 1 : (x < -floor ? -1 : 0); }
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

inline VClipOutcome update(int body, VClipFeature to, const char* rule, bool localMin = false) {
    VClipOutcome o;
    o.kind = VClipStepKind::Update;
    o.body = body;
    o.to = to;
    o.rule = rule;
    o.localMin = localMin;
    return o;
}

inline VClipOutcome penetration(VClipPenetration how, int body, const Vec3& point, const char* rule) {
    VClipOutcome o;
    o.kind = VClipStepKind::Penetration;
    o.penetration = how;
    o.pointBody = body;
    o.point = point;
    o.rule = rule;
    return o;
}

inline VClipOutcome done(const char* rule) {
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
    // (defined in vclip_walk_states.cpp)
    VClipOutcome vertexVertex();
    VClipOutcome vertexEdge(int vb);
    VClipOutcome vertexFace(int vb);
    bool edgeEdgeSubtest(int r, VClipOutcome& out);
    VClipOutcome edgeEdge();
    VClipOutcome edgeFace(int eb);
    VClipOutcome step();

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

}  // namespace cdlab::vclip_internal
