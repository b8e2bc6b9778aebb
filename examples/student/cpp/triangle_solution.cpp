// The reference solution of triangle.cpp's TODO (kept out of the handout: examples/student/README.md).
#include "kit.h"

using kit::V3;

static bool test(kit::TriangleAnswer& r, const char* region, std::vector<std::pair<std::string, double>> terms,
                 bool accepted) {
    r.tests.push_back({region, std::move(terms), accepted});
    return accepted;
}

static kit::TriangleAnswer at(kit::TriangleAnswer r, const char* region, double u, double v, double w, V3 a, V3 b, V3 c) {
    r.region = region;
    r.weights[0] = u, r.weights[1] = v, r.weights[2] = w;
    r.point = u * a + v * b + w * c;
    return r;
}

// Also the triangle case of gjk_solution.cpp's simplex reduction.
kit::TriangleAnswer closestPointTriangle(V3 p, V3 a, V3 b, V3 c) {
    kit::TriangleAnswer r;
    const V3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (test(r, "A", {{"d1", d1}, {"d2", d2}}, d1 <= 0 && d2 <= 0)) return at(r, "A", 1, 0, 0, a, b, c);
    const V3 bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (test(r, "B", {{"d3", d3}, {"d4", d4}}, d3 >= 0 && d4 <= d3)) return at(r, "B", 0, 1, 0, a, b, c);
    const double vc = d1 * d4 - d3 * d2;
    if (test(r, "AB", {{"vc", vc}, {"d1", d1}, {"d3", d3}}, vc <= 0 && d1 >= 0 && d3 <= 0)) {
        const double v = d1 / (d1 - d3);
        return at(r, "AB", 1 - v, v, 0, a, b, c);
    }
    const V3 cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (test(r, "C", {{"d5", d5}, {"d6", d6}}, d6 >= 0 && d5 <= d6)) return at(r, "C", 0, 0, 1, a, b, c);
    const double vb = d5 * d2 - d1 * d6;
    if (test(r, "AC", {{"vb", vb}, {"d2", d2}, {"d6", d6}}, vb <= 0 && d2 >= 0 && d6 <= 0)) {
        const double w = d2 / (d2 - d6);
        return at(r, "CA", 1 - w, 0, w, a, b, c);
    }
    const double va = d3 * d6 - d5 * d4;
    if (test(r, "BC", {{"va", va}, {"d3", d3}, {"d4", d4}, {"d5", d5}, {"d6", d6}},
             va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return at(r, "BC", 0, 1 - w, w, a, b, c);
    }
    test(r, "ABC", {{"va", va}, {"vb", vb}, {"vc", vc}}, true);
    const double denom = 1 / (va + vb + vc), v = vb * denom, w = vc * denom;
    return at(r, "ABC", 1 - v - w, v, w, a, b, c);
}

#ifndef KIT_NO_MAIN
int main() { return kit::runTriangleCases(closestPointTriangle); }
#endif
