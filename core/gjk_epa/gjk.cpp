#include "core/gjk_epa/gjk.h"

#include <algorithm>
#include <utility>

namespace cdlab {

const char* nameOf(GjkStatus status) {
    switch (status) {
        case GjkStatus::Separated: return "Separated";
        case GjkStatus::Intersecting: return "Intersecting";
        case GjkStatus::InvalidInput: return "InvalidInput";
    }
    return "?";
}

const char* nameOf(GjkTermination termination) {
    switch (termination) {
        case GjkTermination::Converged: return "Converged";
        case GjkTermination::DuplicateSupport: return "DuplicateSupport";
        case GjkTermination::NoProgress: return "NoProgress";
        case GjkTermination::OriginInSimplex: return "OriginInSimplex";
        case GjkTermination::SeparatingAxis: return "SeparatingAxis";
        case GjkTermination::MaxIterations: return "MaxIterations";
        case GjkTermination::InvalidInput: return "InvalidInput";
        case GjkTermination::EdgePairCrossed: return "EdgePairCrossed";
    }
    return "?";
}

// Letter i names slot i (A..D = w0..w3, the names the figures use); they name slots, not bodies.
std::string slotLetters(std::uint8_t slots) {
    std::string letters;
    for (int i = 0; i < 4; ++i)
        if (slots & (1u << i)) letters += static_cast<char>('A' + i);
    return letters;
}

namespace detail {

void gjkWitness(const GjkSimplex& s, Vec3& pointA, Vec3& pointB) {
    if (s.count == 0) {
        pointA.setZero();
        pointB.setZero();
        return;
    }
    // pointA = sum lambda_i a_i = a_0 + sum_{i>0} lambda_i (a_i - a_0): the differences are small
    // when the shape is small, so a 1e6 offset only enters once, exactly.
    const GjkVertex& v0 = s.vertex[0];
    Vec3 da = Vec3::Zero();
    Vec3 db = Vec3::Zero();
    for (int i = 1; i < s.count; ++i) {
        da += s.lambda[i] * (s.vertex[i].a - v0.a);
        db += s.lambda[i] * (s.vertex[i].b - v0.b);
    }
    pointA = v0.a + da;
    pointB = v0.b + db;
}

void GjkRecorder::beginStep(int iteration, const Vec3& v, const GjkVertex& support, double lowerBound,
                            double upperBound, double gapTest, const GjkSimplex& s) {
    if (!trace_) return;
    step_ = &trace_->steps.emplace_back();
    step_->iteration = iteration;
    step_->direction = -v;
    step_->support = support;
    step_->lowerBound = lowerBound;
    step_->upperBound = upperBound;
    step_->gapTest = gapTest;
    step_->simplexCount = s.count;
    for (int i = 0; i < s.count; ++i) step_->simplex[i] = s.vertex[i];
    step_->v = v;
    step_->keptSlots = static_cast<std::uint8_t>((1u << s.count) - 1u);
    for (int i = 0; i < s.count; ++i) step_->lambda[i] = s.lambda[i];
    gjkWitness(s, step_->pointA, step_->pointB);
}

void GjkRecorder::candidate(const GjkSimplex& s, int n) {
    if (!step_) return;
    step_->simplexCount = n;
    for (int i = 0; i < n; ++i) step_->simplex[i] = s.vertex[i];
}

void GjkRecorder::reduction(const SimplexClosest& c, const GjkSimplex& reduced) {
    if (!step_) return;
    step_->keptSlots = 0;
    for (int k = 0; k < c.count; ++k) step_->keptSlots |= static_cast<std::uint8_t>(1u << c.index[k]);
    for (int k = 0; k < 4; ++k) step_->lambda[k] = k < c.count ? c.lambda[k] : 0.0;
    step_->v = c.v;
    gjkWitness(reduced, step_->pointA, step_->pointB);
}

void GjkRecorder::stepEndsLoop() {
    if (step_) step_->terminated = true;
}

void GjkRecorder::termination(GjkTermination why) {
    if (trace_) trace_->termination = why;
}

bool gjkNeedsEdgePairs(const GjkSimplex& s, const GjkResult& r) {
    // Uncertified: the lower bound is not within kGjkCertifiedGap of |v|.
    if (!(r.lowerBound >= (1.0 - kGjkCertifiedGap) * r.distance)) return true;
    if (s.count != 3) return false;
    // Sliver: the normal's rounding error is above 1e3 u.
    const Vec3 e1 = s.vertex[1].w - s.vertex[0].w, e2 = s.vertex[2].w - s.vertex[0].w;
    return isSliver(e1, e2);
}

int gjkSimplexShapePoints(const GjkSimplex& s, Vec3* a, int& na, Vec3* b, int& nb) {
    na = nb = 0;
    for (int i = 0; i < s.count; ++i) {
        if (std::find(a, a + na, s.vertex[i].a) == a + na) a[na++] = s.vertex[i].a;
        if (std::find(b, b + nb, s.vertex[i].b) == b + nb) b[nb++] = s.vertex[i].b;
    }
    return na + nb;
}

int gjkEdgePairCandidates(const GjkSimplex& s, EdgePairDistance* out) {
    Vec3 a[4], b[4];
    int na = 0, nb = 0;
    gjkSimplexShapePoints(s, a, na, b, nb);
    int n = 0;
    for (int i = 0; i < na; ++i)
        for (int j = i + 1; j < na; ++j)
            for (int k = 0; k < nb; ++k)
                for (int l = k + 1; l < nb; ++l) {
                    const EdgePairDistance e = edgePairDistance(a[i], a[j], b[k], b[l]);
                    if (e.ok) out[n++] = e;
                }
    // Vertex-face: a point of one shape against a (sliver) triangle of the other.
    if (na == 1 && nb == 3) {
        const EdgePairDistance e = pointTriangleDistance(a[0], b[0], b[1], b[2]);
        if (e.ok) out[n++] = e;
    }
    if (na == 3 && nb == 1) {
        EdgePairDistance e = pointTriangleDistance(b[0], a[0], a[1], a[2]);
        if (e.ok) {
            std::swap(e.pointA, e.pointB);
            e.axis = -e.axis;
            out[n++] = e;
        }
    }
    std::sort(out, out + n,
              [](const EdgePairDistance& x, const EdgePairDistance& y) { return x.distance < y.distance; });
    return n;
}

}  // namespace detail

}  // namespace cdlab
