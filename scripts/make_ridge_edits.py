#!/usr/bin/env python3
"""Writes the hierarchical-edits side-car of the README's edit example: a raised
ridge along spot's back (tests/data/spot-ridge-edits.json, from tests/data/spot.obj).

    scripts/make_ridge_edits.py tests/data/spot.obj tests/data/spot-ridge-edits.json

Deterministic (plain Python floats, values printed to 1e-5), so
rerunning it reproduces the committed file byte for byte.

The ridge: every vertex of subdivision level LEVEL on the top of the back (the
symmetry plane x = 0, from the neck to the tail, where the surface faces up) gets
one `add` edit along the surface normal. Its height is HEIGHT of the bounding-box
diagonal on the spine, falling to 0 across the half-width WIDTH, (1 - (x/w)^2)^2,
and towards both ends (a smoothstep over the first and last TAPER of the length).

Every edit naming a vertex applies (docs/hierarchical-edits.md, section 1), so each
distinct level-k vertex is edited through exactly one path. Vertices are identified
on the lattice of their base triangle (corners at (0,0), (N,0), (0,N), N = 2^k;
point (i, j) = c0 + i/N (c1 - c0) + j/N (c2 - c0)) and named canonically:

    base vertex                  ("v", index)
    on base edge a-b (a < b)     ("e", a, b, steps from a)
    inside base face f           ("f", f, i, j)

The walk visits the 4^k sub-triangles of each base face in Loop child order
(child i keeps corner i; child 3 = (e1, e2, e0), e_i = midpoint of edge i -> i+1):

        C                  corners of a sub-triangle (A, B, C), its edge points
       / \                 e0 = AB/2, e1 = BC/2, e2 = CA/2:
     e2---e1                 child 0 (A, e0, e2)   child 1 (e0, B, e1)
     / \ 3 / \               child 2 (e2, e1, C)   child 3 (e1, e2, e0)
    A---e0----B

and the first (face, path, corner) reaching a ridge vertex names it. Positions and
normals are the base triangle's (barycentric interpolation of its corners and of
the mesh's area-weighted vertex normals): good enough to say where the ridge is;
the edits themselves move the subdivided points.
"""
import math
import sys

LEVEL = 3             # the edits' subdivision level
HEIGHT = 0.025        # ridge height on the spine, fraction of the bounding-box diagonal
WIDTH = 0.07          # half-width of the ridge across the spine (object units, |x|)
Z0, Z1 = 0.15, 0.95   # the ridge runs along z from the neck (Z0) to the tail (Z1)
TAPER = 0.2           # fraction of the length over which each end rises to full height
MIN_UP = 0.3          # only where the (interpolated) normal's y is at least this


def read_obj(path):
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                verts.append(tuple(float(x) for x in p[1:4]))
            elif p[0] == "f":
                idx = [int(c.split("/")[0]) - 1 for c in p[1:]]
                if len(idx) != 3:
                    sys.exit(f"{path}: face {len(faces)} is not a triangle")
                faces.append(tuple(idx))
    return verts, faces


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
    return (a[0] / n, a[1] / n, a[2] / n) if n > 0 else (0.0, 0.0, 0.0)


def vertex_normals(verts, faces):
    acc = [[0.0, 0.0, 0.0] for _ in verts]
    for a, b, c in faces:
        n = cross(sub(verts[b], verts[a]), sub(verts[c], verts[a]))  # length = 2 x area
        for v in (a, b, c):
            for d in range(3):
                acc[v][d] += n[d]
    return [normalize(n) for n in acc]


def smoothstep(t):
    t = min(1.0, max(0.0, t))
    return t * t * (3 - 2 * t)


def ridge_height(p, n, diag):
    """The edit's length along the normal at base-surface point p with normal n."""
    x, _, z = p
    if n[1] < MIN_UP or abs(x) >= WIDTH or not (Z0 < z < Z1):
        return 0.0
    t = (z - Z0) / (Z1 - Z0)
    along = smoothstep(t / TAPER) * smoothstep((1 - t) / TAPER)
    across = (1 - (x / WIDTH) ** 2) ** 2
    return HEIGHT * diag * along * across


def lattice_key(face, corners, i, j, n):
    c0, c1, c2 = corners
    if i == 0 and j == 0:
        return ("v", c0)
    if i == n and j == 0:
        return ("v", c1)
    if i == 0 and j == n:
        return ("v", c2)
    if j == 0:                    # edge c0 -> c1, i steps from c0
        a, b, s = c0, c1, i
    elif i + j == n:              # edge c1 -> c2, j steps from c1
        a, b, s = c1, c2, j
    elif i == 0:                  # edge c2 -> c0, n - j steps from c2
        a, b, s = c2, c0, n - j
    else:
        return ("f", face, i, j)
    return ("e", a, b, s) if a < b else ("e", b, a, n - s)


def mid(p, q):
    return ((p[0] + q[0]) // 2, (p[1] + q[1]) // 2)


def sub_triangles(level, n):
    """(path, corner lattice coordinates) of the 4^level sub-triangles, in path order."""
    out = [((), ((0, 0), (n, 0), (0, n)))]
    for _ in range(level):
        nxt = []
        for path, (a, b, c) in out:
            e0, e1, e2 = mid(a, b), mid(b, c), mid(c, a)
            for child, tri in enumerate(((a, e0, e2), (e0, b, e1), (e2, e1, c), (e1, e2, e0))):
                nxt.append((path + (child,), tri))
        out = nxt
    return out


def fmt(x):
    s = f"{x:.5f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_ridge_edits.py SPOT.obj OUT.json")
    verts, faces = read_obj(sys.argv[1])
    normals = vertex_normals(verts, faces)
    lo = [min(v[d] for v in verts) for d in range(3)]
    hi = [max(v[d] for v in verts) for d in range(3)]
    diag = math.sqrt(sum((hi[d] - lo[d]) ** 2 for d in range(3)))
    n = 1 << LEVEL
    subs = sub_triangles(LEVEL, n)
    seen, edits = set(), []
    for f, corners in enumerate(faces):
        p = [verts[c] for c in corners]
        if min(abs(q[0]) for q in p) >= WIDTH or max(q[2] for q in p) <= Z0 or min(q[2] for q in p) >= Z1:
            continue              # no point of this face can be on the ridge
        nm = [normals[c] for c in corners]
        for path, tri in subs:
            for corner, (i, j) in enumerate(tri):
                key = lattice_key(f, corners, i, j, n)
                if key in seen:
                    continue
                seen.add(key)
                w1, w2 = i / n, j / n
                w0 = 1 - w1 - w2
                pos = tuple(w0 * p[0][d] + w1 * p[1][d] + w2 * p[2][d] for d in range(3))
                nrm = normalize(tuple(w0 * nm[0][d] + w1 * nm[1][d] + w2 * nm[2][d] for d in range(3)))
                h = ridge_height(pos, nrm, diag)
                if h <= 0:
                    continue
                edits.append((f, path, corner, tuple(h * nrm[d] for d in range(3))))
    with open(sys.argv[2], "w") as out:
        out.write('{"edits": [\n')
        for k, (f, path, corner, value) in enumerate(edits):
            out.write('  {"face": %d, "path": [%s], "vertex": %d, "op": "add", "value": [%s]}%s\n' % (
                f, ", ".join(str(c) for c in path), corner, ", ".join(fmt(x) for x in value),
                "," if k + 1 < len(edits) else ""))
        out.write("]}\n")
    print(f"{sys.argv[2]}: {len(edits)} level-{LEVEL} add edits, ridge height {HEIGHT * diag:.4g} "
          f"({HEIGHT:.1%} of the diagonal {diag:.4g})")


if __name__ == "__main__":
    main()
