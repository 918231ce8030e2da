# Builds the yardstick scene in Blender Cycles and renders it (run by bench/cycles/yardstick.py):
#   blender -b --factory-startup --python cycles_scene.py -- CONFIG.json OUT.exr SPP SEED THRESHOLD
# CONFIG.json is the scene the yardstick also writes for arbor (camera, sun, constant sky, ground,
# the tree's OBJ and its materials). THRESHOLD 0 renders SPP samples in every pixel; above 0 it is
# Cycles' adaptive sampling threshold (its default is 0.01) with SPP as the most a pixel takes.
# Prints one line "yardstick: {json}" with the CPU seconds of the render call alone.
import json
import math
import sys
import time

import bpy
from mathutils import Vector

args = sys.argv[sys.argv.index("--") + 1:]
config = json.load(open(args[0]))
out_path, spp, seed, threshold = args[1], int(args[2]), int(args[3]), float(args[4])

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene

# The tree, in arbor's axes (z up; no conversion).
bpy.ops.wm.obj_import(filepath=config["obj"], forward_axis="Y", up_axis="Z")


def node_material(name, build):
    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    links.new(build(nodes, links), output.inputs["Surface"])
    return mat


def diffuse(colour):
    def build(nodes, links):
        bsdf = nodes.new("ShaderNodeBsdfDiffuse")
        bsdf.inputs["Color"].default_value = (*colour, 1.0)
        bsdf.inputs["Roughness"].default_value = 0.0
        return bsdf.outputs["BSDF"]
    return build


def leaf(reflectance, transmittance):
    # The sum of a Lambertian reflection and a Lambertian transmission, as arbor's bare leaf with
    # the same reflectance on both faces.
    def build(nodes, links):
        d = nodes.new("ShaderNodeBsdfDiffuse")
        d.inputs["Color"].default_value = (*reflectance, 1.0)
        d.inputs["Roughness"].default_value = 0.0
        t = nodes.new("ShaderNodeBsdfTranslucent")
        t.inputs["Color"].default_value = (*transmittance, 1.0)
        add = nodes.new("ShaderNodeAddShader")
        links.new(d.outputs["BSDF"], add.inputs[0])
        links.new(t.outputs["BSDF"], add.inputs[1])
        return add.outputs["Shader"]
    return build


materials = {
    "bark": node_material("bark", diffuse(config["bark_albedo"])),
    "leaf": node_material("leaf", leaf(config["leaf_reflectance"], config["leaf_transmittance"])),
}
for obj in scene.objects:
    if obj.type == "MESH":
        for slot in obj.material_slots:
            name = slot.material.name.split(".")[0] if slot.material else ""
            if name in materials:
                slot.material = materials[name]

# The ground: a 20 km Lambertian square at z = 0, as arbor's.
bpy.ops.mesh.primitive_plane_add(size=20000.0, location=(0.0, 0.0, 0.0))
bpy.context.object.data.materials.append(node_material("ground", diffuse(config["ground_albedo"])))

# Camera: arbor's vertical field of view, looking from position to look_at with z up.
cam_data = bpy.data.cameras.new("camera")
cam_data.sensor_fit = "VERTICAL"
cam_data.sensor_height = 24.0
cam_data.lens = 12.0 / math.tan(math.radians(config["fov"]) / 2.0)
cam_data.clip_start = 0.001
cam_data.clip_end = 1.0e5
camera = bpy.data.objects.new("camera", cam_data)
scene.collection.objects.link(camera)
position, look_at = Vector(config["camera_position"]), Vector(config["camera_look_at"])
camera.location = position
camera.rotation_euler = (look_at - position).to_track_quat("-Z", "Y").to_euler()
scene.camera = camera

# Sun: irradiance E on a plane facing it (Cycles' sun strength), toward (elevation, azimuth
# counter-clockwise from +x), a disk of the same angular diameter.
sun_data = bpy.data.lights.new("sun", type="SUN")
sun_data.energy = config["sun_irradiance"]
sun_data.angle = math.radians(config["sun_angular_diameter"])
sun_data.color = (1.0, 1.0, 1.0)
sun = bpy.data.objects.new("sun", sun_data)
scene.collection.objects.link(sun)
el, az = math.radians(config["sun_elevation"]), math.radians(config["sun_azimuth"])
towards_sun = Vector((math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)))
sun.rotation_euler = (-towards_sun).to_track_quat("-Z", "Y").to_euler()

# Sky: constant radiance.
world = bpy.data.worlds.new("world")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (*config["sky_color"], 1.0)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
scene.world = world

# Render settings: CPU, two threads, no denoiser, no clamping, no glossy filter, all bounces of
# every kind up to max_depth, the default Blackman-Harris filter of 1.5 px (standard deviation
# 0.416 px, arbor's tent of radius 1: 0.408 px), scene-linear float EXR.
scene.render.engine = "CYCLES"
cy = scene.cycles
cy.device = "CPU"
cy.samples = spp
cy.seed = seed
cy.use_animated_seed = False
cy.use_denoising = False
cy.use_adaptive_sampling = threshold > 0.0
cy.adaptive_threshold = threshold if threshold > 0.0 else 0.01
cy.adaptive_min_samples = 0
depth = config["max_depth"]
cy.max_bounces = depth
cy.diffuse_bounces = depth
cy.glossy_bounces = depth
cy.transmission_bounces = depth
cy.transparent_max_bounces = depth
cy.volume_bounces = 0
cy.sample_clamp_direct = 0.0
cy.sample_clamp_indirect = 0.0
cy.blur_glossy = 0.0
cy.caustics_reflective = True
cy.caustics_refractive = True
cy.light_sampling_threshold = 0.0
cy.pixel_filter_type = "BLACKMAN_HARRIS"
cy.filter_width = 1.5
scene.render.threads_mode = "FIXED"
scene.render.threads = config["threads"]
scene.render.resolution_x = config["width"]
scene.render.resolution_y = config["height"]
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0.0
scene.view_settings.gamma = 1.0
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.exr_codec = "ZIP"
scene.render.filepath = out_path

cpu0, wall0 = time.process_time(), time.perf_counter()
bpy.ops.render.render(write_still=True)
cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
print("yardstick: " + json.dumps({"render_cpu_s": cpu, "render_wall_s": wall}), flush=True)
