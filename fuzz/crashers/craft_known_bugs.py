#!/usr/bin/env python3
"""Writes the hand-made reproducers of fuzz/crashers/ (listed in fuzz/crashers/README.md).

Usage: python3 fuzz/crashers/craft_known_bugs.py [fuzz]

These are the known bugs of the first fuzz campaign (fuzz/crashers/README.md) that a short fuzz run does not reach by itself: inputs that need
thousands of nested elements, or one exact huge count. Each function says which bug it shows. The .mta
reproducer starts from a seed of fuzz/corpus/mta/ and gets valid checksums, so `tessera mta render`
reproduces it too. Deterministic; standard library only.
"""
import json
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from fix_checksums import fix  # noqa: E402


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def mta_nodes_offset(data):
    """Byte offset of tree 0's node records (docs/mta-format.md, "Metadata"); also returns their count."""
    p = struct.unpack_from("<Q", data, 24)[0]  # metaOffset
    p += 16 + 48  # layerCount, atlasSize, border, screenWidth; six f64 parameters
    p += 40 + 4 + 24  # stats: five u64, u32 maxSplitDepth, three f64
    ntex = struct.unpack_from("<I", data, p)[0]
    p += 4 + 6 * ntex
    nimg = struct.unpack_from("<I", data, p)[0]
    p += 4
    for _ in range(nimg):
        p += 20
        p += 4 + struct.unpack_from("<I", data, p)[0]
    p += 8 + 24 * struct.unpack_from("<Q", data, p)[0]  # pieces
    p += 8 + 56 * struct.unpack_from("<Q", data, p)[0]  # blocks
    assert struct.unpack_from("<I", data, p)[0] >= 1, "no tree"
    p += 4 + 1  # tree count, tree 0's alpha
    return p + 8, struct.unpack_from("<Q", data, p)[0]


NODE = struct.Struct("<6f2f3I4ii4I")  # NodeDisk (mta/paging_file.cpp): 80 bytes


def mta_orphan_leaf(seed, out):
    """Bug 1 (.mta node table -> heap overflow in buildRuntimeGeometry). The seed is a root (2 triangles)
    with two leaves of one triangle each. The root now lists leaf 1 only, and leaf 1 covers both triangles,
    so every check of validateMeta holds. Leaf 2 still says parent 0 but no node lists it: validateMeta only
    checks nodes reachable as children, and buildRuntimeGeometry walks every leaf, placing 3 triangles into
    a vertex array sized for 2."""
    data = bytearray(open(seed, "rb").read())
    at, count = mta_nodes_offset(data)
    assert count == 3, "expected the root-and-two-leaves seed"
    nodes = [list(NODE.unpack_from(data, at + i * NODE.size)) for i in range(3)]
    children = slice(11, 15)
    root, leaf1 = nodes[0], nodes[1]
    assert sorted(root[children]) == [-1, -1, 1, 2] and root[17] == 2
    root[children] = [c if c != 2 else -1 for c in root[children]]
    leaf1[16], leaf1[17] = 0, 2  # firstTriangle, triangleCount: the whole root range
    for i in (0, 1):
        NODE.pack_into(data, at + i * NODE.size, *nodes[i])
    fix(data)
    write(out, bytes(data))


def gltf_doc(nodes, roots, accessor_count=3):
    tri = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"  # 3 x vec3
    return {"asset": {"version": "2.0"}, "scenes": [{"nodes": roots}], "nodes": nodes,
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": accessor_count, "type": "VEC3"}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36, "uri": tri}]}


def gltf_node_chain(out, depth):
    """Bug 2 (glTF deep node chain -> stack overflow): node i's only child is node i + 1; the loader's
    node() recursion (model/load_gltf.cpp) takes one stack frame per level."""
    nodes = [{"children": [i + 1]} for i in range(depth - 1)] + [{"mesh": 0}]
    write(out, json.dumps(gltf_doc(nodes, [0]), separators=(",", ":")))


def gltf_node_dag(out, levels):
    """Bug 3 (glTF node DAG blow-up): node i lists node i + 1 twice; there is no cycle, so the loader
    instantiates the last node's mesh 2^levels times (time and memory without bound)."""
    nodes = [{"children": [i + 1, i + 1]} for i in range(levels)] + [{"mesh": 0}]
    write(out, json.dumps(gltf_doc(nodes, [0]), indent=0))


def gltf_accessor_count(out):
    """Bug 4 (accessor count huge -> allocation before the bounds check, model/gltf_accessors.h): POSITION
    claims 10^9 VEC3 elements over a 36-byte bufferView; Reader::floats() sizes its output (12 GB) before
    locate() finds that the elements overrun the view."""
    write(out, json.dumps(gltf_doc([{"mesh": 0}], [0], accessor_count=1000000000), indent=0))


AC_HEAD = 'AC3Db\nMATERIAL "m" rgb 1 1 1  amb 0.2 0.2 0.2  emis 0 0 0  spec 0.5 0.5 0.5  shi 10  trans 0\n'
AC_TRI = "numvert 3\n0 0 0\n1 0 0\n0 1 0\nnumsurf 1\nSURF 0x10\nmat {mat}\nrefs 3\n0 0 0\n1 1 0\n2 0 1\nkids 0\n"


def ac3d_missing_material(out):
    """Bug 5a (AC3D via Assimp: a surface naming a material that does not exist -> abort)."""
    write(out, AC_HEAD + "OBJECT world\nkids 1\nOBJECT poly\n" + AC_TRI.format(mat=7))


def ac3d_deep_kids(out, depth):
    """Bug 5b (AC3D via Assimp: deeply nested kids -> stack overflow in its recursive object reader)."""
    write(out, AC_HEAD + "OBJECT world\nkids 1\n" + "OBJECT group\nkids 1\n" * depth + "OBJECT poly\n" +
          AC_TRI.format(mat=0))


def ac3d_huge_kids(out):
    """Bug 5c (AC3D via Assimp: `kids 2000000000` -> a huge allocation before the children are read)."""
    write(out, AC_HEAD + "OBJECT world\nkids 2000000000\nOBJECT poly\n" + AC_TRI.format(mat=0))


def main():
    fuzz = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(HERE)
    c = os.path.join(fuzz, "crashers")
    mta_orphan_leaf(os.path.join(fuzz, "corpus", "mta", "two-triangles-root-and-two-leaves.mta"),
                    os.path.join(c, "mta", "mta-orphan-leaf-heap-overflow-in-build-runtime-geometry.mta"))
    gltf_node_chain(os.path.join(c, "gltf", "gltf-node-chain-stack-overflow.gltf"), 20000)
    gltf_node_dag(os.path.join(c, "gltf", "gltf-node-dag-2-pow-40-instances.gltf"), 40)
    gltf_accessor_count(os.path.join(c, "gltf", "gltf-accessor-count-1e9-allocates-before-bounds-check.gltf"))
    ac3d_missing_material(os.path.join(c, "ac3d", "ac3d-missing-material-abort.ac"))
    ac3d_deep_kids(os.path.join(c, "ac3d", "ac3d-deep-kids-stack-overflow.ac"), 20000)
    ac3d_huge_kids(os.path.join(c, "ac3d", "ac3d-kids-2e9-huge-allocation.ac"))


if __name__ == "__main__":
    main()
