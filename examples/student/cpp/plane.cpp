// Assignment item: a convex polyhedron against a plane — the boolean test, the contact points and
// the contact normal (the course's compulsory "polyhedron vs plane" by point-plane tests). Build
// (examples/student/README.md), then
//   ./plane < ../cases/plane.jsonl | ../../../cdlab check
// Each case is a `contact` query: a = the polyhedron, b = the plane normal·x = offset, solid on the
// side the normal points away from (the ground).
#include "kit.h"

using kit::V3;

constexpr std::size_t kMaxPoints = 4;

// Colliding: depth, the normal from the body toward the plane (moving the plane by depth along it
// separates them) and up to kMaxPoints contact points, each a vertex below the plane with its
// projection on it and its depth. Separated: the distance, the normal and the closest pair.
kit::PlaneAnswer contact(const std::vector<V3>& body, V3 normal, double offset) {
    // TODO: each vertex's signed height above the plane (normal·v − offset) / |normal|; colliding
    // when the lowest is <= 0; then the answer above. As shipped nothing collides: `cdlab check`
    // says "yours colliding = false, cdlab's true" where a body reaches the plane.
    (void)body, (void)offset;
    return {false, 1.0, -1.0 * normal, {}};
}

int main() { return kit::runPlaneCases(contact); }
