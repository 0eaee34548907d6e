"""Run by cli.rs's Blender test inside Blender: imports a run's glTF animation and its
point cache on their mesh as a user would, plays both to their last frame, and writes
the vertices Blender shows (in Blender's z-up frame) as JSON.

    blender -b --factory-startup --python blender_animation.py -- \\
        STAGE.glb STAGE.obj STAGE.pc2 SAMPLES OUT.json
"""
import bpy, sys, json
import numpy
# Blender 3.4's glTF importer still says numpy.bool, which numpy 1.24 removed.
if not hasattr(numpy, "bool"):
    numpy.bool = bool
glb, obj, pc2, samples, out = sys.argv[sys.argv.index("--") + 1:]
samples = int(samples)
result = {}

def evaluated(obj):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    mesh = obj.evaluated_get(depsgraph).to_mesh()
    return [list(obj.matrix_world @ v.co) for v in mesh.vertices]

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=glb)
cloth = [o for o in bpy.context.scene.objects if o.type == "MESH"][0]
keys = cloth.data.shape_keys
result["shape_keys"] = [k.name for k in keys.key_blocks]
action = keys.animation_data.action
start, end = action.frame_range
result["frame_range"] = [start, end]
bpy.context.scene.frame_set(int(end), subframe=end - int(end))
result["gltf_last"] = evaluated(cloth)

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=obj, forward_axis="Y", up_axis="Z")
mesh_obj = [o for o in bpy.context.scene.objects if o.type == "MESH"][0]
cache = mesh_obj.modifiers.new("cache", "MESH_CACHE")
cache.cache_format = "PC2"
cache.filepath = pc2
cache.frame_start = 0
bpy.context.scene.frame_set(samples - 1)
result["pc2_last"] = evaluated(mesh_obj)
json.dump(result, open(out, "w"))
