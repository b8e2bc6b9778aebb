"""The reference solution of triangle.py's TODO (kept out of the handout: examples/student/README.md).
python3 triangle_solution.py < ../cases/triangle.jsonl | ../../../cdlab check   ->  all pass"""
import triangle
from kit import add, dot, run, scale, sub
from triangle import test


def closest_point_triangle(p, a, b, c):
    tests = []
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if test(tests, "A", {"d1": d1, "d2": d2}, d1 <= 0 and d2 <= 0):
        return a, "A", (1.0, 0.0, 0.0), tests
    bp = sub(p, b)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    if test(tests, "B", {"d3": d3, "d4": d4}, d3 >= 0 and d4 <= d3):
        return b, "B", (0.0, 1.0, 0.0), tests
    vc = d1 * d4 - d3 * d2
    if test(tests, "AB", {"vc": vc, "d1": d1, "d3": d3}, vc <= 0 and d1 >= 0 and d3 <= 0):
        v = d1 / (d1 - d3)
        return add(a, scale(v, ab)), "AB", (1 - v, v, 0.0), tests
    cp = sub(p, c)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    if test(tests, "C", {"d5": d5, "d6": d6}, d6 >= 0 and d5 <= d6):
        return c, "C", (0.0, 0.0, 1.0), tests
    vb = d5 * d2 - d1 * d6
    if test(tests, "AC", {"vb": vb, "d2": d2, "d6": d6}, vb <= 0 and d2 >= 0 and d6 <= 0):
        w = d2 / (d2 - d6)
        return add(a, scale(w, ac)), "CA", (1 - w, 0.0, w), tests
    va = d3 * d6 - d5 * d4
    if test(tests, "BC", {"va": va, "d3": d3, "d4": d4, "d5": d5, "d6": d6},
            va <= 0 and d4 - d3 >= 0 and d5 - d6 >= 0):
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        return add(b, scale(w, sub(c, b))), "BC", (0.0, 1 - w, w), tests
    test(tests, "ABC", {"va": va, "vb": vb, "vc": vc}, True)
    denom = 1 / (va + vb + vc)
    v, w = vb * denom, vc * denom
    return add(a, add(scale(v, ab), scale(w, ac))), "ABC", (1 - v - w, v, w), tests


triangle.closest_point_triangle = closest_point_triangle

if __name__ == "__main__":
    run(triangle.solve)
