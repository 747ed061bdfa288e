# Blender reads an omnicam multilayer frame (docs/dataset-format.md): run as
#   blender -b --factory-startup --python tests/blender_read_multilayer.py -- FRAME.exr OUT_DIR SIZE
# Loads FRAME.exr as a Blender image, lists the layers (passes) Blender finds in it, and writes
# each pass as Blender read it through the compositor to OUT_DIR/<pass>.exr (float32 RGBA, the
# pass's values in R, G, B), with OUT_DIR/passes.json naming them: the test compares them with
# omnicam's own reader.
import json
import os
import sys

import bpy

frame, out_dir, size = sys.argv[sys.argv.index("--") + 1:]
image = bpy.data.images.load(frame)
scene = bpy.context.scene
for obj in list(scene.objects):
    bpy.data.objects.remove(obj)
scene.render.engine = "CYCLES"
scene.cycles.samples = 1
scene.render.resolution_x = scene.render.resolution_y = int(size)
scene.render.resolution_percentage = 100
settings = scene.render.image_settings
settings.file_format, settings.color_depth, settings.color_mode, settings.exr_codec = "OPEN_EXR", "32", "RGBA", "ZIP"
scene.view_settings.view_transform = "Standard"
scene.use_nodes = True
tree = scene.node_tree
for node in list(tree.nodes):
    tree.nodes.remove(node)
source = tree.nodes.new("CompositorNodeImage")
source.image = image
composite = tree.nodes.new("CompositorNodeComposite")
composite.use_alpha = True
passes = [output.name for output in source.outputs if output.enabled]
for name in passes:
    tree.links.new(source.outputs[name], composite.inputs[0])
    scene.render.filepath = os.path.join(out_dir, name + ".exr")
    bpy.ops.render.render(write_still=True)
with open(os.path.join(out_dir, "passes.json"), "w") as out:
    json.dump({"image_type": image.type, "passes": passes}, out)
