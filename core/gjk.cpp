#include "core/gjk.h"

namespace cdlab {

const char* statusName(GjkStatus status)
{
    switch (status) {
        case GjkStatus::Separated: return "Separated";
        case GjkStatus::Intersecting: return "Intersecting";
        case GjkStatus::InvalidInput: return "InvalidInput";
    }
    return "?";
}

const char* terminationName(GjkTermination termination)
{
    switch (termination) {
        case GjkTermination::Converged: return "Converged";
        case GjkTermination::DuplicateSupport: return "DuplicateSupport";
        case GjkTermination::NoProgress: return "NoProgress";
        case GjkTermination::OriginInSimplex: return "OriginInSimplex";
        case GjkTermination::SeparatingAxis: return "SeparatingAxis";
        case GjkTermination::MaxIterations: return "MaxIterations";
        case GjkTermination::InvalidInput: return "InvalidInput";
    }
    return "?";
}

namespace detail {

void gjkWitness(const GjkSimplex& s, Vec3& pointA, Vec3& pointB)
{
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

void gjkReduce(const GjkVertex* in, const SimplexClosest& c, GjkSimplex& out)
{
    out.count = c.count;
    for (int k = 0; k < c.count; ++k) {
        out.vertex[k] = in[c.index[k]];
        out.lambda[k] = c.lambda[k];
    }
}

void gjkTraceReduction(GjkTraceStep& step, const SimplexClosest& c, const GjkSimplex& reduced)
{
    char name[5];
    simplexRegionName(c, name);
    step.region = name;
    for (int k = 0; k < 4; ++k) step.lambda[k] = k < c.count ? c.lambda[k] : 0.0;
    step.v = c.v;
    gjkWitness(reduced, step.pointA, step.pointB);
}

}  // namespace detail

}  // namespace cdlab
