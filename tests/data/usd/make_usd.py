#!/usr/bin/env python3
"""Writes the USD test assets of tests/data/usd with Pixar's own writer (usd-core),
not ours, so the reader is checked against an independent implementation.

    python3 -m venv /tmp/usd-core && /tmp/usd-core/bin/pip install usd-core==26.11
    /tmp/usd-core/bin/python tests/data/usd/make_usd.py

(usd-core must not go into the build's .venv-usd: see scripts/setup-debian.sh.)
Deterministic: the same files every run. Written:
  <shape>.usdc, <shape>.usda   corpus OBJ shapes (tests/data/corpus/opensubdiv-loop):
                               the same points, faces, faceVarying st (indexed), crease,
                               corner and boundary tags; .usdc with one sharpness a
                               crease (each edge a crease), .usda with chains of edges
                               and one sharpness an edge. Their OBJ is the oracle.
  scene.usda, scene.usdc       a nested Xform hierarchy; /World/Body/Box a Loop mesh of
                               quads with vertex st, uniform displayColor, a hole, a
                               corner, edgeAndCorner by default, time samples on points;
                               /World/Smooth a catmullClark mesh. box.obj: the box's OBJ
                               twin (its default-time points, tags as t lines).
  open_quad.usda, open_quad.obj  a flat open unit quad, one face of 4, USD's default
                               boundary (edgeAndCorner); the OBJ twin says it with a tag.
  bad/*.usda, bad/*.usdc       malformed inputs: loopbake exits 2 naming prim and attribute.
                               (bad/crash_paths.usdc is not written here: fuzz_usd found it.)
"""
import os
import struct

from pxr import Gf, Sdf, Usd, UsdGeom, Vt

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "..", "corpus", "opensubdiv-loop")
SHAPES = ["loop_icos_semisharp", "loop_cubes_infsharp", "loop_triangle_edgenone", "loop_triangle_edgecorner",
          "loop_saddle_edgeonly", "loop_fvar_bound2", "loop_xord_boundary"]
BOUNDARY = {0: "none", 1: "edgeAndCorner", 2: "edgeOnly"}


def f32(x):
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def read_obj(path):
    m = dict(v=[], vt=[], faces=[], fuv=[], creases=[], corners=[], holes=[], boundary=2)
    for line in open(path):
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            m["v"].append(tuple(float(x) for x in t[1:4]))
        elif t[0] == "vt":
            m["vt"].append(tuple(float(x) for x in t[1:3]))
        elif t[0] == "f":
            c = [x.split("/") for x in t[1:]]
            m["faces"].append([int(x[0]) - 1 for x in c])
            m["fuv"].append([int(x[1]) - 1 for x in c] if len(c[0]) > 1 and c[0][1] else None)
        elif t[0] == "t":
            ni, nf, _ = (int(x) for x in t[2].split("/"))
            ints = [int(x) for x in t[3:3 + ni]]
            floats = [float(x) for x in t[3 + ni:3 + ni + nf]]
            if t[1] == "crease":
                for e in range(ni // 2):
                    m["creases"].append((ints[2 * e], ints[2 * e + 1], floats[e if nf > 1 else 0]))
            elif t[1] == "corner":
                for k, v in enumerate(ints):
                    m["corners"].append((v, floats[k if nf > 1 else 0]))
            elif t[1] == "hole":
                m["holes"] += ints
            elif t[1] == "interpolateboundary":
                m["boundary"] = ints[0]
    return m


def chains(edges):
    """Consecutive edges that continue each other (b of one is a of the next) as one crease."""
    out = []
    for a, b, s in edges:
        if out and out[-1][0][-1] == a:
            out[-1][0].append(b)
            out[-1][1].append(s)
        else:
            out.append(([a, b], [s]))
    return out


def define_mesh(stage, path, m, per_edge):
    mesh = UsdGeom.Mesh.Define(stage, path)
    mesh.CreateSubdivisionSchemeAttr("loop")
    mesh.CreatePointsAttr(Vt.Vec3fArray([Gf.Vec3f(*p) for p in m["v"]]))
    mesh.CreateFaceVertexCountsAttr([len(f) for f in m["faces"]])
    mesh.CreateFaceVertexIndicesAttr([i for f in m["faces"] for i in f])
    mesh.CreateInterpolateBoundaryAttr(BOUNDARY[m["boundary"]])
    if m["creases"]:
        if per_edge:
            cs = chains(m["creases"])
            mesh.CreateCreaseIndicesAttr([i for c in cs for i in c[0]])
            mesh.CreateCreaseLengthsAttr([len(c[0]) for c in cs])
            mesh.CreateCreaseSharpnessesAttr([s for c in cs for s in c[1]])
        else:
            mesh.CreateCreaseIndicesAttr([i for a, b, s in m["creases"] for i in (a, b)])
            mesh.CreateCreaseLengthsAttr([2] * len(m["creases"]))
            mesh.CreateCreaseSharpnessesAttr([s for a, b, s in m["creases"]])
    if m["corners"]:
        mesh.CreateCornerIndicesAttr([v for v, s in m["corners"]])
        mesh.CreateCornerSharpnessesAttr([s for v, s in m["corners"]])
    if m["holes"]:
        mesh.CreateHoleIndicesAttr(m["holes"])
    if m["vt"] and all(f is not None for f in m["fuv"]):
        st = UsdGeom.PrimvarsAPI(mesh).CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray,
                                                     UsdGeom.Tokens.faceVarying)
        st.Set(Vt.Vec2fArray([Gf.Vec2f(*uv) for uv in m["vt"]]))
        st.SetIndices(Vt.IntArray([i for f in m["fuv"] for i in f]))
    return mesh


def write(stage_fn, path):
    if os.path.exists(path):
        os.remove(path)
    stage = Usd.Stage.CreateNew(path)
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.y)
    stage_fn(stage)
    stage.GetRootLayer().Save()


def shapes():
    for name in SHAPES:
        m = read_obj(os.path.join(CORPUS, name + ".obj"))
        write(lambda s: define_mesh(s, "/" + name, m, False), os.path.join(HERE, name + ".usdc"))
        write(lambda s: define_mesh(s, "/" + name, m, True), os.path.join(HERE, name + ".usda"))


# The box of the scene: 8 points, 6 quads (face 5 a hole), an infinitely sharp crease
# chain over three edges, a corner.
BOX_POINTS = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1), (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
BOX_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
BOX_CREASE = [4, 5, 6, 7]
BOX_UV = [(0, 0), (0.25, 0), (0.5, 0), (0.75, 0), (0, 1), (0.25, 1), (0.5, 1), (0.75, 1)]


def scene(stage):
    stage.SetStartTimeCode(0)
    stage.SetEndTimeCode(10)
    world = UsdGeom.Xform.Define(stage, "/World")
    world.AddTranslateOp().Set(Gf.Vec3d(0, 1, 0))
    body = UsdGeom.Xform.Define(stage, "/World/Body")
    body.AddTranslateOp().Set(Gf.Vec3d(2, 0, 0))
    body.AddRotateXYZOp().Set(Gf.Vec3f(0, 90, 0))
    body.AddScaleOp().Set(Gf.Vec3f(0.5, 0.5, 0.5))
    UsdGeom.Scope.Define(stage, "/World/Body/Group")
    box = UsdGeom.Mesh.Define(stage, "/World/Body/Group/Box")
    box.CreateSubdivisionSchemeAttr("loop")
    pts = box.CreatePointsAttr(Vt.Vec3fArray([Gf.Vec3f(*p) for p in BOX_POINTS]))
    pts.Set(Vt.Vec3fArray([Gf.Vec3f(p[0] + 3, p[1], p[2]) for p in BOX_POINTS]), 10.0)
    box.CreateFaceVertexCountsAttr([4] * 6)
    box.CreateFaceVertexIndicesAttr([i for f in BOX_FACES for i in f])
    box.CreateCreaseIndicesAttr(BOX_CREASE)
    box.CreateCreaseLengthsAttr([len(BOX_CREASE)])
    box.CreateCreaseSharpnessesAttr([10.0])
    box.CreateCornerIndicesAttr([0])
    box.CreateCornerSharpnessesAttr([3.0])
    box.CreateHoleIndicesAttr([5])
    st = UsdGeom.PrimvarsAPI(box).CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.vertex)
    st.Set(Vt.Vec2fArray([Gf.Vec2f(*uv) for uv in BOX_UV]))
    box.CreateDisplayColorPrimvar(UsdGeom.Tokens.uniform).Set(
        Vt.Vec3fArray([Gf.Vec3f(k / 6.0, 0.5, 1 - k / 6.0) for k in range(6)]))
    smooth = UsdGeom.Mesh.Define(stage, "/World/Smooth")
    smooth.AddTranslateOp().Set(Gf.Vec3d(-3, 0, 0))
    smooth.CreatePointsAttr(Vt.Vec3fArray([Gf.Vec3f(*p) for p in BOX_POINTS]))
    smooth.CreateFaceVertexCountsAttr([4] * 6)
    smooth.CreateFaceVertexIndicesAttr([i for f in BOX_FACES for i in f])


def box_obj(path):
    with open(path, "w") as f:
        f.write("# The Box of scene.usda (tests/data/usd/make_usd.py): the same points, faces and tags.\n")
        for p in BOX_POINTS:
            f.write("v %r %r %r\n" % tuple(f32(x) for x in p))
        for uv in BOX_UV:
            f.write("vt %r %r\n" % tuple(f32(x) for x in uv))
        for face in BOX_FACES:
            f.write("f " + " ".join("%d/%d" % (i + 1, i + 1) for i in face) + "\n")
        for a, b in zip(BOX_CREASE, BOX_CREASE[1:]):
            f.write("t crease 2/1/0 %d %d 10\n" % (a, b))
        f.write("t corner 1/1/0 0 3\n")
        f.write("t hole 1/0/0 5\n")
        f.write("t interpolateboundary 1/0/0 1\n")


QUAD_POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]


def open_quad(stage):
    mesh = UsdGeom.Mesh.Define(stage, "/Quad")
    mesh.CreateSubdivisionSchemeAttr("loop")
    mesh.CreatePointsAttr(Vt.Vec3fArray([Gf.Vec3f(*p) for p in QUAD_POINTS]))
    mesh.CreateFaceVertexCountsAttr([4])
    mesh.CreateFaceVertexIndicesAttr([0, 1, 2, 3])


def open_quad_obj(path):
    with open(path, "w") as f:
        f.write("# The Quad of open_quad.usda (tests/data/usd/make_usd.py): edgeAndCorner as a tag.\n")
        for p in QUAD_POINTS:
            f.write("v %r %r %r\n" % tuple(f32(x) for x in p))
        f.write("f 1 2 3 4\n")
        f.write("t interpolateboundary 1/0/0 1\n")


def quad_mesh(stage, path="/Mesh", scheme="loop"):
    mesh = UsdGeom.Mesh.Define(stage, path)
    mesh.CreateSubdivisionSchemeAttr(scheme)
    mesh.CreatePointsAttr(Vt.Vec3fArray([Gf.Vec3f(*p) for p in BOX_POINTS]))
    mesh.CreateFaceVertexCountsAttr([4] * 6)
    mesh.CreateFaceVertexIndicesAttr([i for f in BOX_FACES for i in f])
    return mesh


def bad_crease_one_vertex(s):
    m = quad_mesh(s)
    m.CreateCreaseIndicesAttr([0])
    m.CreateCreaseLengthsAttr([1])
    m.CreateCreaseSharpnessesAttr([1.0])


def bad_sharpness_length(s):
    m = quad_mesh(s)
    m.CreateCreaseIndicesAttr([0, 1, 2])
    m.CreateCreaseLengthsAttr([3])
    m.CreateCreaseSharpnessesAttr([1.0, 2.0, 3.0])


def bad_points_type(s):
    m = quad_mesh(s)
    m.GetPrim().RemoveProperty("points")
    spec = s.GetRootLayer().GetPrimAtPath("/Mesh")  # Sdf: the schema would refuse the type
    Sdf.AttributeSpec(spec, "points", Sdf.ValueTypeNames.Int).default = 3


def bad_reference(s):
    quad_mesh(s)
    s.DefinePrim("/Ref").GetReferences().AddReference("other.usda")


def bad():
    d = os.path.join(HERE, "bad")
    cases = {
        "counts_mismatch": lambda s: quad_mesh(s).CreateFaceVertexCountsAttr([4] * 5),
        "index_out_of_range": lambda s: quad_mesh(s).CreateFaceVertexIndicesAttr(
            [i for f in BOX_FACES for i in f][:-1] + [8]),
        "negative_count": lambda s: quad_mesh(s).CreateFaceVertexCountsAttr([4] * 5 + [-4]),
        "crease_one_vertex": bad_crease_one_vertex,
        "missing_points": lambda s: quad_mesh(s).GetPrim().RemoveProperty("points"),
        "sharpness_length": bad_sharpness_length,
        "st_count": lambda s: UsdGeom.PrimvarsAPI(quad_mesh(s)).CreatePrimvar(
            "st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.faceVarying).Set(Vt.Vec2fArray([(0, 0)] * 5)),
        "points_type": bad_points_type,
        "reference": bad_reference,
    }
    for name, fn in cases.items():
        write(fn, os.path.join(d, name + ".usda"))
    write(lambda s: quad_mesh(s).CreateFaceVertexCountsAttr([4] * 5), os.path.join(d, "counts_mismatch.usdc"))
    # A crate file cut short, and one with its last 200 bytes (the table of contents)
    # scrambled.
    good = open(os.path.join(HERE, "loop_icos_semisharp.usdc"), "rb").read()
    open(os.path.join(d, "truncated.usdc"), "wb").write(good[:len(good) // 2])
    garbled = bytearray(good)
    for i in range(len(garbled) - 200, len(garbled)):
        garbled[i] = (garbled[i] * 31 + 7) & 0xFF
    open(os.path.join(d, "garbled.usdc"), "wb").write(bytes(garbled))


if __name__ == "__main__":
    shapes()
    write(scene, os.path.join(HERE, "scene.usda"))
    write(scene, os.path.join(HERE, "scene.usdc"))
    box_obj(os.path.join(HERE, "box.obj"))
    write(open_quad, os.path.join(HERE, "open_quad.usda"))
    open_quad_obj(os.path.join(HERE, "open_quad.obj"))
    bad()
