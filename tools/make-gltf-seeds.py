#!/usr/bin/env python3
"""Writes the small hand-made glTF seeds of fuzz/seeds/gltf/ (tools/fuzz.sh
adds the assimp test models and ../shared's bunny.glb to the corpus by path).

    tools/make-gltf-seeds.py [FOLDER]     (default: fuzz/seeds/gltf)
"""
import base64, json, os, struct, sys

folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "fuzz", "seeds", "gltf")
os.makedirs(folder, exist_ok=True)


def pack(fmt, values):
    return b"".join(struct.pack("<" + fmt, *v) if isinstance(v, tuple) else struct.pack("<" + fmt, v) for v in values)


def pad4(b, fill=b"\0"):
    return b + fill * (-len(b) % 4)


def model(blob, accessors, views, primitive, extra=None):
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
           "nodes": [{"mesh": 0}], "meshes": [{"primitives": [primitive]}],
           "buffers": [{"byteLength": len(blob)}], "bufferViews": views, "accessors": accessors}
    for k, v in (extra or {}).items():
        doc[k] = v
    return doc


def write_gltf(name, doc, blob):
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
    with open(os.path.join(folder, name + ".gltf"), "w") as f:
        json.dump(doc, f, separators=(",", ":"))


def write_glb(name, doc, blob):
    js = pad4(json.dumps(doc, separators=(",", ":")).encode(), b" ")
    bin_ = pad4(blob)
    out = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(bin_))
    out += struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(bin_), 0x004E4942) + bin_
    with open(os.path.join(folder, name + ".glb"), "wb") as f:
        f.write(out)


quad = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
normals = [(0.0, 0.0, 1.0)] * 4
uvs = [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)]
indices = [0, 1, 2, 0, 2, 3]

# Indexed quad with normals and uvs, a pbr material, as .gltf and .glb.
blob = pack("fff", quad) + pack("fff", normals) + pack("ff", uvs) + pack("H", indices)
views = [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
         {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}]
accessors = [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
             {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
             {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
             {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"}]
prim = {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}
materials = {"materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1], "metallicFactor": 0.5,
                                                      "roughnessFactor": 0.3},
                            "emissiveFactor": [0.1, 0, 0],
                            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2},
                                           "KHR_materials_ior": {"ior": 1.4}}}],
             "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_materials_ior"]}
doc = model(blob, accessors, views, prim, materials)
write_gltf("quad-indexed", json.loads(json.dumps(doc)), blob)
write_glb("quad-indexed", doc, blob)

# Without indices, interleaved (byteStride), a node tree with TRS and a
# mirroring matrix, a point light and a camera.
tris = [quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]]
blob = b"".join(struct.pack("<6f", *p, 0.0, 0.0, 1.0) for p in tris)
doc = model(blob, [{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3"},
                   {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 6, "type": "VEC3"}],
            [{"buffer": 0, "byteLength": len(blob), "byteStride": 24}],
            {"attributes": {"POSITION": 0, "NORMAL": 1}})
doc["scenes"] = [{"nodes": [0, 2]}]
doc["nodes"] = [{"translation": [1, 0, 0], "rotation": [0, 0.7071068, 0, 0.7071068], "scale": [2, 2, 2], "children": [1]},
                {"mesh": 0, "matrix": [-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5, 0, 0, 1]},
                {"translation": [0, 2, 5], "camera": 0, "children": [3]},
                {"extensions": {"KHR_lights_punctual": {"light": 0}}}]
doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.1}}]
doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0.9, 0.8], "intensity": 683}]}}
doc["extensionsUsed"] = ["KHR_lights_punctual"]
write_gltf("tree-light-camera", doc, blob)

# KHR_mesh_quantization: positions as normalized shorts, uvs as unsigned bytes.
pos = pack("hhhh", [(0, 0, 0, 0), (32767, 0, 0, 0), (32767, 32767, 0, 0), (0, 32767, 0, 0)])
tex = pack("BBBB", [(0, 255, 0, 0), (255, 255, 0, 0), (255, 0, 0, 0), (0, 0, 0, 0)])
blob = pos + tex + pack("B", indices) + b"\0\0"
doc = model(blob, [{"bufferView": 0, "componentType": 5122, "normalized": True, "count": 4, "type": "VEC3"},
                   {"bufferView": 1, "componentType": 5121, "normalized": True, "count": 4, "type": "VEC2"},
                   {"bufferView": 2, "componentType": 5121, "count": 6, "type": "SCALAR"}],
            [{"buffer": 0, "byteOffset": 0, "byteLength": 32, "byteStride": 8},
             {"buffer": 0, "byteOffset": 32, "byteLength": 16, "byteStride": 4},
             {"buffer": 0, "byteOffset": 48, "byteLength": 6}],
            {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2})
doc["extensionsUsed"] = doc["extensionsRequired"] = ["KHR_mesh_quantization"]
write_glb("quantized", doc, blob)
