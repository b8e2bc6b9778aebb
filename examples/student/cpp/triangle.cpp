// Assignment item: the point of a triangle nearest a point p, and the Voronoi region it lies in
// (Ericson, Real-Time Collision Detection §5.1.5). Build (examples/student/README.md), then
//   ./triangle < ../cases/triangle.jsonl | ../../../cdlab check
// `cdlab check` names the first region test that went wrong (docs/check.md, "Voronoi-region trace").
#include "kit.h"

using kit::V3;

// Records one region test (its terms by Ericson's names) and returns its decision.
static bool test(kit::TriangleAnswer& r, const char* region, std::vector<std::pair<std::string, double>> terms,
                 bool accepted) {
    r.tests.push_back({region, std::move(terms), accepted});
    return accepted;
}

kit::TriangleAnswer closestPointTriangle(V3 p, V3 a, V3 b, V3 c) {
    kit::TriangleAnswer r;
    const V3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (test(r, "A", {{"d1", d1}, {"d2", d2}}, d1 <= 0 && d2 <= 0)) return r.point = a, r.region = "A", r.weights[0] = 1, r;
    // TODO: the regions of vertex B, edge AB, vertex C, edge AC and edge BC, in that order, each
    // recorded with test() as vertex A's is above (terms d3..d6 and va, vb, vc, named as Ericson
    // names them). `cdlab check` says "test 1 (ABC): accepted, but the point lies outside this
    // region" until they are here.
    test(r, "ABC", {}, true);
    const V3 n = cross(ab, ac);
    r.point = p - (dot(ap, n) / dot(n, n)) * n;
    r.region = "ABC";
    r.weights[0] = r.weights[1] = r.weights[2] = 1.0 / 3;
    return r;
}

int main() { return kit::runTriangleCases(closestPointTriangle); }
