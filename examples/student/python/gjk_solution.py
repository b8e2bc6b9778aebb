"""The reference solution of gjk.py's TODOs (kept out of the handout: examples/student/README.md).
python3 gjk_solution.py < ../cases/gjk.jsonl | ../../../cdlab check   ->  all pass"""
import gjk
import triangle_solution  # noqa: F401  (fills in triangle.closest_point_triangle)
from kit import add, cross, dot, neg, run, scale, sub
from triangle import closest_point_triangle

ORIGIN = (0.0, 0.0, 0.0)


def support(points, d):
    return max(points, key=lambda v: dot(v, d))


def reduce_segment(s):
    (p, q) = (s[0][0], s[1][0])
    pq = sub(q, p)
    t = -dot(p, pq) / dot(pq, pq) if dot(pq, pq) > 0 else 0.0
    if t <= 0:
        return [s[0]], [1.0]
    if t >= 1:
        return [s[1]], [1.0]
    return s, [1 - t, t]


def reduce_triangle(s):
    _, region, bary, _ = closest_point_triangle(ORIGIN, s[0][0], s[1][0], s[2][0])
    kept = [(entry, t) for entry, t in zip(s, bary) if t > 0]
    return [e for e, _ in kept], [t for _, t in kept]


def reduce_tetrahedron(s):
    """The origin outside a face's plane (on the side away from the fourth point): that face's
    nearest point is a candidate; inside every face plane, the origin is in the tetrahedron."""
    best = None
    for i in range(4):
        face = [s[j] for j in range(4) if j != i]
        a, b, c = (e[0] for e in face)
        n = cross(sub(b, a), sub(c, a))
        if dot(n, neg(a)) * dot(n, sub(s[i][0], a)) < 0:
            kept, weights = reduce_triangle(face)
            v = (0.0, 0.0, 0.0)
            for e, t in zip(kept, weights):
                v = add(v, scale(t, e[0]))
            if best is None or dot(v, v) < best[0]:
                best = (dot(v, v), kept, weights)
    if best is None:
        return s, [0.25] * 4
    return best[1], best[2]


def reduce(simplex):
    return [lambda s: (s, [1.0]), reduce_segment, reduce_triangle, reduce_tetrahedron][len(simplex) - 1](simplex)


gjk.support, gjk.reduce = support, reduce

if __name__ == "__main__":
    run(gjk.solve)
