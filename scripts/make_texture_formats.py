#!/usr/bin/env python3
"""Writes tests/data/scenes/texture_formats.gltf: an octahedron whose material has a
KTX2 base colour texture (KHR_texture_basisu) and a WebP emissive texture
(EXT_texture_webp), each with a PNG fallback as the texture's `source`, every image a
data URI. loopbake must pass both images and both extensions through unchanged.

  images[0]  PNG, 1 x 1 (the fallback of both textures)
  images[1]  KTX2, 4 x 4, UASTC (vkFormat 0, one 16-byte block, no supercompression),
             one level, a Data Format Descriptor with one sample (KTX 2.0 spec 3.x)
  images[2]  WebP, 1 x 1, lossless (the common 26-byte feature-detection image)
"""
import base64, json, struct, sys, zlib

def png_1x1(rgba):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"\0" + bytes(rgba)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))

def ktx2_uastc_4x4():
    #  0: identifier (12)      12: 9 x uint32 header     48: index (32)
    # 80: level index (24)    104: DFD (4 + 24 + 16)     148: pad to 16, level 0 data (16)
    dfd_block = struct.pack("<HHHH", 0, 0, 2, 24 + 16)           # vendor, type, version, block size
    dfd_block += struct.pack("<BBBB", 166, 1, 2, 0)              # UASTC, BT.709, sRGB, flags
    dfd_block += struct.pack("<BBBB", 3, 3, 0, 0)                # texel block 4 x 4 (dimension - 1)
    dfd_block += struct.pack("<8B", 16, 0, 0, 0, 0, 0, 0, 0)     # bytes per plane
    dfd_block += struct.pack("<HBB", 0, 127, 3)                  # bit offset, bit length - 1, channel RGBA
    dfd_block += struct.pack("<4B", 0, 0, 0, 0)                  # sample position
    dfd_block += struct.pack("<II", 0, 0xFFFFFFFF)               # lower, upper
    dfd = struct.pack("<I", 4 + len(dfd_block)) + dfd_block
    dfd_offset = 104
    data_offset = (dfd_offset + len(dfd) + 15) // 16 * 16
    block = bytes(16)
    head = b"\xabKTX 20\xbb\r\n\x1a\n"
    head += struct.pack("<9I", 0, 1, 4, 4, 0, 0, 1, 1, 0)        # vkFormat .. supercompressionScheme
    head += struct.pack("<IIIIQQ", dfd_offset, len(dfd), 0, 0, 0, 0)
    head += struct.pack("<QQQ", data_offset, len(block), len(block))
    out = head + dfd
    out += bytes(data_offset - len(out)) + block
    return out

WEBP_1X1 = base64.b64decode("UklGRhoAAABXRUJQVlA4TA0AAAAvAAAAEAcQERGIiP4HAA==")

X, Y, Z = (1, 0, 0), (0, 1, 0), (0, 0, 1)
neg = lambda p: tuple(-c for c in p)
verts = [X, Y, Z, neg(X), neg(Y), neg(Z)]
faces = [(0, 1, 2), (1, 3, 2), (3, 4, 2), (4, 0, 2), (1, 0, 5), (3, 1, 5), (4, 3, 5), (0, 4, 5)]
blob = b"".join(struct.pack("<3f", *p) for p in verts)
uv_at = len(blob)
blob += b"".join(struct.pack("<2f", 0.5 + 0.4 * p[0], 0.5 - 0.4 * p[1]) for p in verts)
idx_at = len(blob)
blob += struct.pack("<%dH" % (3 * len(faces)), *[i for f in faces for i in f])

def uri(mime, data):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())

doc = {
    "asset": {"version": "2.0", "generator": "scripts/make_texture_formats.py"},
    "extensionsUsed": ["KHR_texture_basisu", "EXT_texture_webp"],
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "octahedron"}],
    "meshes": [{"name": "octahedron", "primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                                      "material": 0}]}],
    "materials": [{"name": "ktx2 and webp", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}},
                   "emissiveTexture": {"index": 1}, "emissiveFactor": [0.2, 0.2, 0.2]}],
    "textures": [{"source": 0, "sampler": 0, "extensions": {"KHR_texture_basisu": {"source": 1}}},
                 {"source": 0, "sampler": 0, "extensions": {"EXT_texture_webp": {"source": 2}}}],
    "samplers": [{"magFilter": 9729, "minFilter": 9729}],
    "images": [{"uri": uri("image/png", png_1x1((200, 180, 40, 255)))},
               {"uri": uri("image/ktx2", ktx2_uastc_4x4())},
               {"uri": uri("image/webp", WEBP_1X1)}],
    "buffers": [{"byteLength": len(blob), "uri": uri("application/octet-stream", blob)}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": uv_at, "target": 34962},
                    {"buffer": 0, "byteOffset": uv_at, "byteLength": idx_at - uv_at, "target": 34962},
                    {"buffer": 0, "byteOffset": idx_at, "byteLength": len(blob) - idx_at, "target": 34963}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
                  {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC2"},
                  {"bufferView": 2, "componentType": 5123, "count": 3 * len(faces), "type": "SCALAR"}],
}
out = sys.argv[1] if len(sys.argv) > 1 else "tests/data/scenes/texture_formats.gltf"
with open(out, "w") as f:
    json.dump(doc, f, indent=1)
    f.write("\n")
