#!/usr/bin/env python3
"""Writes tests/data/scenes/manifold_pinch.gltf: two tetrahedra touching at one
point, in one mesh of two primitives (two materials) over one POSITION accessor,
with EXT_mesh_manifold saying which coincident vertices are one.

  vertices 0..3  tetrahedron A (apex 0 at the origin)     8: a copy of 1 (a seam:
  vertices 4..7  tetrahedron B (apex 4 at the origin)        the face 1 2 3 uses it)

  primitive 0: A's faces, corner "8" where 1 would be    } one indices bufferView,
  primitive 1: B's faces                                 } each primitive a range
  manifoldPrimitive: both ranges, sparse: that corner 8 -> 1

Welded by position, 0 and 4 become one (a pinch: two closed fans at one vertex)
and 8 joins 1: 7 control vertices. Welded as the extension says, 8 joins 1 and 0,
4 stay apart: 8 control vertices, two separate closed surfaces.
"""
import base64, json, struct, sys

A = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
B = [(-x, -y, -z) for (x, y, z) in A]
pos = A + B + [A[1]]

def outward(tri, verts, centre):
    a, b, c = (verts[i] for i in tri)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    m = [(a[k] + b[k] + c[k]) / 3 - centre[k] for k in range(3)]
    return tri if sum(n[k] * m[k] for k in range(3)) > 0 else (tri[0], tri[2], tri[1])

def faces(base):
    verts = {base + i: pos[base + i] for i in range(4)}
    centre = [sum(p[k] for p in verts.values()) / 4 for k in range(3)]
    return [outward((base + a, base + b, base + c), pos, centre) for (a, b, c) in [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)]]

prim0 = [i for tri in faces(0) for i in tri]
prim1 = [i for tri in faces(4) for i in tri]
last = [k for k in range(9, 12) if prim0[k] == 1]   # the face 1 2 3 is the last of A's
seam = last[0]
prim0[seam] = 8

positions = b"".join(struct.pack("<3f", *p) for p in pos)
indices = struct.pack("<%dI" % (len(prim0) + len(prim1)), *(prim0 + prim1))
sparse_i = struct.pack("<I", seam)
sparse_v = struct.pack("<I", 1)
blob = positions + indices + sparse_i + sparse_v
o_idx, o_si, o_sv = len(positions), len(positions) + len(indices), len(positions) + len(indices) + 4

doc = {
    "asset": {"version": "2.0", "generator": "scripts/make_manifold_pinch.py"},
    "extensionsUsed": ["EXT_mesh_manifold"],
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "pinch"}],
    "materials": [{"name": "a", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.5, 0.2, 1]}},
                  {"name": "b", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.9, 1]}}],
    "meshes": [{
        "name": "pinch",
        "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0, "mode": 4},
                       {"attributes": {"POSITION": 0}, "indices": 2, "material": 1, "mode": 4}],
        "extensions": {"EXT_mesh_manifold": {
            "manifoldPrimitive": {"attributes": {"POSITION": 0}, "indices": 3, "mode": 4},
            "mergeIndices": 4, "mergeValues": 5}}}],
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions), "target": 34962},
                    {"buffer": 0, "byteOffset": o_idx, "byteLength": len(indices), "target": 34963},
                    {"buffer": 0, "byteOffset": o_si, "byteLength": 8}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3",
         "min": [min(p[k] for p in pos) for k in range(3)], "max": [max(p[k] for p in pos) for k in range(3)]},
        {"bufferView": 1, "byteOffset": 0, "componentType": 5125, "count": len(prim0), "type": "SCALAR"},
        {"bufferView": 1, "byteOffset": 4 * len(prim0), "componentType": 5125, "count": len(prim1), "type": "SCALAR"},
        {"bufferView": 1, "byteOffset": 0, "componentType": 5125, "count": len(prim0) + len(prim1), "type": "SCALAR",
         "sparse": {"count": 1, "indices": {"bufferView": 2, "byteOffset": 0, "componentType": 5125},
                    "values": {"bufferView": 2, "byteOffset": 4}}},
        {"bufferView": 2, "byteOffset": 0, "componentType": 5125, "count": 1, "type": "SCALAR"},
        {"bufferView": 2, "byteOffset": 4, "componentType": 5125, "count": 1, "type": "SCALAR"}],
}
out = sys.argv[1] if len(sys.argv) > 1 else "tests/data/scenes/manifold_pinch.gltf"
with open(out, "w") as f:
    json.dump(doc, f, indent=1)
    f.write("\n")
