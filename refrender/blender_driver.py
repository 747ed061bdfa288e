"""omnicam's Blender driver: renders omnicam jobs with Cycles. Fixed script; all data comes from
the job JSON named after `--` (never Python built from scene strings):

    blender -b --factory-startup -noaudio --python-exit-code 1 -P blender_driver.py -- job.json

job.json: {"glb": path, "shading": "unlit"|"lit"|"path", "samples": int, "seed": int, "width": int,
           "height": int, "focal_length_px": float, "principal_point_px": [u, v] (raster, v down;
           default the image centre) -- or, for a lens camera, "panorama": {"type": Cycles'
           panorama_type, "sensor_width_mm", "shift_x", "shift_y", "fov" (fisheyes, radians),
           "lens_mm" (equisolid), "polynomial": [k0..k4] (lens polynomial, Cycles' sign),
           "longitude_min", "longitude_max", "latitude_min", "latitude_max" (equirectangular)},
           "lens_camera": true for a lens camera's job (no mirror in the glTF),
           "ambient": float (lit), "background": [r, g, b] (path: light from every direction; unlit and lit:
                           what camera and mirror rays that hit nothing see),
           "textures": {"<material index>": path.exr} (each textured material's texture in linear floats,
                        replacing the glTF's 8-bit sRGB PNG: the material found by extras.omnicam.material_index),
           "environment": {"image": path.exr, "strength": float, "rotation_deg": float} (path; replaces
                           the background: an equirectangular image around the world, Cycles' mapping),
           "lights": [{"watts": float, "diameter": float}] (in the order of the glTF's light_index;
                      diameter 0: a point, > 0: a disc luminaire facing straight down),
           "path_tracing": {"diffuse_bounces": int, "glossy_bounces": int, "clamp_indirect": float,
                            "mirror_seen_by_indirect_rays": bool, "direct_pass": bool} (lit; all optional),
           "frames": [{"world_from_viewpoint": 4x4 rows, "output": path.exr,
                       "direct_output": path.exr (with direct_pass),
                       "motion": {"exposure_s": float, "motion_steps": int,
                                  "world_from_viewpoint": [4x4 rows, ...]} (a moving frame)}],
           "timings_output": path.json (optional)}

timings_output: where the driver writes how its session spent its time, {"setup_seconds": from
the script's start to the first frame (factory settings, glTF import, materials), "frame_seconds":
[each frame's render call, its EXR written, in order]}; Blender's own start-up before the script
runs is the caller's to measure (the whole session's time minus these).

motion: the rig's exact placements at 2^(motion_steps - 1) + 1 evenly spaced instants of a
global shutter's exposure, from the frame's pose on. They are keyed on the rig at those instants
(linear between keys) and Cycles' motion blur samples the rig, mirror and camera at exactly
those instants (its motion steps); each camera ray gets its own random time in the exposure.

direct_pass: `output` becomes a multilayer OpenEXR (ViewLayer.Combined and Cycles' Denoising
Albedo, Normal and Depth passes), and the frame is rendered a second time with the same seed and
no bounce after the first surface seen in the mirror (direct light only) into `direct_output`.

The .glb holds the arena and the rig (nodes omnicam_rig > omnicam_mirror, omnicam_rim_mask,
omnicam_camera; a lens camera's rig holds the camera alone); the importer turns glTF's +Y-up into Blender's +Z-up, which is omnicam's world.
Objects are found by the node extras omnicam's exporter writes ("omnicam": {"role": ...,
"light_index": ...}, custom properties after import), never by name: Blender renames objects
whose names collide or exceed 63 bytes, and a user's object may be called anything.
"""
import json
import math
import sys
import time

import bpy
import numpy
from mathutils import Matrix

# Lit path tracing unless the job says otherwise (docs/blender.md).
PATH_TRACING_DEFAULTS = {"diffuse_bounces": 2, "glossy_bounces": 4, "clamp_indirect": 0.0,
                         "mirror_seen_by_indirect_rays": False, "direct_pass": False}

# Debian 12 pairs Blender 3.4, whose glTF importer still uses `numpy.bool`, with numpy 1.24,
# which removed that alias. Restore it (it was exactly the builtin bool).
if not hasattr(numpy, "bool"):
    numpy.bool = bool


def load_job():
    argv = sys.argv[sys.argv.index("--") + 1:]
    with open(argv[0], encoding="utf-8") as f:
        return json.load(f)


def node_tree_material(name):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    return material, nodes, material.node_tree.links, output


def perfect_mirror():
    material, nodes, links, output = node_tree_material("omnicam_perfect_mirror")
    glossy = nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "SHARP"
    glossy.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    glossy.inputs["Roughness"].default_value = 0.0
    links.new(glossy.outputs["BSDF"], output.inputs["Surface"])
    return material


def black_emission():
    material, nodes, links, output = node_tree_material("omnicam_black")
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    emission.inputs["Strength"].default_value = 0.0
    links.new(emission.outputs["Emission"], output.inputs["Surface"])
    return material


def principled_and_output(material):
    """The imported Principled BSDF and the material output of a glTF material, or (None, None)."""
    nodes = material.node_tree.nodes
    principled = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    output = next((n for n in nodes if n.type == "OUTPUT_MATERIAL"), None)
    return (principled, output) if principled is not None and output is not None else (None, None)


def feed(tree, socket, into):
    """`into` takes what feeds `socket` (a link, or its value)."""
    if socket.is_linked:
        tree.links.new(socket.links[0].from_socket, into)
    else:
        into.default_value = socket.default_value


def make_emission_only(material):
    """unlit (docs/conventions.md §2): radiance = albedo. The albedo is whatever fed the imported Principled
    BSDF's Base Color (factor × texture), now fed to an Emission of strength 1."""
    principled, output = principled_and_output(material)
    if principled is None:
        return
    tree = material.node_tree
    emission = tree.nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    feed(tree, principled.inputs["Base Color"], emission.inputs["Color"])
    tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])


def make_lambertian(material):
    """lit and path (docs/conventions.md §3): surfaces are Lambertian, radiance = albedo/pi x irradiance, plus
    their emission. The imported Principled BSDF (specular 0.5, Disney diffuse) becomes a Diffuse BSDF of
    roughness 0 (exactly Lambert) fed what fed its Base Color; its emission (glTF emissiveFactor x
    KHR_materials_emissive_strength) is added by an Emission shader."""
    principled, output = principled_and_output(material)
    if principled is None:
        return
    tree = material.node_tree
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Roughness"].default_value = 0.0
    feed(tree, principled.inputs["Base Color"], diffuse.inputs["Color"])
    shader = diffuse.outputs["BSDF"]
    emission_colour = principled.inputs["Emission"]
    strength = principled.inputs["Emission Strength"].default_value
    if emission_colour.is_linked or (strength > 0.0 and max(emission_colour.default_value[:3]) > 0.0):
        emission = tree.nodes.new("ShaderNodeEmission")
        feed(tree, emission_colour, emission.inputs["Color"])
        emission.inputs["Strength"].default_value = strength
        add = tree.nodes.new("ShaderNodeAddShader")
        tree.links.new(shader, add.inputs[0])
        tree.links.new(emission.outputs["Emission"], add.inputs[1])
        shader = add.outputs["Shader"]
    tree.links.new(shader, output.inputs["Surface"])


def use_linear_textures(textures):
    """The glTF's textures are 8-bit sRGB PNGs, which Cycles interpolates before it linearises them: a
    magnified texture would be averaged in the wrong space. The job's own float EXRs of them (linear,
    the numbers omnicam samples) replace them, found by the material's index in the scene
    (extras.omnicam.material_index)."""
    for material in bpy.data.materials:
        props = omnicam_props(material)
        index = props.get("material_index") if props is not None else None
        if index is None or not material.use_nodes:
            continue
        if str(index) not in textures:
            continue
        image = bpy.data.images.load(textures[str(index)])
        image.colorspace_settings.name = "Linear"
        swapped = 0
        for node in material.node_tree.nodes:
            if node.type == "TEX_IMAGE":
                node.image = image
                node.interpolation = "Linear"
                swapped += 1
        if swapped != 1:
            raise RuntimeError("omnicam: material %d has %d image textures, not one" % (index, swapped))


def background_world(colour):
    """path (docs/conventions.md §3): the background is light of constant radiance from every direction,
    for every ray (seen directly, in the mirror and by bounces)."""
    world = bpy.data.worlds.new("omnicam_world")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (colour[0], colour[1], colour[2], 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    return world


def environment_world(environment):
    """path with an environment (docs/conventions.md §3): the equirectangular image around the world as
    the Environment Texture maps it, turned counter-clockwise about +Z by rotation_deg: the direction d
    reads the image at Rz(-rotation)·d. Cycles samples it by its own importance map (sampling_method
    AUTOMATIC, the default)."""
    world = bpy.data.worlds.new("omnicam_world")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    texture = nodes.new("ShaderNodeTexEnvironment")
    texture.image = bpy.data.images.load(environment["image"], check_existing=False)
    texture.interpolation = "Linear"
    texture.projection = "EQUIRECTANGULAR"
    coordinates = nodes.new("ShaderNodeTexCoord")
    mapping = nodes.new("ShaderNodeMapping")
    mapping.vector_type = "POINT"
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, -math.radians(environment["rotation_deg"]))
    links.new(coordinates.outputs["Generated"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    background = nodes["Background"]
    links.new(texture.outputs["Color"], background.inputs["Color"])
    background.inputs["Strength"].default_value = environment["strength"]
    return world


def ambient_world(ambient, background):
    """The ambient term of lit shading (docs/conventions.md §3) as uniform light from the sky, for diffuse rays only: seen
    directly or in the mirror the sky is the scene's background, as in the other engines (unlit and lit keep it)."""
    world = bpy.data.worlds.new("omnicam_world")
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    lit = nodes["Background"]
    lit.inputs["Color"].default_value = (ambient, ambient, ambient, 1.0)
    seen_sky = nodes.new("ShaderNodeBackground")
    seen_sky.inputs["Color"].default_value = (background[0], background[1], background[2], 1.0)
    path = nodes.new("ShaderNodeLightPath")
    seen = nodes.new("ShaderNodeMath")
    seen.operation = "MAXIMUM"
    links.new(path.outputs["Is Camera Ray"], seen.inputs[0])
    links.new(path.outputs["Is Glossy Ray"], seen.inputs[1])
    mix = nodes.new("ShaderNodeMixShader")
    links.new(seen.outputs["Value"], mix.inputs["Fac"])
    links.new(lit.outputs["Background"], mix.inputs[1])
    links.new(seen_sky.outputs["Background"], mix.inputs[2])
    links.new(mix.outputs["Shader"], nodes["World Output"].inputs["Surface"])
    return world


def only_camera_sees(obj):
    obj.visible_diffuse = False
    obj.visible_glossy = False
    obj.visible_transmission = False
    obj.visible_volume_scatter = False
    obj.visible_shadow = False


def make_luminaire(obj, diameter):
    """A lamp of real size: a disc of `diameter` metres at the light's position facing straight
    down (an area light emits along its local -Z), with the point light's power."""
    position = obj.matrix_world.translation.copy()
    obj.data.type = "AREA"
    obj.data.shape = "DISK"
    obj.data.size = diameter
    obj.matrix_world = Matrix.Translation(position)


def path_tracing(job):
    settings = dict(PATH_TRACING_DEFAULTS)
    given = job.get("path_tracing", {})
    unknown = sorted(set(given) - set(settings))
    if unknown:
        raise RuntimeError("omnicam: unknown path_tracing settings " + ", ".join(unknown))
    settings.update(given)
    return settings


def omnicam_props(obj):
    props = obj.get("omnicam")
    return props if props is not None and hasattr(props, "get") else None


def find_roles(objects, lens):
    roles, lights = {}, {}
    for obj in objects:
        props = omnicam_props(obj)
        if props is None:
            continue
        role = props.get("role")
        if role == "light" and obj.type == "LIGHT":
            lights[int(props.get("light_index"))] = obj
        elif role in ("rig", "mirror", "rim_mask", "camera"):
            if role in roles:
                raise RuntimeError("omnicam: two objects claim the role " + role)
            roles[role] = obj
    needed = ("rig", "camera") if lens else ("rig", "mirror", "rim_mask", "camera")
    missing = [r for r in needed if r not in roles]
    if missing:
        raise RuntimeError("omnicam: the glTF rig lacks " + ", ".join(missing))
    return roles, lights


def main():
    started = time.perf_counter()
    job = load_job()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=job["glb"])
    scene = bpy.context.scene
    lens = job.get("lens_camera", False)
    roles, lights_by_index = find_roles(bpy.data.objects, lens)
    rig, mirror, mask, camera = roles["rig"], roles.get("mirror"), roles.get("rim_mask"), roles["camera"]
    unlit = job["shading"] == "unlit"
    tracing = path_tracing(job)

    use_linear_textures(job.get("textures", {}))
    # The rig's own materials are replaced below.
    for material in bpy.data.materials:
        if material.use_nodes:
            if unlit:
                make_emission_only(material)
            else:
                make_lambertian(material)
    if mirror is not None:
        mirror.data.materials.clear()
        mirror.data.materials.append(perfect_mirror())
        # The mirror is part of the camera (docs/conventions.md §3): camera rays see it, bounces pass
        # through it and it casts no shadow, as in the fast renderer and POV-Ray.
        if tracing["mirror_seen_by_indirect_rays"]:
            mirror.visible_shadow = False
        else:
            only_camera_sees(mirror)
    if mask is not None:
        mask.data.materials.clear()
        mask.data.materials.append(black_emission())
        only_camera_sees(mask)

    if job["shading"] == "path":
        if "environment" in job:
            scene.world = environment_world(job["environment"])
        else:
            scene.world = background_world(job.get("background", [0.0, 0.0, 0.0]))
    else:
        scene.world = ambient_world(0.0 if unlit else job.get("ambient", 0.0), job.get("background", [0.0, 0.0, 0.0]))
    for index, light in enumerate(job.get("lights", [])):
        obj = lights_by_index.get(index)
        if obj is None:
            raise RuntimeError("omnicam: light %d is missing from the imported scene" % index)
        if light.get("diameter", 0.0) > 0.0:
            make_luminaire(obj, light["diameter"])
        else:
            obj.data.shadow_soft_size = 0.0  # a point: hard shadows
        obj.data.energy = 0.0 if unlit else light["watts"]

    cam = camera.data
    if "panorama" in job:
        set_panorama(cam, job["panorama"])
    else:
        cam.type = "PERSP"
        cam.sensor_fit = "HORIZONTAL"
        cam.sensor_width = 36.0
        cam.lens = job["focal_length_px"] * 36.0 / job["width"]
        # The principal point (raster, v down) as a lens shift, in units of the image width: a shift
        # to the right puts the optical axis left of the centre, one upward puts it below.
        principal = job.get("principal_point_px", [0.5 * job["width"], 0.5 * job["height"]])
        cam.shift_x = (0.5 * job["width"] - principal[0]) / job["width"]
        cam.shift_y = (principal[1] - 0.5 * job["height"]) / job["width"]
    cam.clip_start = 1e-4
    cam.clip_end = 1e4
    scene.camera = camera

    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = job["samples"]
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.seed = job.get("seed", 0)
    cycles.use_animated_seed = False
    cycles.pixel_filter_type = "BOX"
    cycles.filter_width = 1.0
    cycles.glossy_bounces = max(1, tracing["glossy_bounces"])  # the mirror's reflection is one
    cycles.diffuse_bounces = 0 if unlit else tracing["diffuse_bounces"]
    cycles.transmission_bounces = 0
    cycles.volume_bounces = 0
    cycles.transparent_max_bounces = 0
    # max_bounces caps diffuse, glossy, transmission and volume bounces together (transparent ones
    # have their own cap): as their sum it never cuts a path, and diffuse_bounces is what limits
    # (a fixed 8 held --bounces 7 and up at 7, the mirror's reflection being the eighth).
    cycles.max_bounces = (cycles.diffuse_bounces + cycles.glossy_bounces + cycles.transmission_bounces +
                          cycles.volume_bounces)
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0 if unlit else tracing["clamp_indirect"]
    cycles.blur_glossy = 0.0
    scene.render.resolution_x = job["width"]
    scene.render.resolution_y = job["height"]
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    scene.render.threads_mode = "AUTO"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    settings.color_mode = "RGB"

    direct_pass = tracing["direct_pass"] and not unlit
    timings = {"setup_seconds": time.perf_counter() - started, "frame_seconds": []}
    for frame in job["frames"]:
        frame_started = time.perf_counter()
        place_rig(scene, rig, [obj for obj in (rig, mirror, mask, camera) if obj is not None], frame)
        if direct_pass:
            render_with_direct_twin(scene, frame)
        else:
            render_to(scene, frame["output"])
        timings["frame_seconds"].append(time.perf_counter() - frame_started)
    if "timings_output" in job:
        with open(job["timings_output"], "w") as out:
            json.dump(timings, out)


def set_panorama(cam, panorama):
    """Cycles' panoramic camera (Blender 3.4 keeps its settings in the Cycles add-on's
    cam.cycles): image coordinates over [0, 1] across the sensor, shifted like a lens."""
    cam.type = "PANO"
    cam.sensor_fit = "HORIZONTAL"
    cam.sensor_width = panorama["sensor_width_mm"]
    cam.shift_x = panorama["shift_x"]
    cam.shift_y = panorama["shift_y"]
    settings = cam.cycles
    settings.panorama_type = panorama["type"]
    if panorama["type"] == "EQUIRECTANGULAR":
        settings.longitude_min = panorama["longitude_min"]
        settings.longitude_max = panorama["longitude_max"]
        settings.latitude_min = panorama["latitude_min"]
        settings.latitude_max = panorama["latitude_max"]
        return
    settings.fisheye_fov = panorama["fov"]
    if panorama["type"] == "FISHEYE_EQUISOLID":
        settings.fisheye_lens = panorama["lens_mm"]
    elif panorama["type"] == "FISHEYE_LENS_POLYNOMIAL":
        for index, k in enumerate(panorama["polynomial"]):
            setattr(settings, "fisheye_polynomial_k%d" % index, k)


def place_rig(scene, rig, rig_objects, frame):
    """The rig still at the frame's placement, or keyed over a moving frame's exposure."""
    rig.animation_data_clear()
    motion = frame.get("motion")
    scene.render.use_motion_blur = motion is not None
    if motion is None:
        rig.matrix_world = Matrix(frame["world_from_viewpoint"])
        return
    # One frame per interval between the placements: the shutter opens at frame 1 (the frame's
    # pose) and stays open for `intervals` frames. Blender merges keys closer than 0.01 frames
    # (BEZT_BINARYSEARCH_THRESH), so keys spaced by the exposure in seconds (0.0005 frames apart
    # at 1/30 s) would collapse onto a few, each holding a later pose: the blur ran about 1.5x
    # too long. Nothing in the job depends on the frame rate.
    placements = motion["world_from_viewpoint"]
    intervals = len(placements) - 1
    scene.render.fps, scene.render.fps_base = 1, 1.0
    scene.cycles.motion_blur_position = "START"
    scene.render.motion_blur_shutter = intervals
    scene.cycles.rolling_shutter_type = "NONE"
    rig.rotation_mode = "QUATERNION"
    if intervals != 2 ** (motion["motion_steps"] - 1):
        raise RuntimeError("omnicam: a moving frame needs 2^(motion_steps - 1) + 1 placements")
    previous = None
    for k, rows in enumerate(placements):
        rig.matrix_world = Matrix(rows)
        rotation = rig.rotation_quaternion.copy()
        if previous is not None:
            rotation.make_compatible(previous)  # q and -q are one rotation: keys must not flip between them
        rig.rotation_quaternion = rotation
        previous = rotation
        at = 1.0 + k
        rig.keyframe_insert("location", frame=at)
        rig.keyframe_insert("rotation_quaternion", frame=at)
    for fcurve in rig.animation_data.action.fcurves:
        if len(fcurve.keyframe_points) != len(placements):
            raise RuntimeError("omnicam: Blender kept %d of the %d motion keys" % (len(fcurve.keyframe_points), len(placements)))
        for key in fcurve.keyframe_points:
            key.interpolation = "LINEAR"
    for obj in rig_objects:
        obj.cycles.use_motion_blur = True
        obj.cycles.motion_steps = motion["motion_steps"]
    scene.frame_set(1)


def render_to(scene, path):
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    print("omnicam: wrote", path, flush=True)


def render_with_direct_twin(scene, frame):
    """Every path with the guide passes, then the same samples (same seed) ending at the first
    surface seen in the mirror: its direct light only (indirect_filter.h). Leaves the settings as
    it found them."""
    cycles, layer, settings = scene.cycles, bpy.context.view_layer, scene.render.image_settings
    kept = (cycles.diffuse_bounces, cycles.glossy_bounces, layer.cycles.denoising_store_passes, settings.file_format)
    layer.cycles.denoising_store_passes = True
    settings.file_format = "OPEN_EXR_MULTILAYER"
    render_to(scene, frame["output"])
    layer.cycles.denoising_store_passes = kept[2]
    settings.file_format = kept[3]
    cycles.diffuse_bounces, cycles.glossy_bounces = 0, 1  # the mirror's reflection is the one glossy bounce
    render_to(scene, frame["direct_output"])
    cycles.diffuse_bounces, cycles.glossy_bounces = kept[0], kept[1]


main()
