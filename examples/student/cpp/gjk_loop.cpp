// GJK's loop (given): the search direction, the supports, the simplex reduction (gjk.cpp) and the
// stopping rule, each iteration traced for `cdlab check`. Build (examples/student/README.md), then
//   ./gjk < ../cases/gjk.jsonl | ../../../cdlab check
#include <cmath>

#include "gjk.h"

using kit::V3;

static kit::GjkAnswer gjk(const std::vector<V3>& shapeA, const std::vector<V3>& shapeB, V3 direction) {
    kit::GjkAnswer r;
    std::vector<SimplexPoint> simplex;
    std::vector<double> weights;
    V3 v, d = direction;
    for (int k = 0; k < 64; ++k) {
        const V3 a = support(shapeA, d), b = support(shapeB, -d), w = a - b;
        r.steps.push_back({d, a, b, {}});
        // No progress along −v: v is the point of A − B nearest the origin (the step keeps no simplex).
        if (k > 0 && dot(v, v) - dot(v, w) <= 1e-12 * dot(v, v)) break;
        simplex.push_back({w, a, b});
        reduce(simplex, weights);
        v = V3{};
        for (std::size_t i = 0; i < simplex.size(); ++i) {
            r.steps.back().simplex.push_back(simplex[i].w);
            v = v + weights[i] * simplex[i].w;
        }
        if (simplex.size() == 4 || dot(v, v) == 0) {  // the origin is in A − B
            r.intersect = true;
            return r;
        }
        d = -v;
    }
    for (std::size_t i = 0; i < simplex.size(); ++i) {
        r.pointA = r.pointA + weights[i] * simplex[i].a;
        r.pointB = r.pointB + weights[i] * simplex[i].b;
    }
    r.distance = std::sqrt(dot(v, v));
    return r;
}

int main() { return kit::runGjkCases(gjk); }
