// The V-Clip state rules (Mirtich 1998, §5): one update, DONE or penetration per feature pair;
// conventions and numerics as stated at the top of vclip_walk.cpp.
#include "core/feature_walk/vclip_walk_internal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cdlab::vclip_internal {

// V-V: each vertex must lie in the other's region; a violated VE plane names the edge of the
// other vertex that leads towards it (strict decrease).
VClipOutcome VClipWalk::vertexVertex() {
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
VClipOutcome VClipWalk::vertexEdge(int vb) {
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
VClipOutcome VClipWalk::vertexFace(int vb) {
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
bool VClipWalk::edgeEdgeSubtest(int r, VClipOutcome& out) {
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

VClipOutcome VClipWalk::edgeEdge() {
    VClipOutcome out;
    // E_A against VR(E_B) first, then E_B against VR(E_A) (Mirtich Fig. 9).
    if (edgeEdgeSubtest(1, out)) return out;
    if (edgeEdgeSubtest(0, out)) return out;
    return done("E-E: each edge's closest point in the other's region");
}

// E-F (edge on body eb, face on the other). Never DONE: either an update or a penetration.
VClipOutcome VClipWalk::edgeFace(int eb) {
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

VClipOutcome VClipWalk::step() {
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

}  // namespace cdlab::vclip_internal
