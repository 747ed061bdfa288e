#!/usr/bin/env python3
"""Writes the small hostile inputs of docs/robustness.md's bad-input table (and the fuzzers'
seeds): run from anywhere, it regenerates tests/bad_inputs/ and fuzz/assets/ + fuzz/seeds/.

Layout: tests/bad_inputs/scenes/ is "the scene's folder"; outside.* lie just outside it."""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SCENES = os.path.join(HERE, "scenes")


def png(width, height, bit_depth=8, pixels=None, idat=True):
    """A PNG (RGB). pixels: rows of (r, g, b) ints; idat=False writes a header that claims the
    size followed by one tiny IDAT (a single row's worth): a header that lies."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, 2, 0, 0, 0)
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr)
    if idat:
        raw = b""
        for row in pixels:
            raw += b"\x00"
            for r, g, b in row:
                raw += struct.pack(">HHH", r, g, b) if bit_depth == 16 else bytes((r, g, b))
        out += chunk(b"IDAT", zlib.compress(raw))
    else:
        out += chunk(b"IDAT", zlib.compress(b"\x00" * 64))
    return out + chunk(b"IEND", b"")


TRIANGLE = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)  # glTF: a triangle in the X-Y plane
UV3 = struct.pack("<6f", 0, 0, 1, 0, 0, 1)


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(path, mode) as f:
        f.write(data)


def symlink(target, path):
    if os.path.lexists(path):
        os.remove(path)
    os.symlink(target, path)


def data_uri(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def gltf(buffer_uri=None, buffer=TRIANGLE + UV3, accessors=None, image_uri=None, nodes=None, extra=None):
    """A one-triangle glTF; every argument bends one part of it."""
    doc = {
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}],
        "nodes": nodes or [{"name": "tri", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "buffers": [{"byteLength": len(buffer), "uri": buffer_uri or data_uri(buffer)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
        "accessors": accessors or [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}],
        "materials": [{"name": "m", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.2, 1]}}],
    }
    if image_uri:
        doc["images"] = [{"uri": image_uri}]
        doc["textures"] = [{"source": 0}]
        doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    if extra:
        extra(doc)
    return json.dumps(doc, indent=1) + "\n"


def scene(objects, materials=None, **top):
    doc = {"format": "omnicam-scene/1",
           "materials": materials or {"grey": {"color": 0.5}},
           "objects": objects}
    doc.update(top)
    return json.dumps(doc, indent=1) + "\n"


FLOOR = {"type": "quad", "material": "grey", "origin": [-2, -2, 0], "edge_u": [4, 0, 0], "edge_v": [0, 4, 0]}


def main():
    tex = png(2, 2, 8, [[(255, 0, 0), (0, 255, 0)], [(0, 0, 255), (255, 255, 255)]])
    write(os.path.join(HERE, "outside.bin"), TRIANGLE + UV3)
    write(os.path.join(HERE, "outside.png"), tex)
    write(os.path.join(SCENES, "triangle.bin"), TRIANGLE + UV3)
    write(os.path.join(SCENES, "tex.png"), tex)
    write(os.path.join(SCENES, "huge_1e6.png"), png(1000000, 1000000, idat=False))
    write(os.path.join(SCENES, "huge_30000.png"), png(30000, 30000, idat=False))
    write(os.path.join(SCENES, "truncated.png"), tex[:60])  # valid header, pixel data cut off
    corrupt = bytearray(tex)
    corrupt[45] ^= 0xFF  # inside the compressed pixel data
    write(os.path.join(SCENES, "corrupt.png"), bytes(corrupt))
    symlink("../outside.bin", os.path.join(SCENES, "link_outside.bin"))
    symlink("../outside.png", os.path.join(SCENES, "link_outside.png"))

    cases = {
        "ok": gltf("triangle.bin"),
        "buffer_outside": gltf("../outside.bin"),
        "buffer_passwd": gltf("/etc/passwd"),
        "buffer_symlink": gltf("link_outside.bin"),
        "image_outside": gltf(image_uri="../outside.png"),
        "image_huge": gltf(image_uri="huge_30000.png"),
        "short_uv": gltf(accessors=[
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC2"}]),
        "no_bufferview": gltf(accessors=[
            {"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]),
        "byte_positions": gltf(accessors=[
            {"bufferView": 0, "componentType": 5121, "count": 3, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]),
        "uv_not_normalized": gltf(accessors=[
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5121, "count": 3, "type": "VEC2"}]),
        "count_past_view": gltf(accessors=[
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]),
        "node_cycle": gltf(nodes=[{"name": "a", "mesh": 0, "children": [1]}, {"name": "b", "children": [0]}]),
        "bad_texture_index": gltf(extra=lambda d: d["materials"][0]["pbrMetallicRoughness"].update(
            {"baseColorTexture": {"index": 7}})),
        # Every JSON input: bounded depth (tinygltf walks extras recursively), no key twice.
        "deep_extras": gltf().rstrip()[:-1] + ', "extras": ' + "[" * 1000 + "]" * 1000 + "}\n",
        "duplicate_key": gltf().replace('"asset": {', '"asset": {"version": "2.0"}, "asset": {', 1),
        # A NaN in the second coordinate of a UV (a check by the largest of |u|, |v| let it pass).
        "uv_nan_v": gltf(buffer=TRIANGLE + struct.pack("<6f", 0, 0, 1, float("nan"), 0, 1)),
    }
    for name, text in cases.items():
        write(os.path.join(SCENES, "arena_" + name + ".gltf"), text)
        write(os.path.join(SCENES, "gltf_" + name + ".json"),
              scene([FLOOR, {"type": "gltf", "name": "arena", "file": "arena_" + name + ".gltf"}]))
    # A .glb that is a .gltf's JSON: not binary glTF.
    write(os.path.join(SCENES, "arena_json.glb"), gltf())
    write(os.path.join(SCENES, "gltf_not_binary.json"),
          scene([FLOOR, {"type": "gltf", "name": "arena", "file": "arena_json.glb"}]))

    def textured(file):
        return scene([FLOOR], {"grey": {"color": 0.5, "texture": {"file": file}}})
    write(os.path.join(SCENES, "texture_outside.json"), textured("../outside.png"))
    write(os.path.join(SCENES, "texture_folder.json"), textured("."))
    write(os.path.join(SCENES, "texture_symlink.json"), textured("link_outside.png"))
    write(os.path.join(SCENES, "texture_absolute.json"), textured("/etc/passwd"))
    write(os.path.join(SCENES, "texture_huge_1e6.json"), textured("huge_1e6.png"))
    write(os.path.join(SCENES, "texture_huge_30000.json"), textured("huge_30000.png"))
    write(os.path.join(SCENES, "texture_corrupt.json"), textured("corrupt.png"))
    # Radiance is not an albedo: a Radiance HDR whose every texel is 2 (RGBE 128 128 128 130).
    write(os.path.join(SCENES, "radiance_2.hdr"),
          b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n" + bytes([128, 128, 128, 130]) * 32)
    write(os.path.join(SCENES, "texture_radiance.json"), textured("radiance_2.hdr"))
    # Repeats beyond float texture coordinates' reach (the engines would round them apart).
    write(os.path.join(SCENES, "texture_scale_huge.json"),
          scene([FLOOR], {"grey": {"color": 0.5, "texture": {"file": "tex.png", "scale": [1e12, 1]}}}))

    # Lit-shading factors and mesh texture coordinates beyond what a float product or a float UV holds.
    write(os.path.join(SCENES, "ambient_huge.json"), scene([FLOOR], {"grey": {"color": 0.5, "ambient": 1e39}}))
    write(os.path.join(SCENES, "mesh_uv_huge.json"),
          scene([{"type": "mesh", "material": "grey", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                  "triangles": [[0, 1, 2]], "uvs": [[0, 0], [1e300, 0], [0, 1]]}]))

    ball = {"type": "sphere", "material": "grey", "center": [1, 0, 0.2], "radius": 0.1}
    write(os.path.join(SCENES, "radius_1e400.json"),
          scene([FLOOR, dict(ball, radius=0.1)]).replace('"radius": 0.1', '"radius": 1e400'))
    write(os.path.join(SCENES, "coordinate_1e20.json"), scene([FLOOR, dict(ball, center=[1e20, 0, 0])]))
    # Emission: one range, [0, 1e6], and one message for either side of it (issue #45).
    write(os.path.join(SCENES, "emission_2e6.json"), scene([FLOOR], {"grey": {"color": 0.5, "emission": [2e6, 1, 1]}}))
    write(os.path.join(SCENES, "emission_negative.json"), scene([FLOOR], {"grey": {"color": 0.5, "emission": -1}}))
    # The physical camera block (rig.camera): strict, bounded, and the pinhole stays below the mirror.
    write(os.path.join(SCENES, "camera_unknown_key.json"), scene([FLOOR], rig={"camera": {"tilt_deg": 1}}))
    write(os.path.join(SCENES, "camera_offset_two.json"), scene([FLOOR], rig={"camera": {"offset_mm": [1, 2]}}))
    write(os.path.join(SCENES, "camera_rotation_huge.json"), scene([FLOOR], rig={"camera": {"rotation_deg": [0, 45, 0]}}))
    write(os.path.join(SCENES, "camera_inside_mirror.json"), scene([FLOOR], rig={"camera": {"offset_mm": [0, 0, 40]}}))
    write(os.path.join(SCENES, "camera_distortion_nan.json"),
          scene([FLOOR], rig={"camera": {"distortion": {"k1": "x"}}}))
    write(os.path.join(SCENES, "mirror_shape_unknown.json"), scene([FLOOR], rig={"mirror": {"shape": "ellipsoid\n"}}))
    sphere = {"shape": "sphere", "radius": 0.03, "camera_distance_m": 0.12}
    write(os.path.join(SCENES, "sphere_with_k.json"), scene([FLOOR], rig={"mirror": dict(sphere, k=11)}))
    write(os.path.join(SCENES, "sphere_no_camera.json"),
          scene([FLOOR], rig={"mirror": {"shape": "sphere", "radius": 0.03}}))
    write(os.path.join(SCENES, "sphere_camera_inside.json"),
          scene([FLOOR], rig={"mirror": dict(sphere, camera_distance_m=0.02)}))
    write(os.path.join(SCENES, "sphere_without_shape.json"),
          scene([FLOOR], rig={"mirror": {"radius": 0.03, "camera_distance_m": 0.12}}))
    write(os.path.join(SCENES, "sphere_rim_hidden.json"),
          scene([FLOOR], rig={"mirror": dict(sphere, cap_angle_deg=90)}))
    write(os.path.join(SCENES, "paraboloid_framing.json"),
          scene([FLOOR], rig={"mirror": {"shape": "paraboloid", "h": 0.02}, "image": {"framing_elevation_deg": 30}}))
    write(os.path.join(SCENES, "cone.json"),
          scene([FLOOR], rig={"mirror": {"shape": "cone", "rim_radius": 0.03, "camera_distance_m": 0.05}}))
    write(os.path.join(SCENES, "camera_away.json"), scene([FLOOR], rig={"camera": {"offset_mm": [100, 0, 0]}}))
    write(os.path.join(SCENES, "camera_misaligned.json"),
          scene([FLOOR], rig={"camera": {"offset_mm": [2, 0, 0], "distortion": {"k1": -0.05}}}))
    # The shutter (rig.shutter, docs/motion.md): strict and bounded.
    write(os.path.join(SCENES, "shutter_readout.json"),
          scene([FLOOR], rig={"shutter": {"exposure_s": 0.01, "rolling": {"line_time_us": 30, "readout": "diagonal"}}}))
    write(os.path.join(SCENES, "shutter_negative.json"), scene([FLOOR], rig={"shutter": {"exposure_s": -0.01}}))
    write(os.path.join(SCENES, "shutter_no_line_time.json"), scene([FLOOR], rig={"shutter": {"rolling": {}}}))
    write(os.path.join(SCENES, "shutter_time_samples.json"), scene([FLOOR], rig={"shutter": {"exposure_s": 0.01, "time_samples": 1000}}))
    write(os.path.join(SCENES, "shutter_rolling.json"),
          scene([FLOOR], rig={"shutter": {"exposure_s": 0.01, "rolling": {"line_time_us": 30}}}))
    write(os.path.join(SCENES, "shutter_unknown_key.json"), scene([FLOOR], rig={"shutter": {"iso": 100}}))
    write(os.path.join(SCENES, "shutter_line_time.json"),
          scene([FLOOR], rig={"shutter": {"exposure_s": 0.01, "rolling": {"line_time": 30}}}))
    # A global shutter open while the robot moves, seen at 8 instants: POV-Ray renders each.
    write(os.path.join(SCENES, "shutter_eight_instants.json"), scene([FLOOR], rig={"shutter": {"exposure_s": 0.01, "time_samples": 8}}))
    write(os.path.join(SCENES, "tilt_too_far.json"), scene([FLOOR], rig={"tilt_deg": [40, 0]}))
    # Lens cameras (rig.lens, docs/lens-cameras.md): each model takes only its own fields, range-checked.
    kb = {"model": "kannala_brandt", "width": 64, "height": 48, "fx": 20, "fy": 20}
    write(os.path.join(SCENES, "lens_unknown_model.json"), scene([FLOOR], rig={"lens": dict(kb, model="fisheye\n")}))
    write(os.path.join(SCENES, "lens_foreign_field.json"), scene([FLOOR], rig={"lens": dict(kb, xi=0.5)}))
    write(os.path.join(SCENES, "lens_and_mirror.json"), scene([FLOOR], rig={"lens": kb, "mirror": {"k": 11}}))
    write(os.path.join(SCENES, "lens_folding.json"), scene([FLOOR], rig={"lens": dict(kb, k=[-0.5, 0, 0, 0], max_theta_deg=120)}))
    write(os.path.join(SCENES, "lens_sees_nothing.json"),
          scene([FLOOR], rig={"lens": {"model": "fisheye_equisolid", "width": 64, "height": 64, "f_px": 1, "fov_deg": 180, "cx": -60}}))
    write(os.path.join(SCENES, "lens_alpha_one.json"),
          scene([FLOOR], rig={"lens": {"model": "double_sphere", "width": 64, "height": 64, "fx": 20, "fy": 20, "xi": 0.1, "alpha": 1}}))
    write(os.path.join(SCENES, "lens_kb_povray.json"), scene([FLOOR], rig={"lens": kb}))
    # 160 x 120 keeps its aspect only at widths that are multiples of 4 (--size 161 cannot).
    write(os.path.join(SCENES, "lens_160x120.json"),
          scene([FLOOR], rig={"lens": {"model": "fisheye_equidistant", "width": 160, "height": 120, "f_px": 50, "fov_deg": 180}}))
    write(os.path.join(SCENES, "duplicate_object.json"), scene([dict(FLOOR, name="wall"), dict(ball, name="wall")]))
    write(os.path.join(SCENES, "light_shares_name.json"),
          scene([dict(FLOOR, name="lamp")], lights=[{"name": "lamp", "position": [0, 0, 2]}]))
    write(os.path.join(SCENES, "duplicate_light.json"),
          scene([FLOOR], lights=[{"name": "l", "position": [0, 0, 2]}, {"name": "l", "position": [1, 0, 2]}]))
    write(os.path.join(SCENES, "long_name.json"), scene([dict(FLOOR, name="x" * 64)]))
    # Names that would break a one-line message if echoed raw: newlines, quotes, control bytes.
    long_material = 'line1\n"quoted"\n'
    long_material += "x" * (300 - len(long_material))
    write(os.path.join(SCENES, "long_material_name.json"),
          scene([FLOOR], {"grey": {"color": 0.5}, long_material: {"color": 0.2}}))
    write(os.path.join(SCENES, "control_name.json"), scene([dict(FLOOR, name="bad\tname\x01")]))
    write(os.path.join(SCENES, "duplicate_material_key.json"),
          '{"format": "omnicam-scene/1", "materials": {"grey": {"color": 0.5}, "grey": {"color": 0.9}},\n'
          ' "objects": [' + json.dumps(FLOOR) + ']}\n')
    for name, rig in {"rig_c_tiny": {"mirror": {"c": 1e-12}}, "rig_c_huge": {"mirror": {"c": 1e6}},
                      "rig_k_huge": {"mirror": {"k": 1e9}}, "rig_height_huge": {"height": 1e9},
                      "rig_k_asymptote": {"mirror": {"k": 4}}}.items():
        write(os.path.join(SCENES, name + ".json"), scene([FLOOR], rig=rig))
    # A user object whose name starts with omnicam_ must survive a glTF round trip.
    write(os.path.join(SCENES, "omnicam_prefix.json"),
          scene([FLOOR, dict(ball, name="omnicam_redbox")], start_pose=[0, 0, 0]))
    # A rig file (for `view --rig`), an image whose sidecar lies about its mirror, and a folder
    # whose name looks like an output file.
    write(os.path.join(HERE, "rig.json"), json.dumps({"height": 0.4, "mirror": {"k": 11.546, "c": 0.02321}}) + "\n")
    write(os.path.join(HERE, "lying_sidecar.png"), tex)
    write(os.path.join(HERE, "lying_sidecar.png.json"), json.dumps({"rig": {"mirror": {"k": 1.5}}}) + "\n")
    # An image whose sidecar states another camera than rig.json (which --rig must not override),
    # and a view's output.
    write(os.path.join(HERE, "with_sidecar.png"), tex)
    write(os.path.join(HERE, "with_sidecar.png.json"), json.dumps({"rig": {"mirror": {"k": 6}}}) + "\n")
    write(os.path.join(HERE, "a_view.png"), tex)
    write(os.path.join(HERE, "a_view.png.json"), json.dumps({"rig": {}, "view": {"kind": "panorama"}}) + "\n")
    write(os.path.join(HERE, "folder.png", "README"), "A folder named like an image: -o must refuse it.\n")

    # Fuzzing: assets a fuzzed scene may name, and seeds.
    assets = os.path.join(REPO, "fuzz", "assets")
    write(os.path.join(assets, "tex.png"), tex)
    write(os.path.join(assets, "triangle.bin"), TRIANGLE + UV3)
    write(os.path.join(assets, "arena.gltf"), gltf("triangle.bin", image_uri="tex.png"))
    seeds = os.path.join(REPO, "fuzz", "seeds")
    write(os.path.join(seeds, "scene_loader", "textured_gltf.json"),
          scene([FLOOR, {"type": "gltf", "name": "arena", "file": "arena.gltf"}],
                {"grey": {"color": 0.5, "texture": {"file": "tex.png", "scale": [2, 2]}}},
                rig={"height": 0.5, "mirror": {"k": 9, "c": 0.03, "rim_elevation_deg": 30}, "image": {"size": 64}},
                lights=[{"name": "l", "position": [0, 0, 2]}],
                landmarks=[{"name": "lm", "position": [1, 0, 0.3], "diameter": 0.1, "height": 0.1, "colour_class": "grey"}],
                paths=[{"name": "p", "waypoints": [[0, 0], [1, 0], [1, 1]], "frames": 5}, {"name": "q", "poses": [[0, 0, 0]]}]))
    write(os.path.join(seeds, "gltf_import", "textured.gltf"), gltf(image_uri="tex.png"))
    sidecar = {"engine": "fast", "rig": {"height": 0.4, "mirror": {"k": 11.546, "c": 0.02321, "rim_elevation_deg": 45},
                                         "image": {"size": 360, "framing_elevation_deg": 45}}, "pose": {"x": 0, "y": 0, "yaw_deg": 0}}
    write(os.path.join(seeds, "sidecar", "render.png.json"), json.dumps(sidecar, indent=1) + "\n")
    write(os.path.join(seeds, "sidecar", "rig_only.json"), json.dumps({"rig": {"height": 1.0}}) + "\n")

    # Inputs that crashed omnicam or ended in exit 4 (an internal error) before the readers were
    # hardened: each must now be an orderly InputError (fuzz_regression_test).
    regressions = os.path.join(REPO, "fuzz", "regressions")
    for name in ("no_bufferview", "node_cycle", "bad_texture_index", "short_uv", "count_past_view", "byte_positions"):
        write(os.path.join(regressions, "gltf_import", name + ".gltf"), cases[name])
    write(os.path.join(regressions, "gltf_import", "base_color_factor_short.gltf"),
          gltf(extra=lambda d: d["materials"][0]["pbrMetallicRoughness"].update({"baseColorFactor": [0.5]})))
    write(os.path.join(regressions, "gltf_import", "mesh_index_out_of_range.gltf"),
          gltf(nodes=[{"name": "tri", "mesh": 5}]))
    write(os.path.join(regressions, "gltf_import", "material_out_of_range.gltf"),
          gltf(extra=lambda d: d["meshes"][0]["primitives"][0].update({"material": 9})))
    write(os.path.join(regressions, "scene_loader", "radius_1e400.json"),
          scene([FLOOR, dict(ball, radius=0.1)]).replace('"radius": 0.1', '"radius": 1e400'))
    write(os.path.join(regressions, "scene_loader", "pose_1e20.json"), scene([FLOOR], start_pose=[1e20, 0, 0]))
    write(os.path.join(regressions, "sidecar", "rig_k_1e9.json"), json.dumps({"rig": {"mirror": {"k": 1e9}}}) + "\n")
    write(os.path.join(regressions, "sidecar", "rig_wrong_type.json"), json.dumps({"rig": {"mirror": "k"}}) + "\n")

    # Dataset specs (docs/dataset-format.md) over a scene of this folder.
    datasets = os.path.join(HERE, "datasets")
    write(os.path.join(datasets, "box.json"),
          scene([FLOOR, {"type": "box", "material": "grey", "center": [0, 0, 0.5], "size": [4, 4, 1]}],
                paths=[{"name": "p", "poses": [[0, 0, 0]]}]))

    def dataset_spec(name, **fields):
        doc = {"format": "omnicam-dataset/1", "scene": "box.json", "poses": {"path": "p"}}
        doc.update(fields)
        write(os.path.join(datasets, name + ".json"), json.dumps(doc, indent=1) + "\n")
    dataset_spec("spp_3", spp=3)
    dataset_spec("camera_dotdot", cameras=[{"name": "../x"}])
    dataset_spec("camera_newline", cameras=[{"name": "cam\nzero"}])
    dataset_spec("unknown_output", outputs={"depht": True})
    dataset_spec("crowded", poses={"random": {"count": 5, "seed": 1, "region": [-1, -1, 1, 1], "clearance": 0.2}})
    dataset_spec("no_scene", scene="missing.json")
    dataset_spec("no_path", poses={"path": "nowhere"})
    dataset_spec("povray_mode", engine="povray", mode="cubemap")
    dataset_spec("camera_rig", cameras=[{"name": "c", "rig": {"height": -1}}])
    dataset_spec("camera_misaligned", mode="cubemap", cameras=[{"name": "c", "rig": {"camera": {"offset_mm": [1, 0, 0]}}}])
    dataset_spec("recording_jpeg", recording={"jpeg_quality": 150})
    # The recording camera's stages and distributions (docs/experiments.md).
    dataset_spec("recording_stage", recording={"sharpening": 1.0})
    dataset_spec("recording_distribution", recording={"exposure_ev": {"normal": [0, 1]}})
    dataset_spec("recording_lo_hi", recording={"read_noise": {"uniform": [0.02, 0.01]}})
    dataset_spec("recording_nan", recording={"exposure_ev": float("nan")})
    dataset_spec("recording_domain", recording={"vignetting": {"uniform": [0.5, 2]}})
    dataset_spec("recording_bayer", recording={"bayer": "rgbb"})
    dataset_spec("recording_log_zero", recording={"full_well_electrons": {"log_uniform": [0, 1000]}})
    dataset_spec("recording_preset", recording={"preset": "dslr"})
    dataset_spec("recording_gamma_unused", recording={"preset": "phone", "gamma": 2.0})
    dataset_spec("recording_kernel_unblurred", recording={"blur_kernel": "disc", "blur_radius_px": 0})
    dataset_spec("one_frame")  # a good spec of one frame (box.json's path)
    dataset_spec("scene_folder", scene="../datasets")
    dataset_spec("seed_past_64_bits", shading="path", seed=18446744073709551617)
    write(os.path.join(datasets, "test_camera_bayer.json"), json.dumps({"bayer": {"choice": ["rggb", "rgbb"]}}) + "\n")
    dataset_spec("coco_unknown_class", outputs={"coco": {"classes": ["victim"]}})
    dataset_spec("coco_classes_text", outputs={"coco": {"classes": "victim"}})
    dataset_spec("layout_unknown", layout="layers")
    dataset_spec("multilayer_png", layout="multilayer", outputs={"rgb": "png"})
    dataset_spec("files_compression", multilayer_compression="zip")
    # Time and shaking (docs/motion.md): timed waypoints, vibration, the EuRoC layout.
    dataset_spec("vibration_tilt", vibration={"seed": 1, "rig_tilt_deg": [20, 0]})
    # A live sensor renders each pose as it comes: a rocking robot too is refused (it was ignored).
    dataset_spec("vibration_robot_tilt", vibration={"seed": 1, "robot_tilt_deg": [1, 1]})
    dataset_spec("vibration_lens_offset", cameras=[{"name": "omni"}, {"name": "fisheye", "rig": {"lens": {
        "model": "fisheye_equidistant", "width": 32, "height": 32, "f_px": 9, "fov_deg": 190}}}],
                 vibration={"seed": 1, "camera_offset_mm": [1, 1, 1]})
    dataset_spec("vibration_pushed", cameras=[{"name": "c", "rig": {"tilt_deg": [29.9, 29.9]}}],
                 poses={"list": [[0, 0, 0], [0.1, 0, 0], [0.2, 0, 0], [0.3, 0, 0]]}, vibration={"seed": 1, "rig_tilt_deg": [5, 5]})
    dataset_spec("timestamps_backwards", poses={"list": [[0, 0, 0], [0.1, 0, 0]], "timestamps_s": [1, 0.5]})
    dataset_spec("speed_no_turn_rate", poses={"path": "p", "speed_m_s": 1})
    dataset_spec("euroc_exr", euroc=True, outputs={"rgb": "exr"})
    dataset_spec("motion_no_shutter", motion={"velocity": [1, 0, 90]})
    # A typo of a field its reader looks for is named as such, before "give exactly one of".
    dataset_spec("motion_typo", motion={"between_pose": True})
    dataset_spec("timestamps_typo", poses={"list": [[0, 0, 0], [0.1, 0, 0]], "timestamp_s": [0, 1]})
    # An output's value of the wrong type names every form it takes; the colour cannot be turned off.
    dataset_spec("coco_yes", outputs={"coco": "yes"})
    dataset_spec("rgb_false", outputs={"rgb": False})
    # A bundled scene's bare name in a spec elsewhere: where the spec looked, and omnicam's copy.
    dataset_spec("bundled_scene", scene="robocup2006.json")
    # Waypoints driven in time give the frames their motion: a refusal of it names timestamps_s.
    dataset_spec("timestamps_blender_rolling", engine="blender", poses={"list": [[0, 0, 0], [0.1, 0, 0]], "timestamps_s": [0, 1]},
                 cameras=[{"name": "c", "rig": {"shutter": {"exposure_s": 0.01, "rolling": {"line_time_us": 30}}}}])
    # A value just beyond its range is shown as it is, not rounded onto the limit.
    dataset_spec("interval_just_over_a_day", frame_interval_s=86400.001)
    # Calibration sequences (docs/calibration.md): the target, the still robot, the bag's images.
    still = {"list": [[0, 0, 0]]}
    board_poses = {"random": {"count": 5, "seed": 1}}
    dataset_spec("calibration_no_target", poses=still, calibration={"target": "board", "poses": board_poses})
    dataset_spec("calibration_path", calibration={"target": "board", "poses": board_poses})
    dataset_spec("calibration_bag_exr", poses=still, outputs={"rgb": "exr"},
                 calibration={"target": "board", "poses": board_poses, "rosbag": True})
    dataset_spec("calibration_axes", poses=still,
                 calibration={"target": "board", "poses": {"list": [{"origin": [1, 0, 0], "x_axis": [0, 1, 0], "y_axis": [0, 1, 0]}]}})
    # Kalibr's limits and the board's place: a grid starting at tag 5, a board at the mirror, one under the floor.
    grid = {"kind": "aprilgrid", "tag_rows": 3, "tag_columns": 3, "tag_size": 0.05, "tag_spacing": 0.3}
    write(os.path.join(datasets, "grids.json"), scene([
        FLOOR,
        {"name": "board", "type": "calibration_target", "pattern": grid, "origin": [1, 0, 0.5], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1]},
        {"name": "board5", "type": "calibration_target", "pattern": dict(grid, first_id=5),
         "origin": [-1, 0, 0.5], "x_axis": [0, -1, 0], "y_axis": [0, 0, 1]},
        {"name": "board2", "type": "calibration_target", "pattern": dict(grid, tag_columns=2),
         "origin": [0, 1, 0.5], "x_axis": [1, 0, 0], "y_axis": [0, 0, 1]}]))
    dataset_spec("calibration_first_id", scene="grids.json", poses=still, calibration={"target": "board5", "poses": board_poses})
    dataset_spec("calibration_two_columns", scene="grids.json", poses=still, calibration={"target": "board2", "poses": board_poses})
    dataset_spec("calibration_at_mirror", scene="grids.json", poses=still, calibration={"target": "board", "poses": {"random": {
        "count": 5, "seed": 1, "distance_m": [0.01, 0.02], "max_tilt_deg": 80, "min_seen_corners": 4}}})
    dataset_spec("calibration_bag_panorama", scene="grids.json", poses=still, cameras=[
        {"name": "omni"}, {"name": "pano", "rig": {"lens": {"model": "equirectangular", "width": 32, "height": 16}}}],
                 calibration={"target": "board", "poses": board_poses, "rosbag": True})
    dataset_spec("calibration_into_mirror", scene="grids.json", poses=still, calibration={"target": "board", "poses": {"list": [
        {"origin": [0.04, -0.04, 0], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1]}]}})
    dataset_spec("calibration_under_floor", scene="grids.json", poses=still, calibration={"target": "board", "poses": {"list": [
        {"origin": [0.3, 0, 0.2], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1]},
        {"origin": [0.3, 0, -5], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1]}]}})

    # Untrusted specs (docs/robustness.md, "Threat model"): confinement, numbers that size work.
    random = {"count": 5, "seed": 1, "region": [-1, -1, 1, 1]}
    dataset_spec("allow_outside", allow_outside_files=True)
    dataset_spec("clearance_1e200", poses={"random": dict(random, clearance=1e200)})
    dataset_spec("jpeg_4294967346", recording={"jpeg_quality": 4294967346})
    dataset_spec("mount_y", cameras=[{"name": "c", "mount": {"y": 1000}}])
    # The robot inside the world, its camera's mount outside it.
    dataset_spec("mount_past_world", cameras=[{"name": "c", "mount": {"x": 99}}], poses={"list": [[9999.99, 0, 0]]})
    dataset_spec("lens_size", size=161, cameras=[{"name": "fisheye", "rig": {"lens": {
        "model": "fisheye_equidistant", "width": 160, "height": 120, "f_px": 50, "fov_deg": 180}}}])
    dataset_spec("samples_huge", size=16384, spp=16)
    dataset_spec("camera_frames", cameras=[{"name": "a"}, {"name": "b"}], poses={"random": dict(random, count=60000)})
    dataset_spec("seed_inexact", poses={"random": dict(random, seed=2 ** 53 + 1)})
    dataset_spec("timeout_1e300", engine="povray", timeout_s=1e300)
    dataset_spec("polygons_17", mode="thesis-mesh", mode_options={"polygons": 17})
    # 100,000 levels deep: a stack overflow once (the spec is copied into the manifest).
    write(os.path.join(datasets, "deep_comment.json"),
          '{"format": "omnicam-dataset/1", "scene": "box.json", "poses": {"path": "p"}, "comment": ' +
          "[" * 100000 + "]" * 100000 + "}\n")

    # Forged manifests: DIR/manifest.json of a one-frame dataset with one thing wrong.
    sha = "0" * 64
    def manifest(name, edit=None, text=None):
        pose = {"x": 0, "y": 0, "yaw_deg": 0}
        doc = {"format": "omnicam-dataset-manifest/1", "spec": {}, "spec_sha256": sha, "engine": {},
               "scene": {"sha256": sha}, "frame_count": 1, "complete": True,
               "cameras": [{"name": "cam0", "files": {"poses_tum": {"path": "cam0/poses.tum", "sha256": sha}}}],
               "frames": [{"index": 0, "timestamp": 0, "pose": pose, "cameras": {"cam0": {
                   "pose": pose, "files": {"rgb": {"path": "cam0/rgb/000000.png", "sha256": sha}}}}}]}
        if edit:
            edit(doc)
        body = json.dumps(doc, indent=1) + "\n"
        write(os.path.join(HERE, "manifests", name, "manifest.json"), text(body) if text else body)
    def rgb(doc, path):
        doc["frames"][0]["cameras"]["cam0"]["files"]["rgb"]["path"] = path
    manifest("path_dotdot", lambda d: rgb(d, "../secret.txt"))
    manifest("path_absolute", lambda d: rgb(d, "/etc/passwd"))
    manifest("index_negative", lambda d: d["frames"][0].update(index=-1))
    manifest("index_twice", lambda d: d["frames"].append(d["frames"][0]))
    manifest("count_string", lambda d: d.update(frame_count="1"))
    manifest("pose_missing", lambda d: d["frames"][0].pop("pose"))
    manifest("truncated", text=lambda body: body[:len(body) // 2])

    # An experiment's folder holding another experiment's results.
    write(os.path.join(HERE, "experiments", "texture_realism_run", "results.json"),
          json.dumps({"study": "texture-realism", "conditions": {}}) + "\n")
    # A convergence study's results that lack their fields; an experiment folder marked by another study.
    write(os.path.join(HERE, "experiments", "convergence_no_format", "convergence.json"), json.dumps({"seconds": 1}) + "\n")
    write(os.path.join(HERE, "experiments", "calibration_marked", ".omnicam-experiment.json"),
          json.dumps({"study": "calibration"}) + "\n")
    write(os.path.join(HERE, "experiments", "mark_without_study", ".omnicam-experiment.json"), json.dumps({"by": "me"}) + "\n")


if __name__ == "__main__":
    main()
