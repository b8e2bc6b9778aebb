"""Assignment item: the distance of two convex polyhedra by GJK, with its trace (Gilbert, Johnson,
Keerthi; the course's "GJK" and "point vs simplex").

    python3 gjk.py < ../cases/gjk.jsonl | ../../../cdlab check

Each case is a `distance` query of two polytopes; you answer {"intersect", "distance", "point_a",
"point_b"} and trace every iteration (its search direction d, the support points a of A and b of B,
the simplex kept), so that `cdlab check` names the first iteration that breaks a rule of GJK and
which part broke it (docs/check.md, "GJK trace schema")."""
import math

from kit import add, dot, neg, run, scale, sub, vertices

MAX_ITERATIONS = 64


def support(points, d):
    """The point of the polytope (its vertices) farthest along d."""
    # TODO: the vertex with the largest dot(v, d). As shipped it returns the first vertex:
    # `cdlab check` says "your a is not extreme in A" (or b in B) at the first iteration where that is wrong.
    return points[0]


def reduce(simplex):
    """simplex: 1 to 4 entries (w, a, b), w = a - b, the newest last. Returns (kept, weights): the
    smallest sub-simplex whose hull holds the point of the simplex nearest the origin (the feature
    whose Voronoi region holds the origin), and that point's barycentric weights on the kept
    entries (each > 0, summing to 1). A tetrahedron holding the origin is kept whole."""
    # TODO: the closest point of a segment, triangle (triangle.py) and tetrahedron to the origin,
    # by Voronoi regions. As shipped it keeps the newest point alone: `cdlab check` says "wrong
    # sub-simplex kept: the origin is in the Voronoi region of ... keep ..." where that is wrong.
    return [simplex[-1]], [1.0]


def gjk(A, B, direction):
    """GJK distance of conv(A) and conv(B) from the first search direction; returns (answer, steps)."""
    simplex, steps, v, d = [], [], None, direction
    for _ in range(MAX_ITERATIONS):
        a, b = support(A, d), support(B, neg(d))
        w = sub(a, b)
        step = {"direction": d, "support": {"a": a, "b": b}}
        steps.append(step)
        # No progress along -v: v is the point of A - B nearest the origin (the step keeps no simplex).
        if v is not None and dot(v, v) - dot(v, w) <= 1e-12 * dot(v, v):
            break
        simplex, weights = reduce(simplex + [(w, a, b)])
        step["simplex"] = [s[0] for s in simplex]
        v = (0.0, 0.0, 0.0)
        for (p, _, _), t in zip(simplex, weights):
            v = add(v, scale(t, p))
        if len(simplex) == 4 or dot(v, v) == 0:  # the origin is in A - B
            return {"intersect": True, "distance": 0}, steps
        d = neg(v)
    point_a, point_b = (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    for (_, pa, pb), t in zip(simplex, weights):
        point_a, point_b = add(point_a, scale(t, pa)), add(point_b, scale(t, pb))
    return {"intersect": False, "distance": math.sqrt(dot(v, v)), "point_a": point_a, "point_b": point_b}, steps


def solve(case):
    answer, steps = gjk(vertices(case["a"]), vertices(case["b"]), tuple(case.get("initial_direction", (1, 0, 0))))
    return answer, {"algorithm": "gjk", "steps": steps}


if __name__ == "__main__":
    run(solve)
