"""What the three assignment programs share: vector arithmetic on 3-tuples, reading the cases
(JSON Lines: one `cdlab query` line each) and writing each case back with your "answer" (and
"trace") added, the line `cdlab check` reads. Nothing here is part of the assignment."""
import json
import sys


def add(p, q): return (p[0] + q[0], p[1] + q[1], p[2] + q[2])
def sub(p, q): return (p[0] - q[0], p[1] - q[1], p[2] - q[2])
def scale(s, p): return (s * p[0], s * p[1], s * p[2])
def dot(p, q): return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]
def neg(p): return (-p[0], -p[1], -p[2])
def cross(p, q): return (p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0])


def vertices(shape):
    """The vertices of a case's polytope ({"polytope": {"vertices": [...]}}) as tuples."""
    return [tuple(v) for v in shape["polytope"]["vertices"]]


def run(solve):
    """Reads the cases on stdin; for each, solve(case) returns (answer, trace or None); writes the
    case with them added to stdout: `python3 gjk.py < ../cases/gjk.jsonl | ./cdlab check`."""
    for line in sys.stdin:
        if not line.strip():
            continue
        case = json.loads(line)
        answer, trace = solve(case)
        case["answer"] = answer
        if trace is not None:
            case["trace"] = trace
        print(json.dumps(case))
