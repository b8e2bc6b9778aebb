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

double mag(const Vec3& v) { return v.cwiseAbs().maxCoeff(); }

std::uint64_t pairKey(const VClipFeature& a, const VClipFeature& b) {
    const auto code = [](const VClipFeature& f) {
        return (static_cast<std::uint64_t>(f.type) << 30) | static_cast<std::uint64_t>(static_cast<std::uint32_t>(f.index));
    };
    return (code(a) << 32) | code(b);
}

bool validFeature(const VClipPolyhedron& p, const VClipFeature& f) {
    const ConvexPolyhedron& m = p.mesh();
    switch (f.type) {
        case FT::Vertex: return f.index >= 0 && f.index < m.vertexCount();
        case FT::Edge: return f.index >= 0 && f.index < m.edgeCount();
        case FT::Face: return f.index >= 0 && f.index < m.faceCount();
        case FT::None: break;
    }
    return false;
}

bool finitePose(const Transform& t) {
    return t.position.allFinite() && t.rotation.coeffs().allFinite() && t.rotation.norm() > 0.0;
}

ContactType pairType(const VClipFeature& a, const VClipFeature& b) {
    const int lo = std::min(a.dimension(), b.dimension()), hi = std::max(a.dimension(), b.dimension());
    if (lo == 0) return hi == 0 ? ContactType::VV : hi == 1 ? ContactType::VE : ContactType::VF;
    if (lo == 1) return hi == 1 ? ContactType::EE : ContactType::EF;
    return ContactType::FF;
}

/// What one step decided.
struct Outcome {
    VClipStepKind kind = VClipStepKind::Done;
    int body = -1;
    VClipFeature to;
    bool localMin = false;
    LinCannyPenetration penetration = LinCannyPenetration::None;
    std::string rule;
};

struct Walk {
    const VClipPolyhedron* P[2];
    const ConvexPolyhedron* M[2];
    Transform pose[2];
    Mat3 R[2];  // R[i], T[i]: body i frame -> frame of body 1 - i
    Vec3 T[2];
    VClipFeature X[2];
    double eps = 0.0;    // applicability slack, absolute (options.applicability * scale)
    double touch = 0.0;  // touching distance, absolute
    bool insideTest = false;
    LinCannyTraceStep* ts = nullptr;
    std::vector<Vec3> polyA, polyB;  // scratch: face polygons in A's frame

    // Closest points of the pair, A's frame: p[0] on X[0], p[1] on X[1].
    Vec3 p[2];
    double distance = 0.0;

    Vec3 toFrame(int from, const Vec3& x) const { return R[from] * x + T[from]; }
    // Body-i point in A's frame.
    Vec3 inA(int i, const Vec3& x) const { return i == 0 ? x : toFrame(1, x); }
    Vec3 world(int i, const Vec3& x) const { return pose[i].apply(x); }
    const Vec3& pos(int i, int v) const { return M[i]->position(v); }

    void polygon(int i, int f, std::vector<Vec3>& out) const {
        out.clear();
        M[i]->forEachFaceHalfEdge(f, [&](int h) { out.push_back(inA(i, pos(i, M[i]->halfEdge(h).origin))); });
    }
    Segment segment(int i, int e) const { return {inA(i, pos(i, P[i]->edgeTail(e))), inA(i, pos(i, P[i]->edgeHead(e)))}; }

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
            const Vec3 on = pl.other.type == FT::Vertex ? pos(r, pl.other.index) : pos(r, P[r]->edgeTail(pl.edge.index));
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
                if (t.regionBody == ts->planes.back().regionBody && t.violated && (!best || t.signedDistance < best->signedDistance))
                    best = &t;
            if (best) best->maximal = true;
        }
    }

    // --- 2./3./4. applicability test of point x (frame of body r) against VR(X[r]) ----------
    // Returns true and fills `out` when a plane is violated by more than eps.
    bool applicability(int r, const Vec3& x, Outcome& out) {
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
        const char* point = r == 0 ? "pB" : "pA";
        if (worst >= 0) {
            const VClipPlane& pl = poly.plane(worst);
            out.kind = VClipStepKind::Update;
            out.body = r;
            out.to = owner.type == FT::Edge ? pl.other : pl.edge;
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
            out.rule = std::string("local minimum: ") + point + " behind " + nameOf(owner) + ", farthest in front of F" +
                       std::to_string(bestFace);
            return true;
        }
        out.kind = VClipStepKind::Penetration;
        out.body = r;
        out.penetration = LinCannyPenetration::PointInside;
        out.rule = std::string(point) + " behind every face plane of " + (r == 0 ? "A" : "B");
        return true;
    }

    Outcome step() {
        Outcome out;
        closest();
        if (distance <= touch) {
            out.kind = VClipStepKind::Penetration;
            out.penetration = LinCannyPenetration::FeaturesMeet;
            out.rule = "features meet";
            return out;
        }
        if (applicability(0, p[1], out)) return out;
        if (applicability(1, toFrame(0, p[0]), out)) return out;
        out.kind = VClipStepKind::Done;
        out.rule = "pA in VR(XB) and pB in VR(XA)";
        return out;
    }
};

}  // namespace

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
    if (!finitePose(poseA) || !finitePose(poseB)) return finish(LinCannyStatus::InvalidInput, "lin_canny: non-finite pose");

    Walk w;
    w.P[0] = &a;
    w.P[1] = &b;
    w.M[0] = &a.mesh();
    w.M[1] = &b.mesh();
    w.pose[0] = poseA;
    w.pose[1] = poseB;
    w.pose[0].rotation.normalize();
    w.pose[1].rotation.normalize();
    const Mat3 ra = w.pose[0].rotation.toRotationMatrix(), rb = w.pose[1].rotation.toRotationMatrix();
    // B -> A: x_A = RA^T (RB x_B + pB - pA); A -> B is its inverse.
    w.R[1] = ra.transpose() * rb;
    w.T[1] = ra.transpose() * (w.pose[1].position - w.pose[0].position);
    w.R[0] = w.R[1].transpose();
    w.T[0] = -(w.R[0] * w.T[1]);
    // Scale: largest coordinate magnitude met in A's frame (B's bounds shifted by its offset).
    const double scale = std::max({mag(a.mesh().boundsMin()), mag(a.mesh().boundsMax()),
                                   mag(b.mesh().boundsMin()) + mag(b.mesh().boundsMax()) + mag(w.T[1])});
    w.eps = options.applicability * scale;
    w.touch = options.touching * scale;
    w.insideTest = options.insideTest;

    w.X[0] = VClipFeature::vertex(0);
    w.X[1] = VClipFeature::vertex(0);
    if (cache && validFeature(a, cache->a) && validFeature(b, cache->b)) {
        w.X[0] = cache->a;
        w.X[1] = cache->b;
    }

    const long long bound = static_cast<long long>(a.featureCount()) * b.featureCount();
    const long long maxSteps = options.maxSteps > 0 ? options.maxSteps : bound;
    // Brent's cycle detection: `tortoise` is the pair at the last power-of-two checkpoint.
    std::uint64_t tortoise = pairKey(w.X[0], w.X[1]);
    long long power = 1, lambda = 0;
    const double extent = std::max((a.mesh().boundsMax() - a.mesh().boundsMin()).norm(),
                                   (b.mesh().boundsMax() - b.mesh().boundsMin()).norm());

    for (int steps = 0;; ++steps) {
        res.steps = steps;
        res.featureA = w.X[0];
        res.featureB = w.X[1];
        if (cache) *cache = LinCannyCache{w.X[0], w.X[1]};
        if (steps >= maxSteps)
            return finish(LinCannyStatus::StepLimit, "lin_canny: step limit " + std::to_string(maxSteps) + " reached");
        LinCannyTraceStep* ts = nullptr;
        if (trace) {
            trace->steps.emplace_back();
            ts = &trace->steps.back();
            ts->step = steps;
            ts->state = pairType(w.X[0], w.X[1]);
            ts->featureA = w.X[0];
            ts->featureB = w.X[1];
            ts->featureAWorld = featureGeometry(a, w.pose[0], w.X[0]);
            ts->featureBWorld = featureGeometry(b, w.pose[1], w.X[1]);
        }
        w.ts = ts;
        const Outcome out = w.step();
        if (ts) {
            ts->closestA = w.world(0, w.p[0]);
            ts->closestB = w.world(0, w.p[1]);
            ts->distanceBefore = ts->distanceAfter = w.distance;
            ts->kind = out.kind;
            ts->rule = out.rule;
            ts->localMinimum = out.localMin;
        }
        if (out.kind == VClipStepKind::Update) {
            if (ts) {
                ts->updatedBody = out.body;
                ts->from = w.X[out.body];
                ts->to = out.to;
            }
            w.X[out.body] = out.to;
            if (ts) {
                const double before = w.distance;
                w.closest();
                ts->distanceAfter = w.distance;
                // Equal in exact arithmetic can differ by rounding: 1e-12 of the bodies' size.
                const double tol = 1e-12 * (extent + before);
                const double diff = ts->distanceAfter - before;
                ts->distanceChange = diff > tol ? 1 : diff < -tol ? -1 : 0;
            }
            if (options.detectCycles) {
                ++lambda;
                const std::uint64_t key = pairKey(w.X[0], w.X[1]);
                if (key == tortoise) {
                    res.steps = steps + 1;
                    res.featureA = w.X[0];
                    res.featureB = w.X[1];
                    res.cycleLength = static_cast<int>(lambda);
                    if (cache) *cache = LinCannyCache{w.X[0], w.X[1]};
                    if (trace) {
                        trace->cycleLength = res.cycleLength;
                        trace->steps.back().kind = VClipStepKind::Aborted;
                    }
                    return finish(LinCannyStatus::CycleDetected,
                                  "lin_canny: cycle of " + std::to_string(lambda) + " feature pairs through " +
                                      nameOf(w.X[0]) + "/" + nameOf(w.X[1]) + " (penetrating?)");
                }
                if (lambda == power) {
                    tortoise = key;
                    power *= 2;
                    lambda = 0;
                }
            }
            continue;
        }
        // Done or Penetration.
        const Vec3 pa = w.world(0, w.p[0]), pb = w.world(0, w.p[1]);
        if (out.kind == VClipStepKind::Done) {
            res.distance = w.distance;
            res.pointA = pa;
            res.pointB = pb;
            // From the A-frame difference: world points far from the origin lose digits.
            res.normal = w.pose[0].rotate(w.p[1] - w.p[0]) / w.distance;
            return finish(LinCannyStatus::Separated, "");
        }
        res.intersect = true;
        res.penetration = out.penetration;
        if (out.penetration == LinCannyPenetration::FeaturesMeet) {
            res.pointA = res.pointB = 0.5 * (pa + pb);
        } else {
            // PointInside: the tested point was B's (A's region failed first) or A's.
            res.pointA = res.pointB = out.body == 0 ? pb : pa;
        }
        return finish(LinCannyStatus::Penetrating, "");
    }
}

}  // namespace cdlab
