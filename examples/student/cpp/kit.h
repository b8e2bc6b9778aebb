// What the three C++ assignment programs share: a 3-vector, the answer each item returns, and the
// drivers that read the cases (JSON Lines on stdin, one `cdlab query` line each) and write each case
// back with your "answer" and "trace" added, the lines `cdlab check` reads. Nothing here is part
// of the assignment; kit.cpp holds the JSON (nlohmann-json), so your files need no JSON.
#pragma once

#include <string>
#include <vector>

namespace kit {

struct V3 {
    double x = 0, y = 0, z = 0;
};
inline V3 operator+(V3 p, V3 q) { return {p.x + q.x, p.y + q.y, p.z + q.z}; }
inline V3 operator-(V3 p, V3 q) { return {p.x - q.x, p.y - q.y, p.z - q.z}; }
inline V3 operator-(V3 p) { return {-p.x, -p.y, -p.z}; }
inline V3 operator*(double s, V3 p) { return {s * p.x, s * p.y, s * p.z}; }
inline double dot(V3 p, V3 q) { return p.x * q.x + p.y * q.y + p.z * q.z; }
inline V3 cross(V3 p, V3 q) { return {p.y * q.z - p.z * q.y, p.z * q.x - p.x * q.z, p.x * q.y - p.y * q.x}; }

// Item 1, closest_point_triangle: the point, its region (A, B, C, AB, BC, CA, ABC), its barycentric
// weights on a, b, c, and the region tests made in order (docs/check.md, "Voronoi-region trace").
struct RegionTest {
    std::string region;
    std::vector<std::pair<std::string, double>> terms;  // d1..d6, va, vb, vc as Ericson names them
    bool accepted = false;
};
struct TriangleAnswer {
    V3 point;
    std::string region;
    double weights[3] = {0, 0, 0};
    std::vector<RegionTest> tests;
};
int runTriangleCases(TriangleAnswer (*closestPointTriangle)(V3 p, V3 a, V3 b, V3 c));

// Item 2, distance by GJK: the answer and one step per iteration (docs/check.md, "GJK trace").
struct GjkStep {
    V3 direction, a, b;      // the search direction d; a = s_A(d), b = s_B(−d)
    std::vector<V3> simplex;  // the points of A − B kept after reducing (empty: not given)
};
struct GjkAnswer {
    bool intersect = false;
    double distance = 0;
    V3 pointA, pointB;
    std::vector<GjkStep> steps;
};
int runGjkCases(GjkAnswer (*gjk)(const std::vector<V3>& a, const std::vector<V3>& b, V3 firstDirection));

// Item 3, a polyhedron against the plane normal·x = offset: colliding (depth, normal, points) or
// separated (distance, normal, the closest pair as points[0] with depth 0).
struct ContactPoint {
    V3 pointA, pointB;
    double depth = 0;
};
struct PlaneAnswer {
    bool colliding = false;
    double depthOrDistance = 0;
    V3 normal;  // from the body toward the plane
    std::vector<ContactPoint> points;
};
int runPlaneCases(PlaneAnswer (*contact)(const std::vector<V3>& body, V3 normal, double offset));

}  // namespace kit
