#!/usr/bin/env python3
"""Writes the seed corpora of fuzz/corpus/<target>/ (fuzz/README.md, "Seeds").

Usage: python3 fuzz/make_seeds.py build/tessera [fuzz/corpus]

Every seed is small (well under 64 KiB) and most are valid inputs, so that the fuzzer starts from the
parsers' deep paths; a few are malformed on purpose. The .tframe seeds are recorded from built-in scenes
and the .mta seeds are built from tiny scenes with the given `tessera` binary; everything else is written
here (the .tab seeds by an encoder of docs/tab-format.md of this script's own, independent of
batching/tab_file.cpp). The output is deterministic: running it again rewrites the same bytes (the
recorded frames and the paging files are reproducible by the project's own rules). Seeds that are in the
corpus but not written here (minimised fuzzer finds, fixed crashers) are left alone.
Standard library only.
"""
import base64
import hashlib
import json
import os
import struct
import subprocess
import sys
import tempfile
import zlib


def png(width, height, pixel, channels=3):
    """An 8-bit PNG (colour type 2 or 6) with pixel(x, y) -> tuple of `channels` bytes."""
    rows = b"".join(b"\x00" + b"".join(bytes(pixel(x, y)) for x in range(width)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 6 if channels == 4 else 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


TINY_PNG = png(2, 2, lambda x, y: ((255, 0, 0, 255), (0, 255, 0, 128), (0, 0, 255, 255), (255, 255, 255, 0))[y * 2 + x], 4)


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(path, "wb") as f:
        f.write(data)


# --- tframe -------------------------------------------------------------------------------------------
def tframe_seeds(tessera, out, tmp):
    os.makedirs(out, exist_ok=True)
    # s3tc_blocks: a version-2 file (CreateTexture with desc.compression, S3TC blocks in the uploads).
    for scene in ["depth", "wrap_filter", "blend", "clip_planes", "fill_fan", "layered_target", "s3tc_blocks"]:
        subprocess.run([tessera, "render", scene, "--record", os.path.join(out, scene + ".tframe"), "-o",
                        os.path.join(tmp, scene + ".png")], check=True, stdout=subprocess.DEVNULL)
    # An empty frame: header only, 0 commands, 0 blob bytes, nextId 1 (valid).
    empty = b"TSFRAME\x00" + struct.pack("<IIQQQ", 1, 72, 0, 0, 1) + hashlib.sha256(b"").digest()
    write(os.path.join(out, "empty-frame.tframe"), empty)
    depth = open(os.path.join(out, "depth.tframe"), "rb").read()
    write(os.path.join(out, "bad-truncated-in-command.tframe"), depth[:150])
    # Version 2 is known since S3TC textures, so this one is bad in another way now: version-1 CreateTexture
    # payloads (26 bytes) under a version-2 header (27). bad-version-3 is the unknown version.
    write(os.path.join(out, "bad-version-2.tframe"), depth[:8] + struct.pack("<I", 2) + depth[12:])
    write(os.path.join(out, "bad-version-3.tframe"), depth[:8] + struct.pack("<I", 3) + depth[12:])
    write(os.path.join(out, "bad-header-only-magic.tframe"), b"TSFRAME\x00")


# --- mta ----------------------------------------------------------------------------------------------
def mta_seeds(tessera, out, tmp):
    os.makedirs(out, exist_ok=True)
    def build(model, name, *args):
        subprocess.run([tessera, "mta", "build", model, "--atlas-size", "64", "--border", "1", "--quiet", "-o",
                        os.path.join(out, name)] + list(args), check=True, stdout=subprocess.DEVNULL)

    # 1. Two buildings of the synthetic city with 8x8 facades: one leaf, textured and untextured triangles.
    city = os.path.join(tmp, "city")
    subprocess.run([tessera, "city", "--preset", "berlin", "--buildings", "2", "--texture-size", "8", "--quiet",
                    "-o", city], check=True, stdout=subprocess.DEVNULL)
    build(os.path.join(city, "berlin.gltf"), "city-2-buildings-one-leaf.mta", "--d-min", "50")
    # 2. Two triangles with a 40x40 texture each: their atlas areas do not fit one 64x64 atlas, so the root
    #    splits into two leaves (children -1 in the other quadrants): three nodes, three atlases.
    scene = os.path.join(tmp, "tri")
    os.makedirs(scene, exist_ok=True)
    write(os.path.join(scene, "a.png"), png(40, 40, lambda x, y: ((x * 5) & 255, (y * 5) & 255, ((x ^ y) * 3) & 255)))
    write(os.path.join(scene, "b.png"), png(40, 40, lambda x, y: ((x * 5 + 99) & 255, (y * 5) & 255, (x ^ y) & 255)))
    write(os.path.join(scene, "c.png"), png(16, 16, lambda x, y: (x * 16, y * 16, 128, (x + y) * 8), 4))
    write(os.path.join(scene, "two.mtl"), "newmtl a\nmap_Kd a.png\nnewmtl b\nmap_Kd b.png\nnewmtl c\nmap_Kd c.png\n")
    tri = "mtllib two.mtl\nv 0 0 0\nv 10 0 0\nv 10 10 0\nv 20 0 0\nv 30 0 0\nv 30 10 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
    write(os.path.join(scene, "two.obj"), tri + "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 4/1 5/2 6/3\n")
    build(os.path.join(scene, "two.obj"), "two-triangles-root-and-two-leaves.mta", "--d-min", "5")
    #    The same tree with raw blocks (`--raw`): row pieces and raw atlases (the others store S3TC chains).
    build(os.path.join(scene, "two.obj"), "two-triangles-raw-blocks.mta", "--d-min", "5", "--raw")
    # 3. One triangle with an RGBA texture: an RGBA tree (BC3 blocks).
    write(os.path.join(scene, "rgba.obj"), tri + "usemtl c\nf 1/1 2/2 3/3\n")
    build(os.path.join(scene, "rgba.obj"), "one-triangle-rgba-tree.mta", "--d-min", "5")
    # No malformed .mta seeds yet: PagingFile leaks its descriptor on every file it rejects, which the mta
    # target reports (fuzz/crashers/mta/mta-rejected-file-leaks-its-descriptor.mta). Once that is fixed,
    # add a truncated header and a header-only file here.


# --- gltf ---------------------------------------------------------------------------------------------
def gltf_triangle_buffer():
    """Positions (3 x vec3), texcoords (3 x vec2), indices (3 x u16 + 2 pad): 36 + 24 + 8 = 68 bytes."""
    pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    uv = struct.pack("<6f", 0, 1, 1, 1, 0, 0)
    idx = struct.pack("<3H", 0, 1, 2) + b"\x00\x00"
    return pos + uv + idx


def gltf_doc(buffer_uri, buffer_len, image, extra_views=()):
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
             {"buffer": 0, "byteOffset": 36, "byteLength": 24},
             {"buffer": 0, "byteOffset": 60, "byteLength": 6}] + list(extra_views)
    buf = {"byteLength": buffer_len}
    if buffer_uri is not None:
        buf["uri"] = buffer_uri
    return {
        "asset": {"version": "2.0", "generator": "tessera fuzz/make_seeds.py"},
        "extensionsUsed": ["KHR_texture_transform"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "parent", "children": [1], "matrix": [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1]},
                  {"name": "child", "mesh": 0, "translation": [0, 0, -1], "rotation": [0, 0, 0.7071068, 0.7071068],
                   "scale": [1, -1, 1]}],
        "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                                   "material": 0}]}],
        "materials": [{"name": "m", "alphaMode": "MASK", "alphaCutoff": 0.25, "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.5, 1], "baseColorTexture": {
                           "index": 0, "texCoord": 0,
                           "extensions": {"KHR_texture_transform": {"offset": [0, 1], "rotation": 1.5707963,
                                                                    "scale": [0.5, 0.5]}}}}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"wrapS": 33071, "wrapT": 33648}],
        "images": [image],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}],
        "bufferViews": views,
        "buffers": [buf],
    }


def glb(doc, bin_chunk):
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    bin_chunk += b"\x00" * (-len(bin_chunk) % 4)
    body = struct.pack("<I", len(js)) + b"JSON" + js + struct.pack("<I", len(bin_chunk)) + b"BIN\x00" + bin_chunk
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def gltf_seeds(out):
    data = gltf_triangle_buffer()
    uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    image = {"uri": "data:image/png;base64," + base64.b64encode(TINY_PNG).decode()}
    doc = gltf_doc(uri, len(data), image)
    write(os.path.join(out, "triangle-data-uris-texture-transform.gltf"), json.dumps(doc, indent=1))
    # The same triangle with its texture in an external file of the scratch directory.
    doc_ext = gltf_doc(uri, len(data), {"uri": "tex.png"})
    write(os.path.join(out, "triangle-external-png.gltf"), json.dumps(doc_ext, indent=1))
    # .glb: geometry and the PNG in the BIN chunk, the image through a bufferView.
    bin_chunk = data + TINY_PNG
    doc_glb = gltf_doc(None, len(bin_chunk), {"bufferView": 3, "mimeType": "image/png"},
                       [{"buffer": 0, "byteOffset": len(data), "byteLength": len(TINY_PNG)}])
    write(os.path.join(out, "triangle-embedded-png.glb"), glb(doc_glb, bin_chunk))
    # Strip and fan over 4 vertices, a sparse accessor substituting one position, normals, no material, a
    # points primitive (skipped with a note) and a node without a mesh.
    pos = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0)
    nrm = struct.pack("<12f", *([0, 0, 1] * 4))
    sparse_idx = struct.pack("<H", 2) + b"\x00\x00"
    sparse_val = struct.pack("<3f", 0, 2, 0)
    blob = pos + nrm + sparse_idx + sparse_val
    doc2 = {
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"name": "empty"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "mode": 5},
                                   {"attributes": {"POSITION": 2}, "mode": 6},
                                   {"attributes": {"POSITION": 0}, "mode": 0}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5123},
                                  "values": {"bufferView": 3}}}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 2},
                        {"buffer": 0, "byteOffset": 100, "byteLength": 12}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    }
    write(os.path.join(out, "strip-fan-sparse-points.gltf"), json.dumps(doc2, indent=1))
    # Quantized texcoords (normalized unsigned bytes, KHR_mesh_quantization) with a byteStride.
    q = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + bytes([0, 255, 0, 0, 255, 255, 0, 0, 0, 0, 0, 0])
    doc3 = {
        "asset": {"version": "2.0"},
        "extensionsRequired": ["KHR_mesh_quantization"], "extensionsUsed": ["KHR_mesh_quantization"],
        "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}], "images": [{"uri": "tex.png"}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5121, "normalized": True, "count": 3, "type": "VEC2"}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 12, "byteStride": 4}],
        "buffers": [{"byteLength": len(q), "uri": "data:application/octet-stream;base64," + base64.b64encode(q).decode()}],
    }
    write(os.path.join(out, "quantized-texcoords-stride.gltf"), json.dumps(doc3, indent=1))
    # Malformed ones.
    write(os.path.join(out, "bad-truncated.glb"), glb(doc_glb, bin_chunk)[:40])
    bad = json.loads(json.dumps(doc))
    bad["accessors"][0]["count"] = 4
    write(os.path.join(out, "bad-accessor-overruns-view.gltf"), json.dumps(bad, indent=1))
    cyc = json.loads(json.dumps(doc))
    cyc["nodes"][1]["children"] = [0]
    write(os.path.join(out, "bad-node-cycle.gltf"), json.dumps(cyc, indent=1))
    write(os.path.join(out, "bad-not-json.gltf"), '{"asset": {"version": "2.0"}, "nodes": [')
    write(os.path.join(out, "gltf-1.0-asset-goes-to-assimp.gltf"),
          json.dumps({"asset": {"version": "1.0"}, "scene": "s", "scenes": {"s": {"nodes": []}}}))


# --- obj ----------------------------------------------------------------------------------------------
def obj_seeds(out):
    write(os.path.join(out, "quad-textured-with-mtl.obj"), """# a textured quad; "#MTL" splits the input (fuzz/obj.cpp)
mtllib input.mtl
o quad
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
usemtl tex
f 1/1/1 2/2/1 3/3/1 4/4/1
#MTL
newmtl tex
Kd 1 0.5 0.25
d 0.5
map_Kd -o 0.5 0.5 0 -s 2 2 1 -clamp on tex.png
""")
    write(os.path.join(out, "groups-negative-indices-polygons.obj"), """mtllib input.mtl
g first
v 0 0 0
v 2 0 0
v 3 1 0
v 1 2 0
v -1 1 0
usemtl red
f -5 -4 -3 -2 -1
g second
v 0 0 1
v 1 0 1
v 0 1 1
vt 0.25 0.25
vt 0.75 0.25
vt 0.25 0.75
usemtl blue
f 6/1 7/2 8/3
usemtl missing
f 6 8 7
l 1 2
#MTL
newmtl red
Kd 1 0 0
newmtl blue
Kd 0 0 1
Tr 0.25
map_Kd tex.png
""")
    write(os.path.join(out, "no-mtl.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    write(os.path.join(out, "bad-face-index-out-of-range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    write(os.path.join(out, "bad-missing-texture.obj"),
          "mtllib input.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n#MTL\nnewmtl m\nmap_Kd nothere.png\n")


# --- ac3d ---------------------------------------------------------------------------------------------
AC_MATERIALS = """MATERIAL "white" rgb 1 1 1  amb 0.2 0.2 0.2  emis 0 0 0  spec 0.5 0.5 0.5  shi 10  trans 0
MATERIAL "glass" rgb 0.5 0.7 1  amb 0.2 0.2 0.2  emis 0 0 0  spec 0.5 0.5 0.5  shi 64  trans 0.5
"""


def ac3d_seeds(out):
    write(os.path.join(out, "quad-textured.ac"), "AC3Db\n" + AC_MATERIALS + """OBJECT world
kids 1
OBJECT poly
name "quad"
texture "tex.png"
texrep 1 1
loc 0 0 0
numvert 4
0 0 0
1 0 0
1 1 0
0 1 0
numsurf 1
SURF 0x10
mat 0
refs 4
0 0 0
1 1 0
2 1 1
3 0 1
kids 0
""")
    write(os.path.join(out, "group-rot-loc-two-materials-line.ac"), "AC3Db\n" + AC_MATERIALS + """OBJECT world
kids 1
OBJECT group
name "g"
loc 1 2 3
rot 0 1 0  -1 0 0  0 0 1
kids 2
OBJECT poly
name "tri"
numvert 3
0 0 0
1 0 0
0 1 0
numsurf 2
SURF 0x20
mat 1
refs 3
0 0 0
1 1 0
2 0 1
SURF 0x1
mat 0
refs 2
0 0 0
1 0 0
kids 0
OBJECT poly
name "empty"
numvert 0
numsurf 0
kids 0
""")
    write(os.path.join(out, "bad-truncated-numvert.ac"), "AC3Db\n" + AC_MATERIALS + """OBJECT world
kids 1
OBJECT poly
numvert 3
0 0 0
""")
    write(os.path.join(out, "bad-not-ac3d.ac"), "AC3Dx\nOBJECT world\n")


# --- camera_path --------------------------------------------------------------------------------------
def camera_path_seeds(out):
    write(os.path.join(out, "street-and-roof.path"), """tessera-camera-path 1
# Along a street, then up onto a roof.
name street-and-roof
fov 60
near 0.2
far 5000
0    1.7  0     10 1.7  0      # eye x y z, target x y z
5    1.7  0     15 1.7  0
10   1.7  0     20 1.7  0
10  30    -5    40 0    20     # on the roof, looking down into the next street
""")
    write(os.path.join(out, "every-directive-bom-crlf.path"),
          "\ufefftessera-camera-path 1\r\n\ttan_half_fov 0.5\r\nup 0 0 1\r\nnear +1e-3\r\nfar 1E4\r\n"
          "-1 -2 -3  4 5 6\r\nfov 90\r\n1.5e2 0 0 0 0 0.125\r\n")
    write(os.path.join(out, "bad-unknown-directive.path"), "tessera-camera-path 1\nzoom 2\n0 0 0 1 1 1\n")
    write(os.path.join(out, "bad-five-numbers.path"), "tessera-camera-path 1\n0 0 0 1 1\n")
    write(os.path.join(out, "bad-eye-equals-target.path"), "tessera-camera-path 1\n1 2 3 1 2 3\n")


# --- scene_manifest -----------------------------------------------------------------------------------
def scene_manifest_seeds(out):
    """Manifests over the fixtures fuzz/scene_manifest.cpp keeps beside its input: a.glb, c.obj,
    parts/b.gltf (empty files), sub/ (a directory) and nested.json (a manifest)."""
    def manifest(models, **extra):
        return json.dumps(dict(schema=1, models=models, **extra), indent=1) + "\n"
    write(os.path.join(out, "trs-two-models.json"), manifest(
        [{"file": "a.glb", "name": "house", "translation": [10, 0, -2.5], "rotation": [0, 90, 0], "scale": [1, 1, 2]},
         {"file": "parts/b.gltf", "rotation": [-45, 1e9, 0.5]}], comment="two models, degrees"))
    write(os.path.join(out, "column-major-transform.json"), manifest(
        [{"file": "c.obj", "transform": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1]}]))
    write(os.path.join(out, "bad-row-major-transform.json"), manifest(
        [{"file": "c.obj", "transform": [1, 0, 0, 5, 0, 1, 0, 6, 0, 0, 1, 7, 0, 0, 0, 1]}]))
    write(os.path.join(out, "bad-nested-manifest.json"), manifest([{"file": "nested.json"}]))
    write(os.path.join(out, "bad-directory-entry.json"), manifest([{"file": "sub"}]))
    write(os.path.join(out, "bad-missing-file.json"), manifest([{"file": "none.glb"}]))
    write(os.path.join(out, "bad-zero-scale.json"), manifest([{"file": "a.glb", "scale": [1, 0, 1]}]))
    write(os.path.join(out, "bad-both-transforms.json"), manifest(
        [{"file": "a.glb", "translation": [0, 0, 0], "transform": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}]))
    write(os.path.join(out, "bad-unknown-key.json"), manifest([{"file": "a.glb", "matrix": []}]))
    write(os.path.join(out, "bad-schema-2.json"), '{"schema": 2, "models": [{"file": "a.glb"}]}\n')
    write(os.path.join(out, "bad-syntax.json"), '{"schema": 1,\n "models": [{"file": "a.glb"},]}\n')
    write(os.path.join(out, "bad-number-beyond-double.json"),
          '{"schema": 1, "models": [{"file": "a.glb", "scale": [1e309, 1, 1]}]}\n')


# --- tab ----------------------------------------------------------------------------------------------
def tab_file(sections):
    """A .tab file (docs/tab-format.md) around the seven section payloads, with valid checksums."""
    offset, table = 456, b""
    for kind, payload in enumerate(sections, 1):
        table += struct.pack("<IIQQ", kind, 0, offset, len(payload)) + hashlib.sha256(payload).digest()
        offset += len(payload)
    head = b"TESSTAB\x1a" + struct.pack("<IIIIQ", 1, 456, 7, 0, offset) + table
    return head + hashlib.sha256(head).digest() + b"".join(sections)


def tab_string(text):
    return struct.pack("<I", len(text)) + text.encode()


def tab_one_quad(tam_layer=0):
    """One 2x2 REPEAT texture in one array, one output batch drawing a two-triangle batched mesh, then an
    untextured triangle."""
    meta = struct.pack("<III", 1 << 20, 256, 8) + tab_string("quad.glb") + struct.pack("<6f", 0, 0, 0, 1, 1, 0)
    textures = struct.pack("<I", 1) + tab_string("q.png") + struct.pack("<IIBBBB", 2, 2, 0, 0, 0, 2)
    texels = bytes(range(16)) + bytes([200, 100, 50, 255])
    arrays = struct.pack("<I", 1) + struct.pack("<IIBBB", 2, 2, 0, 0, 0) + struct.pack("<II", 1, 0)
    batches = (struct.pack("<I", 1) + struct.pack("<II", 1, 0) + struct.pack("<I", 1) +
               struct.pack("<II4ffB", 0, tam_layer, 1, 1, 1, 1, 0, 1) + struct.pack("<I", 1) +
               struct.pack("<IIII", 0, 6, 0, 1))
    meshes = struct.pack("<I", 2)
    meshes += tab_string("quad") + struct.pack("<BIII", 0, 0, 0, 6) + struct.pack("<II", 1, 0)
    meshes += struct.pack("<4fBfII", 1, 1, 1, 1, 0, 0.5, 0, 0)
    meshes += tab_string("roof") + struct.pack("<BIII", 1, 1, 6, 3) + struct.pack("<I", 0)
    meshes += struct.pack("<4fBfII", 0.5, 0.5, 0.5, 1, 0, 0.5, 0, 0)
    corners = [(0, 0), (1, 0), (1, 1), (0, 0), (1, 1), (0, 1), (0, 0), (1, 0), (0, 1)]
    vertices = struct.pack("<I", 9) + b"".join(struct.pack("<6f", x, y, 0, x, y, 0) for x, y in corners)
    return [meta, textures, texels, arrays, batches, meshes, vertices]


def tab_seeds(out):
    quad = tab_file(tab_one_quad())
    write(os.path.join(out, "one-quad-and-a-roof.tab"), quad)
    empty = [struct.pack("<III", 1 << 20, 256, 8) + tab_string("") + bytes(24)] + [struct.pack("<I", 0)] * 6
    empty[2] = b""  # no textures, no texels
    write(os.path.join(out, "empty-scene.tab"), tab_file(empty))
    write(os.path.join(out, "bad-truncated-in-textures.tab"), quad[:456 + 60])
    write(os.path.join(out, "bad-tam-layer-outside-its-array.tab"), tab_file(tab_one_quad(tam_layer=1)))


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    tessera = os.path.abspath(sys.argv[1])
    corpus = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
    with tempfile.TemporaryDirectory(prefix="tessera-seeds-") as tmp:
        tframe_seeds(tessera, os.path.join(corpus, "tframe"), tmp)
        mta_seeds(tessera, os.path.join(corpus, "mta"), tmp)
    gltf_seeds(os.path.join(corpus, "gltf"))
    obj_seeds(os.path.join(corpus, "obj"))
    ac3d_seeds(os.path.join(corpus, "ac3d"))
    camera_path_seeds(os.path.join(corpus, "camera_path"))
    tab_seeds(os.path.join(corpus, "tab"))
    scene_manifest_seeds(os.path.join(corpus, "scene_manifest"))
    for target in sorted(os.listdir(corpus)):
        d = os.path.join(corpus, target)
        for name in sorted(os.listdir(d)):
            size = os.path.getsize(os.path.join(d, name))
            if size > 64 * 1024:
                print(f"warning: {target}/{name} has {size} bytes (> 64 KiB)", file=sys.stderr)


if __name__ == "__main__":
    main()
