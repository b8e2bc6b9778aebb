// The kinds of candidate axis of a separating axis test, shared by the primitive SAT tests
// (core/overlap/sat_tests.h) and the SAT contact generators (core/contact/contact_sat.h).
#pragma once

namespace cdlab {

enum class SatAxisKind {
    FaceA,     ///< a face normal of A (for a box: axis indexA)
    FaceB,     ///< a face normal of B
    EdgeEdge,  ///< the cross product of an edge (direction) of A and one of B
    Normal,    ///< a triangle's normal (triangle-AABB only)
};

}  // namespace cdlab
