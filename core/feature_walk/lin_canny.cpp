// Lin–Canny closest-feature tracking (Lin & Canny, ICRA 1991; Lin, PhD thesis 1993, ch. 3;
// summarised in Mirtich, ACM TOG 1998, §2). See core/feature_walk/lin_canny.h for the outline.
//
// Conventions as in core/feature_walk/vclip_walk.cpp: body 0 is A, body 1 is B, X[i] the feature of body i.
// Closest points of the pair are computed in A's frame; the point of B is tested against A's
// planes there, the point of A is mapped into B's frame and tested against B's planes. Region
// distances are positive INSIDE the region.
#include "core/feature_walk/lin_canny.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/closest/closest_point.h"
#include "core/feature_walk/feature_walk_pair.h"

namespace cdlab {

const char* nameOf(LinCannyStatus status) {
    switch (status) {
        case LinCannyStatus::Separated: return "Separated";
        case LinCannyStatus::Penetrating: return "Penetrating";
        case LinCannyStatus::CycleDetected: return "CycleDetected";
        case LinCannyStatus::StepLimit: return "StepLimit";
        case LinCannyStatus::InvalidInput: return "InvalidInput";
    }
    return "?";
}

const char* nameOf(LinCannyPenetration how) {
    switch (how) {
        case LinCannyPenetration::None: return "None";
        case LinCannyPenetration::FeaturesMeet: return "FeaturesMeet";
        case LinCannyPenetration::PointInside: return "PointInside";
    }
    return "?";
}

namespace {

using FT = VClipFeatureType;

using feature_walk::finitePose;
using feature_walk::maxAbs;
using feature_walk::validFeature;

ContactType pairType(const VClipFeature& a, const VClipFeature& b) {
    const int lo = std::min(a.dimension(), b.dimension()), hi = std::max(a.dimension(), b.dimension());
    if (lo == 0) return hi == 0 ? ContactType::VV : hi == 1 ? ContactType::VE : ContactType::VF;
    if (lo == 1) return hi == 1 ? ContactType::EE : ContactType::EF;
    return ContactType::FF;
}

/// What one step decided.
struct LinCannyOutcome {
    VClipStepKind kind = VClipStepKind::Done;
    int body = -1;
    VClipFeature to;
    bool localMin = false;
    LinCannyPenetration penetration = LinCannyPenetration::None;
    std::string rule;
};

struct LinCannyWalk : feature_walk::WalkPair {
    double eps = 0.0;    // applicability slack, absolute (options.applicability * scale)
    double touch = 0.0;  // touching distance, absolute
    bool insideTest = false;
    LinCannyTraceStep* ts = nullptr;
    std::vector<Vec3> polyA, polyB;  // scratch: face polygons in A's frame

    // Closest points of the pair, A's frame: p[0] on X[0], p[1] on X[1].
    Vec3 p[2];
    double distance = 0.0;

    // Body-i point in A's frame.
    Vec3 inA(int i, const Vec3& x) const { return i == 0 ? x : toFrame(1, x); }
    Vec3 world(int i, const Vec3& x) const { return pose[i].apply(x); }

    void polygon(int i, int f, std::vector<Vec3>& out) const {
        out.clear();
        M[i]->forEachFaceHalfEdge(f, [&](int h) { out.push_back(inA(i, pos(i, M[i]->halfEdge(h).origin))); });
    }
    Segment segment(int i, int e) const {
        return {inA(i, pos(i, P[i]->edgeTail(e))), inA(i, pos(i, P[i]->edgeHead(e)))};
    }

    // --- 1. closest points of the feature pair (Ericson §5.1 via core/closest/closest_point.h and
    //        core/closest/feature_distance.h; both have their own parallel thresholds, documented there) ---
    void closest() {
        const VClipFeature &a = X[0], &b = X[1];
        // Order so that the lower-dimensional feature comes first; swap back at the end.
        const bool swap = a.dimension() > b.dimension();
        const VClipFeature& f = swap ? b : a;
        const VClipFeature& g = swap ? a : b;
        const int fi = swap ? 1 : 0, gi = 1 - fi;
        Vec3 q, r;  // on f, on g
        if (f.type == FT::Vertex) {
            q = inA(fi, pos(fi, f.index));
            if (g.type == FT::Vertex) {
                r = inA(gi, pos(gi, g.index));
            } else if (g.type == FT::Edge) {
                r = closestPointOnSegment(q, segment(gi, g.index)).point;
            } else {
                polygon(gi, g.index, polyB);
                r = closestPointOnPolygon(q, polyB).point;
            }
        } else if (f.type == FT::Edge) {
            const Segment s = segment(fi, f.index);
            if (g.type == FT::Edge) {
                const SegmentSegmentResult ss = closestPointsSegmentSegment(s, segment(gi, g.index));
                q = ss.pointOnFirst;
                r = ss.pointOnSecond;
            } else {
                polygon(gi, g.index, polyB);
                const FeaturePairPoints sp = closestPointsSegmentPolygon(s, polyB);
                q = sp.pointA;
                r = sp.pointB;
            }
        } else {
            polygon(fi, f.index, polyA);
            polygon(gi, g.index, polyB);
            const FeaturePairPoints pp = closestPointsPolygonPolygon(polyA, polyB);
            q = pp.pointA;
            r = pp.pointB;
        }
        p[fi] = q;
        p[gi] = r;
        distance = (p[1] - p[0]).norm();
    }

    // --- trace recording -------------------------------------------------------------------
    void recordPlane(int r, const VClipFeature& owner, int plane, double d, const Vec3& tested) {
        if (!ts) return;
        VClipPlaneTest t;
        t.regionBody = r;
        t.owner = owner;
        t.plane = plane;
        t.signedDistance = d;
        t.violated = d < -eps;
        t.testedPoint = world(r, tested);
        if (plane >= 0) {
            const VClipPlane& pl = P[r]->plane(plane);
            t.neighbor = owner.type == FT::Edge ? pl.other : pl.edge;
            const Vec3 on =
                pl.other.type == FT::Vertex ? pos(r, pl.other.index) : pos(r, P[r]->edgeTail(pl.edge.index));
            t.planePoint = world(r, on);
            t.planeNormal = pose[r].rotate(owner.type == FT::Edge ? pl.normal : Vec3(-pl.normal));
        } else {  // the face plane itself
            const int f = owner.index;
            t.planePoint = world(r, pos(r, M[r]->halfEdge(M[r]->face(f).halfEdge).origin));
            t.planeNormal = pose[r].rotate(M[r]->face(f).normal);
        }
        ts->planes.push_back(t);
    }
    void markMaximal() {
        if (ts && !ts->planes.empty()) {
            // The chosen plane is the most violated one recorded for this region: mark it.
            VClipPlaneTest* best = nullptr;
            for (VClipPlaneTest& t : ts->planes)
                if (t.regionBody == ts->planes.back().regionBody && t.violated &&
                    (!best || t.signedDistance < best->signedDistance))
                    best = &t;
            if (best) best->maximal = true;
        }
    }

    // --- 2./3./4. applicability test of point x (frame of body r) against VR(X[r]) ----------
    // Returns true and fills `out` when a plane is violated by more than eps.
    bool applicability(int r, const Vec3& x, LinCannyOutcome& out) {
        const VClipFeature& owner = X[r];
        const VClipPolyhedron& poly = *P[r];
        int worst = -1;
        double worstD = -eps;  // violated = more than eps outside (see LinCannyOptions::applicability)
        auto test = [&](int i) {
            const double d = poly.regionDistance(i, owner, x);
            recordPlane(r, owner, i, d, x);
            if (d < worstD) {
                worstD = d;
                worst = i;
            }
        };
        if (owner.type == FT::Vertex) {
            for (int i : poly.vertexPlanes(owner.index)) test(i);
        } else if (owner.type == FT::Edge) {
            for (int k = 0; k < 4; ++k) test(VClipPolyhedron::edgePlane(owner.index, k));
        } else {
            for (int i : poly.facePlanes(owner.index)) test(i);
        }
        const char* point = r == 0 ? "pB" : "pA";  // rules are text for the trace only
        if (worst >= 0) {
            const VClipPlane& pl = poly.plane(worst);
            out.kind = VClipStepKind::Update;
            out.body = r;
            out.to = owner.type == FT::Edge ? pl.other : pl.edge;
            if (ts)
                out.rule = std::string(point) + " violates " + (pl.other.type == FT::Vertex ? "VE(" : "FE(") +
                           nameOf(pl.edge) + " | " + nameOf(pl.other) + ")";
            markMaximal();
            return true;
        }
        if (owner.type != FT::Face) return false;
        // The face plane bounds VR(F) from below. Behind it (by more than eps) while inside every
        // side plane: no neighbour of F is nearer; Lin 1993's local-minimum search over all faces.
        const int f = owner.index;
        const double h = M[r]->planeDistance(f, x);
        recordPlane(r, owner, -1, h, x);
        if (h >= -eps) return false;
        int bestFace = -1;
        double bestH = -std::numeric_limits<double>::infinity();
        for (int g = 0; g < M[r]->faceCount(); ++g) {
            const double hg = M[r]->planeDistance(g, x);
            if (hg > bestH) {
                bestH = hg;
                bestFace = g;
            }
        }
        if (ts) ts->planes.back().maximal = true;
        // In front of some face by more than eps: go there (the local-minimum jump). Behind every
        // face plane, x (a point of the other body) is inside this body: the original has no test
        // for that and jumps to the least-behind face anyway, which is where it cycles on
        // penetrating bodies; insideTest (cdlab's addition, V-Clip's handleLocalMin test) stops.
        // If the least-behind face is F itself there is nowhere to go: x is inside either way.
        if (bestH > eps || (!insideTest && bestFace != f)) {
            out.kind = VClipStepKind::Update;
            out.body = r;
            out.to = VClipFeature::face(bestFace);
            out.localMin = true;
            if (ts)
                out.rule = std::string("local minimum: ") + point + " behind " + nameOf(owner) +
                           ", farthest in front of F" + std::to_string(bestFace);
            return true;
        }
        out.kind = VClipStepKind::Penetration;
        out.body = r;
        out.penetration = LinCannyPenetration::PointInside;
        if (ts) out.rule = std::string(point) + " behind every face plane of " + (r == 0 ? "A" : "B");
        return true;
    }

    LinCannyOutcome step() {
        LinCannyOutcome out;
        closest();
        if (distance <= touch) {
            out.kind = VClipStepKind::Penetration;
            out.penetration = LinCannyPenetration::FeaturesMeet;
            if (ts) out.rule = "features meet";
            return out;
        }
        if (applicability(0, p[1], out)) return out;
        if (applicability(1, toFrame(0, p[0]), out)) return out;
        out.kind = VClipStepKind::Done;
        if (ts) out.rule = "pA in VR(XB) and pB in VR(XA)";
        return out;
    }
};

}  // namespace

namespace {

// The trace step of the pair before it moves: the state, the features in world space.
LinCannyTraceStep* beginTraceStep(LinCannyTrace* trace, const LinCannyWalk& w, int step) {
    if (!trace) return nullptr;
    LinCannyTraceStep* ts = &trace->steps.emplace_back();
    ts->step = step;
    ts->state = pairType(w.X[0], w.X[1]);
    ts->featureA = w.X[0];
    ts->featureB = w.X[1];
    ts->featureAWorld = featureGeometry(*w.P[0], w.pose[0], w.X[0]);
    ts->featureBWorld = featureGeometry(*w.P[1], w.pose[1], w.X[1]);
    return ts;
}

// What the step decided and the closest points it found.
void recordOutcome(LinCannyTraceStep* ts, const LinCannyWalk& w, const LinCannyOutcome& out) {
    if (!ts) return;
    ts->closestA = w.world(0, w.p[0]);
    ts->closestB = w.world(0, w.p[1]);
    ts->distanceBefore = ts->distanceAfter = w.distance;
    ts->kind = out.kind;
    ts->rule = out.rule;
    ts->localMinimum = out.localMin;
}

// The distance after an update and its sign of change. Equal in exact arithmetic can differ by
// rounding: 1e-12 of the bodies' size.
void recordUpdate(LinCannyTraceStep* ts, LinCannyWalk& w, const LinCannyOutcome& out, const VClipFeature& from, double extent) {
    if (!ts) return;
    ts->updatedBody = out.body;
    ts->from = from;
    ts->to = out.to;
    const double before = w.distance;
    w.closest();
    ts->distanceAfter = w.distance;
    const double tol = 1e-12 * (extent + before);
    const double diff = ts->distanceAfter - before;
    ts->distanceChange = diff > tol ? 1 : diff < -tol ? -1 : 0;
}

// The answer when the walk stops: separated at the closest points, or penetrating.
void finalAnswer(const LinCannyWalk& w, const LinCannyOutcome& out, LinCannyResult& res) {
    const Vec3 pa = w.world(0, w.p[0]), pb = w.world(0, w.p[1]);
    if (out.kind == VClipStepKind::Done) {
        res.distance = w.distance;
        res.pointA = pa;
        res.pointB = pb;
        // From the A-frame difference: world points far from the origin lose digits.
        res.normal = w.pose[0].rotate(w.p[1] - w.p[0]) / w.distance;
        return;
    }
    res.intersect = true;
    res.penetration = out.penetration;
    if (out.penetration == LinCannyPenetration::FeaturesMeet) {
        res.pointA = res.pointB = 0.5 * (pa + pb);
    } else {
        // PointInside: the tested point was B's (A's region failed first) or A's.
        res.pointA = res.pointB = out.body == 0 ? pb : pa;
    }
}

}  // namespace

// Lin and Canny, "A fast algorithm for incremental distance calculation" (ICRA 1991), Lin's
// thesis (1993) §3: walk the pair of closest features, each step moving one feature to a
// neighbour whose Voronoi region the other body's closest point violates.
LinCannyResult linCanny(const VClipPolyhedron& a, const Transform& poseA, const VClipPolyhedron& b,
                        const Transform& poseB, LinCannyCache* cache, const LinCannyOptions& options,
                        LinCannyTrace* trace) {
    LinCannyResult res;
    if (trace) *trace = LinCannyTrace{};
    auto finish = [&](LinCannyStatus status, std::string message) {
        res.status = status;
        res.message = std::move(message);
        if (trace) trace->status = status;
        return res;
    };
    if (a.empty() || b.empty()) return finish(LinCannyStatus::InvalidInput, "lin_canny: empty polyhedron");
    if (!finitePose(poseA) || !finitePose(poseB))
        return finish(LinCannyStatus::InvalidInput, "lin_canny: non-finite pose");

    LinCannyWalk w;
    w.setup(a, poseA, b, poseB);
    // Scale: largest coordinate magnitude met in A's frame (B's bounds shifted by its offset).
    const double scale = std::max({maxAbs(a.mesh().boundsMin()), maxAbs(a.mesh().boundsMax()),
                                   maxAbs(b.mesh().boundsMin()) + maxAbs(b.mesh().boundsMax()) + maxAbs(w.T[1])});
    w.eps = options.applicability * scale;
    w.touch = options.touching * scale;
    w.insideTest = options.insideTest;
    if (cache && validFeature(a, cache->a) && validFeature(b, cache->b)) {
        w.X[0] = cache->a;
        w.X[1] = cache->b;
    }

    const long long bound = static_cast<long long>(a.featureCount()) * b.featureCount();
    const long long maxSteps = options.maxSteps > 0 ? options.maxSteps : bound;
    feature_walk::FeaturePairCycle cycle(w.X[0], w.X[1]);
    const double extent = std::max((a.mesh().boundsMax() - a.mesh().boundsMin()).norm(),
                                   (b.mesh().boundsMax() - b.mesh().boundsMin()).norm());

    for (int steps = 0;; ++steps) {
        res.steps = steps;
        res.featureA = w.X[0];
        res.featureB = w.X[1];
        if (cache) *cache = LinCannyCache{w.X[0], w.X[1]};
        if (steps >= maxSteps)
            return finish(LinCannyStatus::StepLimit, "lin_canny: step limit " + std::to_string(maxSteps) + " reached");
        LinCannyTraceStep* ts = beginTraceStep(trace, w, steps);
        w.ts = ts;
        const LinCannyOutcome out = w.step();
        recordOutcome(ts, w, out);
        if (out.kind != VClipStepKind::Update) {  // Done or Penetration
            finalAnswer(w, out, res);
            return finish(res.intersect ? LinCannyStatus::Penetrating : LinCannyStatus::Separated, "");
        }
        const VClipFeature from = w.X[out.body];
        w.X[out.body] = out.to;
        recordUpdate(ts, w, out, from, extent);
        if (options.detectCycles && cycle.repeats(w.X[0], w.X[1])) {
            res.steps = steps + 1;
            res.featureA = w.X[0];
            res.featureB = w.X[1];
            res.cycleLength = static_cast<int>(cycle.cycleLength());
            if (cache) *cache = LinCannyCache{w.X[0], w.X[1]};
            if (trace) {
                trace->cycleLength = res.cycleLength;
                trace->steps.back().kind = VClipStepKind::Aborted;
            }
            return finish(LinCannyStatus::CycleDetected, "lin_canny: cycle of " + std::to_string(cycle.cycleLength()) +
                                                             " feature pairs through " + nameOf(w.X[0]) + "/" +
                                                             nameOf(w.X[1]) + " (penetrating?)");
        }
    }
}

}  // namespace cdlab
