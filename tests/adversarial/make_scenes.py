#!/usr/bin/env python3
"""Writes the adversarial scene files (glTF, glb, OBJ) into a folder.

They are generated rather than committed because some are large (a 20,000-deep node
hierarchy) and all are variations of one valid triangle; `valid.gltf` is the control.
Usage: make_scenes.py OUT_DIR
"""
import base64
import json
import os
import struct
import sys


def triangle(indices=(0, 1, 2)):
    """A glTF dict with one triangle mesh (positions + indices) and one root node."""
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    index_bytes = struct.pack("<%dH" % len(indices), *indices)
    index_bytes += b"\0" * (-len(index_bytes) % 4)
    data = positions + index_bytes
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 2 * len(indices)},
        ],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," +
                            base64.b64encode(data).decode()}],
    }


def with_camera(gltf, node_extra):
    gltf["cameras"] = [{"type": "perspective",
                        "perspective": {"yfov": 0.8, "znear": 0.01, "aspectRatio": 1.0}}]
    camera = {"camera": 0, "translation": [0.3, 0.3, 3]}
    camera.update(node_extra)
    gltf["nodes"].append(camera)
    gltf["scenes"][0]["nodes"].append(len(gltf["nodes"]) - 1)
    return gltf


def deep(depth):
    gltf = triangle()
    gltf["nodes"] = [{"children": [i + 1]} for i in range(depth - 1)] + [{"mesh": 0}]
    return gltf


def glb(json_bytes, declared_json=None, declared_total=None, extra=b""):
    json_bytes += b" " * (-len(json_bytes) % 4)
    chunk = struct.pack("<II", declared_json if declared_json is not None else len(json_bytes),
                        0x4E4F534A) + json_bytes
    body = chunk + extra
    total = declared_total if declared_total is not None else 12 + len(body)
    return b"glTF" + struct.pack("<II", 2, total) + body


def write(out, name, content):
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(os.path.join(out, name), mode) as f:
        f.write(content)


def main(out):
    os.makedirs(out, exist_ok=True)
    dump = json.dumps
    write(out, "valid.gltf", dump(triangle()))
    write(out, "deep_20000.gltf", dump(deep(20000)))
    write(out, "deep_1001.gltf", dump(deep(1001)))
    write(out, "nested_json.gltf", '{"asset": {"version": "2.0"}, "extras": ' +
          "[" * 100000 + "]" * 100000 + "}")
    t = triangle()
    t["nodes"][0]["children"] = [0]
    write(out, "self_child.gltf", dump(t))
    t = triangle()
    t["nodes"] = [{"children": [1], "mesh": 0}, {"children": [0]}]
    write(out, "cycle.gltf", dump(t))
    t = triangle()
    t["nodes"][0]["mesh"] = 7
    write(out, "mesh_index_out_of_range.gltf", dump(t))
    t = triangle()
    t["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99
    write(out, "accessor_index_out_of_range.gltf", dump(t))
    t = triangle()
    t["accessors"][0]["count"] = 1000000
    write(out, "accessor_past_view.gltf", dump(t))
    t = triangle()
    t["bufferViews"][1]["byteLength"] = 1 << 31
    write(out, "view_past_buffer.gltf", dump(t))
    write(out, "vertex_index_out_of_range.gltf", dump(triangle((0, 1, 60000))))
    # Found by memograph_gltf_fuzzer: a negative offset reached an unsigned conversion.
    t = triangle()
    t["bufferViews"][1]["byteOffset"] = -36
    write(out, "negative_view_offset.gltf", dump(t))
    t = triangle()
    t["bufferViews"][1]["byteStride"] = 0
    write(out, "zero_stride.gltf", dump(t))
    t = triangle()
    t["scenes"][0]["nodes"] = [5]
    write(out, "scene_node_out_of_range.gltf", dump(t))
    write(out, "camera_zero_scale.gltf", dump(with_camera(triangle(), {"scale": [0, 0, 0]})))
    write(out, "camera_zero_rotation.gltf",
          dump(with_camera(triangle(), {"rotation": [0, 0, 0, 0]})))
    write(out, "camera_singular_matrix.gltf",
          dump(with_camera(triangle(), {"matrix": [0] * 16, "translation": None})))
    write(out, "not_json.gltf", "{ this is not json")
    write(out, "empty.gltf", "")
    write(out, "array_root.gltf", "[]")
    valid_json = dump(triangle()).encode()
    # A .glb whose buffer is its BIN chunk.
    t = triangle()
    data = base64.b64decode(t["buffers"][0]["uri"].split(",")[1])
    del t["buffers"][0]["uri"]
    write(out, "valid.glb", glb(dump(t).encode(),
                                extra=struct.pack("<II", len(data), 0x004E4942) + data))
    t = triangle((0, 1, 2, 0, 1, 60000))
    write(out, "one_face_out_of_range.gltf", dump(t))
    write(out, "glb_4gib_chunk.glb", glb(valid_json, declared_json=0xFFFFFFF0))
    write(out, "glb_4gib_total.glb", glb(valid_json, declared_total=0xFFFFFFFF))
    write(out, "glb_bin_chunk_too_long.glb",
          glb(valid_json, extra=struct.pack("<II", 0xFFFFFF00, 0x004E4942) + b"\0" * 8))
    write(out, "glb_version_1.glb", b"glTF" + struct.pack("<II", 1, 20) + b"\0" * 8)
    write(out, "glb_truncated.glb", b"glTF\x02\x00")
    write(out, "obj_index_out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n")
    write(out, "obj_garbage.obj", "\x00\x01\x02garbage\nf a b c\n")
    write(out, "obj_empty.obj", "")


if __name__ == "__main__":
    main(sys.argv[1])
