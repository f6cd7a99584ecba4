#!/usr/bin/env python3
"""Writes tests/data/scenes/vertex_attributes.gltf: an octahedron in one mesh of two
primitives whose vertices are per corner (unwelded), with the optional vertex
attributes a baked surface carries onto the limit surface:

  primitive 0 (the 4 faces with z > 0): TEXCOORD_0, TEXCOORD_1 (float),
                                        COLOR_0 (unsigned byte normalized, VEC4)
  primitive 1 (the 4 faces with z < 0): TEXCOORD_0, COLOR_0 (float, VEC3)

Colours differ between the corners of one position (face-varying, like UV seams),
and primitive 1 has no TEXCOORD_1 (the format reads (0, 0) there).
"""
import base64, json, struct, sys

X, Y, Z = (1, 0, 0), (0, 1, 0), (0, 0, 1)
neg = lambda p: tuple(-c for c in p)
upper = [(X, Y, Z), (Y, neg(X), Z), (neg(X), neg(Y), Z), (neg(Y), X, Z)]
lower = [(Y, X, neg(Z)), (neg(X), Y, neg(Z)), (neg(Y), neg(X), neg(Z)), (X, neg(Y), neg(Z))]

def corners(faces):
    return [p for f in faces for p in f]

def uv0(p):
    return (0.5 + 0.4 * p[0], 0.5 - 0.4 * p[1])

def uv1(p):
    return (0.25 * (p[2] + 1), 0.75 - 0.25 * p[0])

def rgba8(k, p):
    return (int(127 + 120 * p[0]) & 255, (60 * k) & 255, int(127 + 120 * p[2]) & 255, 200 + k)

def rgb(k, p):
    return (0.5 + 0.5 * p[1], 0.1 * (k % 5), 0.25)

c0, c1 = corners(upper), corners(lower)
blob = b""
views, accessors = [], []

def add(data, component, count, kind, target=None, extra=None):
    global blob
    while len(blob) % 4:
        blob += b"\0"
    view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
    if target:
        view["target"] = target
    views.append(view)
    blob += data
    acc = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": kind}
    acc.update(extra or {})
    accessors.append(acc)
    return len(accessors) - 1

def positions(cs):
    return add(b"".join(struct.pack("<3f", *p) for p in cs), 5126, len(cs), "VEC3", 34962,
               {"min": [min(p[k] for p in cs) for k in range(3)], "max": [max(p[k] for p in cs) for k in range(3)]})

def floats(values, kind):
    return add(b"".join(struct.pack("<%df" % len(v), *v) for v in values), 5126, len(values), kind, 34962)

def indices(n):
    return add(struct.pack("<%dH" % n, *range(n)), 5123, n, "SCALAR", 34963)

p0 = {"POSITION": positions(c0), "TEXCOORD_0": floats([uv0(p) for p in c0], "VEC2"),
      "TEXCOORD_1": floats([uv1(p) for p in c0], "VEC2"),
      "COLOR_0": add(b"".join(struct.pack("<4B", *rgba8(k, p)) for k, p in enumerate(c0)), 5121, len(c0), "VEC4",
                     34962, {"normalized": True})}
i0 = indices(len(c0))
p1 = {"POSITION": positions(c1), "TEXCOORD_0": floats([uv0(p) for p in c1], "VEC2"),
      "COLOR_0": floats([rgb(k, p) for k, p in enumerate(c1)], "VEC3")}
i1 = indices(len(c1))

doc = {
    "asset": {"version": "2.0", "generator": "scripts/make_vertex_attributes.py"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "octahedron"}],
    "meshes": [{"name": "octahedron", "primitives": [{"attributes": p0, "indices": i0, "mode": 4},
                                                     {"attributes": p1, "indices": i1, "mode": 4}]}],
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    "bufferViews": views,
    "accessors": accessors,
}
out = sys.argv[1] if len(sys.argv) > 1 else "tests/data/scenes/vertex_attributes.gltf"
with open(out, "w") as f:
    json.dump(doc, f, indent=1)
    f.write("\n")
