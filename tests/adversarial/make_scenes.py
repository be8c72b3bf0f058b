#!/usr/bin/env python3
"""Writes the adversarial scene files (glTF, glb, OBJ) into a folder.

They are generated rather than committed because some are large (a 20,000-deep node
hierarchy) and all are variations of one valid triangle; `valid*.gltf` are the controls.
Scenes with an external buffer have a `.bin` file of the same name beside them.
Usage: make_scenes.py OUT_DIR
       make_scenes.py --fuzz-seeds OUT_DIR   (seeds for the glTF fuzzers, docs/design/testing.md)
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


def external(gltf, uri):
    """The glTF with its buffer moved to the file `uri`; returns (gltf, the buffer's bytes)."""
    buffer = gltf["buffers"][0]
    data = base64.b64decode(buffer["uri"].split(",")[1])
    buffer["uri"] = uri
    return gltf, data


def rich():
    """A valid scene reaching more of the importer: two primitives (one with normals, UVs,
    tangents and vertex colours), materials, a camera under a parent node's TRS, a
    matrix node and KHR_lights_punctual point, spot and directional lights."""
    positions = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0)
    normals = struct.pack("<12f", *([0, 0, 1] * 4))
    uvs = struct.pack("<8f", 0, 0, 1, 0, 1, 1, 0, 1)
    tangents = struct.pack("<16f", *([1, 0, 0, 1] * 4))
    colors = struct.pack("<16f", *([1, 0.5, 0.25, 1] * 4))
    indices = struct.pack("<6H", 0, 1, 2, 0, 2, 3) + struct.pack("<3I", 0, 1, 2)
    parts = [positions, normals, uvs, tangents, colors, indices[:12], indices[12:]]
    views, offset = [], 0
    for part in parts:
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(part)})
        offset += len(part)
    data = b"".join(parts)

    def acc(view, component, count, kind, **extra):
        a = {"bufferView": view, "componentType": component, "count": count, "type": kind}
        a.update(extra)
        return a

    return {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 0.9, 0.8], "intensity": 20},
            {"type": "spot", "intensity": 5, "spot": {"innerConeAngle": 0.2,
                                                      "outerConeAngle": 0.6}},
            {"type": "directional", "intensity": 2}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 3, 4]}],
        "nodes": [
            {"mesh": 0, "children": [1, 2], "translation": [0, 0, -1]},
            {"mesh": 1, "scale": [0.5, 0.5, 0.5], "rotation": [0, 0.38268343, 0, 0.92387953]},
            {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 0]},
            {"camera": 0, "translation": [0.5, 0.5, 3], "children": [5]},
            {"extensions": {"KHR_lights_punctual": {"light": 2}},
             "matrix": [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 3, 0, 1]},
            {"extensions": {"KHR_lights_punctual": {"light": 1}}},
        ],
        "cameras": [{"type": "perspective",
                     "perspective": {"yfov": 0.7, "znear": 0.05, "zfar": 100,
                                     "aspectRatio": 1.5}}],
        "materials": [{"name": "Painted", "pbrMetallicRoughness": {
                           "baseColorFactor": [0.8, 0.2, 0.2, 1], "baseColorTexture": {"index": 0}}},
                      {"name": "Plain/with:separators"}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729}],
        "images": [{"uri": "painted.png"}],
        "meshes": [
            {"name": "quad", "primitives": [{"attributes": {
                "POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3, "COLOR_0": 4},
                "indices": 5, "material": 0}]},
            {"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 6,
                                            "material": 1, "mode": 4}]},
        ],
        "accessors": [
            acc(0, 5126, 4, "VEC3", min=[0, 0, 0], max=[1, 1, 0]),
            acc(1, 5126, 4, "VEC3"),
            acc(2, 5126, 4, "VEC2"),
            acc(3, 5126, 4, "VEC4"),
            acc(4, 5126, 4, "VEC4"),
            acc(5, 5123, 6, "SCALAR"),
            acc(6, 5125, 3, "SCALAR"),
        ],
        "bufferViews": views,
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," +
                            base64.b64encode(data).decode()}],
    }


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
    # Found by memograph_gltf_import_fuzzer: a componentType beyond int's range reached a
    # conversion to int (UBSan).
    t = triangle()
    t["accessors"][1]["componentType"] = 5.2e92
    write(out, "huge_component_type.gltf", dump(t))
    # Found by memograph_gltf_import_fuzzer: assimp 5.2 leaks the decoded buffer when base64
    # data holds a byte over 127, and a data: header over 127 characters wraps its offset.
    t = triangle()
    uri = t["buffers"][0]["uri"]
    t["buffers"][0]["uri"] = uri[:-9] + "\u00ff" + uri[-7:]  # two UTF-8 bytes for two
    write(out, "base64_not_ascii.gltf", dump(t))
    t = triangle()
    t["buffers"][0]["uri"] = t["buffers"][0]["uri"][:-1]  # 59 characters: not groups of 4
    write(out, "base64_length.gltf", dump(t))
    t = triangle()
    t["buffers"][0]["uri"] = t["buffers"][0]["uri"].replace(";base64", ";x=" + "y" * 200 + ";base64")
    write(out, "data_uri_long_header.gltf", dump(t))
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
    # External buffers (a .bin beside the glTF): index values are checked there too, and a
    # missing, short or absolutely named file is an error naming it.
    t, data = external(triangle(), "valid_external.bin")
    write(out, "valid_external.gltf", dump(t))
    write(out, "valid_external.bin", data)
    t, data = external(triangle((0, 1, 60000)), "external_index_out_of_range.bin")
    write(out, "external_index_out_of_range.gltf", dump(t))
    write(out, "external_index_out_of_range.bin", data)
    t, _ = external(triangle(), "missing.bin")
    write(out, "external_missing_buffer.gltf", dump(t))
    t, data = external(triangle(), "external_short_buffer.bin")
    write(out, "external_short_buffer.gltf", dump(t))
    write(out, "external_short_buffer.bin", data[:20])
    t, _ = external(triangle(), "/etc/passwd")
    write(out, "external_absolute_uri.gltf", dump(t))
    write(out, "valid_rich.gltf", dump(rich()))
    write(out, "obj_index_out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n")
    write(out, "obj_garbage.obj", "\x00\x01\x02garbage\nf a b c\n")
    write(out, "obj_empty.obj", "")


def fuzz_seeds(out):
    """The glTF and glb scenes above as fuzzer inputs: one byte first (0: .gltf, 1: .glb),
    scenes over 64 KiB left out. gltf_import_fuzzer.cpp keeps a valid triangle buffer
    named fuzz.bin beside its input: external buffers are renamed to it, and each glTF
    scene is also seeded as a .glb with its buffer in the BIN chunk."""
    import tempfile
    with tempfile.TemporaryDirectory() as scenes:
        main(scenes)
        os.makedirs(out, exist_ok=True)
        for name in sorted(os.listdir(scenes)):
            with open(os.path.join(scenes, name), "rb") as f:
                content = f.read()
            if len(content) > 65536 or not name.endswith((".gltf", ".glb")):
                continue
            glb_file = name.endswith(".glb")
            if not glb_file:
                try:
                    gltf = json.loads(content)
                except ValueError:
                    gltf = None
                if isinstance(gltf, dict):
                    for buffer in gltf.get("buffers", []):
                        if "uri" in buffer and not buffer["uri"].startswith(("data:", "/")):
                            buffer["uri"] = "fuzz.bin"
                    content = json.dumps(gltf).encode()
                    buffers = gltf.get("buffers", [])
                    if buffers and buffers[0].get("uri", "").startswith("data:"):
                        try:
                            data = base64.b64decode(buffers[0]["uri"].split(",", 1)[1])
                        except ValueError:  # the scenes with broken base64
                            data = b""
                        del buffers[0]["uri"]
                        data += b"\0" * (-len(data) % 4)
                        write(out, name[:-5] + "_bin.seed", b"\1" + glb(
                            json.dumps(gltf).encode(),
                            extra=struct.pack("<II", len(data), 0x004E4942) + data))
            write(out, name.replace(".", "_") + ".seed", (b"\1" if glb_file else b"\0") + content)


if __name__ == "__main__":
    if sys.argv[1] == "--fuzz-seeds":
        fuzz_seeds(sys.argv[2])
    else:
        main(sys.argv[1])
