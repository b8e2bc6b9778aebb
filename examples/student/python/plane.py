"""Assignment item: a convex polyhedron against a plane — the boolean test, the contact points and
the contact normal (the course's compulsory "polyhedron vs plane" by point-plane tests).

    python3 plane.py < ../cases/plane.jsonl | ../../../cdlab check

Each case is a `contact` query: a = the polyhedron (its vertices), b = the plane n·x = d, solid on
the side n points away from (the ground). You answer whether they collide; if so the depth, the
normal (from the body toward the plane: moving the plane by depth along it separates them) and up
to 4 contact points, each a point of the body with its projection on the plane and its depth; if
not, the distance and the closest pair (docs/check.md, "What is compared")."""
from kit import run, vertices

MAX_POINTS = 4


def contact(body, normal, offset):
    """body: the polyhedron's vertices; the plane normal·x = offset (normal not always unit).
    Returns the answer: colliding -> {"colliding": True, "depth", "normal", "points": [{"point_a",
    "point_b", "depth"}, ...]}; separated -> {"colliding": False, "distance", "normal", "closest":
    [{"point_a", "point_b"}]}."""
    # TODO: each vertex's signed height above the plane (normal·v − offset) / |normal|; colliding
    # when the lowest is <= 0; then the depth, the normal and up to MAX_POINTS of the vertices below
    # the plane, each with its projection on the plane. As shipped nothing collides: `cdlab check`
    # says "yours colliding = false, cdlab's true" where a body reaches the plane.
    return {"colliding": False, "distance": 1.0, "normal": (0.0, 0.0, -1.0), "closest": []}


def solve(case):
    plane = case["b"]["plane"]
    return contact(vertices(case["a"]), tuple(plane["normal"]), plane["offset"]), None


if __name__ == "__main__":
    run(solve)
