// The reference solution of gjk.cpp's TODOs (kept out of the handout: examples/student/README.md).
// The triangle case is triangle_solution.cpp's closestPointTriangle.
#include <algorithm>

#include "gjk.h"

using kit::V3;

kit::TriangleAnswer closestPointTriangle(V3 p, V3 a, V3 b, V3 c);

V3 support(const std::vector<V3>& vertices, V3 d) {
    return *std::max_element(vertices.begin(), vertices.end(), [&](V3 p, V3 q) { return dot(p, d) < dot(q, d); });
}

static void reduceSegment(std::vector<SimplexPoint>& s, std::vector<double>& weights) {
    const V3 pq = s[1].w - s[0].w;
    const double t = dot(pq, pq) > 0 ? -dot(s[0].w, pq) / dot(pq, pq) : 0;
    if (t <= 0) s = {s[0]}, weights = {1.0};
    else if (t >= 1) s = {s[1]}, weights = {1.0};
    else weights = {1 - t, t};
}

static void reduceTriangle(std::vector<SimplexPoint>& s, std::vector<double>& weights) {
    const kit::TriangleAnswer r = closestPointTriangle(V3{}, s[0].w, s[1].w, s[2].w);
    std::vector<SimplexPoint> kept;
    weights.clear();
    for (int i = 0; i < 3; ++i)
        if (r.weights[i] > 0) kept.push_back(s[i]), weights.push_back(r.weights[i]);
    s = kept;
}

// The origin outside a face's plane (on the side away from the fourth point): that face's nearest
// point is a candidate; inside every face plane, the origin is in the tetrahedron.
static void reduceTetrahedron(std::vector<SimplexPoint>& s, std::vector<double>& weights) {
    double best = -1;
    std::vector<SimplexPoint> bestKept;
    std::vector<double> bestWeights;
    for (int i = 0; i < 4; ++i) {
        std::vector<SimplexPoint> face;
        for (int j = 0; j < 4; ++j)
            if (j != i) face.push_back(s[j]);
        const V3 n = cross(face[1].w - face[0].w, face[2].w - face[0].w);
        if (dot(n, -face[0].w) * dot(n, s[i].w - face[0].w) >= 0) continue;
        std::vector<double> w;
        reduceTriangle(face, w);
        V3 v;
        for (std::size_t k = 0; k < face.size(); ++k) v = v + w[k] * face[k].w;
        if (best < 0 || dot(v, v) < best) best = dot(v, v), bestKept = face, bestWeights = w;
    }
    if (best < 0) weights = {0.25, 0.25, 0.25, 0.25};
    else s = bestKept, weights = bestWeights;
}

void reduce(std::vector<SimplexPoint>& simplex, std::vector<double>& weights) {
    switch (simplex.size()) {
        case 1: weights = {1.0}; break;
        case 2: reduceSegment(simplex, weights); break;
        case 3: reduceTriangle(simplex, weights); break;
        default: reduceTetrahedron(simplex, weights); break;
    }
}
