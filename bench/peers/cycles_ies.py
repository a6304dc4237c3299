"""Renders the IES comparison scene with Blender's Cycles, for lucent's test
`crates/lucent-scene/tests/ies_cycles.rs`:

    blender -b --factory-startup --python bench/peers/cycles_ies.py -- OUT.exr [SPP]

A point lamp 3 units above a floor, 3 in front of a wall, with the asymmetric type C profile
`crates/lucent-scene/tests/data/ies-asymmetric.ies` on its emission (an IES Texture node);
Lambertian floor and wall of reflectance 0.5, a black world, a box pixel filter, 8 bounces;
96 × 64 pixels, linear float EXR. Blender is z-up: lucent's (x, y, z) is Blender's (x, −z, y),
so the lucent scene of the test is this one turned. (`apt-get install blender`: Debian's 3.4.)
"""
import math
import sys
from pathlib import Path

import bpy
from mathutils import Vector

args = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
out = Path(args[0] if args else "cycles-ies.exr").resolve()
spp = int(args[1]) if len(args) > 1 else 4096
root = Path(__file__).resolve().parents[2]
ies = root / "crates/lucent-scene/tests/data/ies-asymmetric.ies"

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = spp
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.pixel_filter_type = "BOX"
scene.cycles.max_bounces = 8
scene.cycles.diffuse_bounces = 8
scene.cycles.sample_clamp_direct = 0
scene.cycles.sample_clamp_indirect = 0
scene.cycles.seed = 1
scene.render.threads_mode = "FIXED"
scene.render.threads = 2
scene.render.resolution_x = 96
scene.render.resolution_y = 64
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.color_mode = "RGB"
scene.view_settings.view_transform = "Standard"

world = bpy.data.worlds.new("black")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
scene.world = world


def diffuse(name, grey):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    nodes.clear()
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (grey, grey, grey, 1)
    bsdf.inputs["Roughness"].default_value = 0.0
    output = nodes.new("ShaderNodeOutputMaterial")
    m.node_tree.links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])
    return m


def plane(name, size, location, rotation, material):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(material)


grey = diffuse("grey", 0.5)
plane("floor", 20, (0, 0, 0), (0, 0, 0), grey)
# The wall at lucent's z = −3 (Blender's y = 3), facing the camera.
plane("wall", 20, (0, 3, 0), (math.pi / 2, 0, 0), grey)

lamp = bpy.data.lights.new("lamp", "POINT")
lamp.shadow_soft_size = 0.0
lamp.energy = 100.0
lamp.use_nodes = True
nodes = lamp.node_tree.nodes
texture = nodes.new("ShaderNodeTexIES")
texture.mode = "EXTERNAL"
texture.filepath = str(ies)
lamp.node_tree.links.new(texture.outputs["Fac"], nodes["Emission"].inputs["Strength"])
lamp_object = bpy.data.objects.new("lamp", lamp)
lamp_object.location = (0, 0, 3)
scene.collection.objects.link(lamp_object)

camera = bpy.data.cameras.new("camera")
camera.sensor_fit = "VERTICAL"
camera.angle_y = math.radians(50)
camera_object = bpy.data.objects.new("camera", camera)
camera_object.location = (0, -7, 4)
look = Vector((0, 1, 1)) - camera_object.location
camera_object.rotation_euler = look.to_track_quat("-Z", "Y").to_euler()
scene.collection.objects.link(camera_object)
scene.camera = camera_object

scene.render.filepath = str(out)
bpy.ops.render.render(write_still=True)
print(f"wrote {out} ({spp} spp)")
