# The clients test (ctest -L clients): Blender 3.4, headless, opens what arbor writes as a user would.
#   blender -b --factory-startup --python-exit-code 1 --python blender_test.py -- ARBOR SOURCE_DIR WORK
# Checks, each failing the run with a message:
# 1. the default EXR loads in Blender's scene-linear ("Linear", Rec.709) with nothing set, and a
#    known colour (a constant sky of scene-linear Rec.709 (0.2, 0.5, 0.8)) comes out as that colour;
# 2. an EXR with every AOV is read as multilayer and every AOV is a pass of Blender's Image node;
# 3. Blender's Cryptomatte node, given the tree's name, makes the matte arbor's Cryptomatte
#    channels say (the coverage summed over the ranks whose id is the tree's);
# 4. `grow -o X.obj --up y` imports standing upright (z from 0 to the tree's height) with its
#    bark and leaf materials and the .mtl's colours.
import json
import os
import struct
import subprocess
import sys

import bpy
import numpy as np
import OpenImageIO as oiio

arbor, source, work = sys.argv[sys.argv.index("--") + 1:][:3]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def run(*args):
    r = subprocess.run([arbor, *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"arbor {' '.join(args)} failed ({r.returncode}): {r.stderr}")
    return r


def scene(path, body):
    with open(path, "w") as f:
        f.write(body)
    return path


os.makedirs(work, exist_ok=True)

# 1. A known colour: the camera sees only a constant sky of scene-linear Rec.709 (0.2, 0.5, 0.8).
sky = scene(os.path.join(work, "sky.toml"), """
[render]
width = 8
height = 6
spp = 4
[camera]
position = [0.0, 0.0, 1.0]
look_at = [0.0, 0.0, 10.0]
up = [0.0, 1.0, 0.0]
[sun]
irradiance = 0.0
[sky]
model = "constant"
color = [0.2, 0.5, 0.8]
[ground]
enabled = false
""")
run("render", sky, "-o", os.path.join(work, "sky.exr"))
img = bpy.data.images.load(os.path.join(work, "sky.exr"))
check(img.colorspace_settings.name == "Linear", f"the default EXR opens as Blender's 'Linear' (got {img.colorspace_settings.name!r})")
px = np.array(img.pixels[:]).reshape(-1, 4)
check(np.allclose(px[:, :3], [0.2, 0.5, 0.8], rtol=2e-3), f"its pixels are the sky's Rec.709 colour (got {px[0, :3]})")

# 2 and 3. A tree against the sky with every AOV.
tree = scene(os.path.join(work, "tree.toml"), f"""
[render]
width = 48
height = 36
spp = 16
seed = 3
[camera]
position = [0.0, -30.0, 7.0]
look_at = [0.0, 0.0, 7.0]
[[tree]]
species = "{source}/species/quaking_aspen.toml"
[ground]
enabled = false
[output]
aovs = ["albedo", "normal", "depth", "variance", "samples", "object_id", "material_id", "crypto_object", "crypto_material"]
""")
aovs_exr = os.path.join(work, "aovs.exr")
run("render", tree, "-o", aovs_exr)
img = bpy.data.images.load(aovs_exr)
bpy.context.scene.use_nodes = True
nodes = bpy.context.scene.node_tree.nodes
links = bpy.context.scene.node_tree.links
for n in list(nodes):
    nodes.remove(n)
image_node = nodes.new("CompositorNodeImage")
image_node.image = img
passes = {o.name for o in image_node.outputs if o.enabled}
print("passes:", sorted(passes))
check(img.type == "MULTILAYER", f"the EXR with AOVs is read as multilayer (got {img.type})")
for name in ["Combined", "Alpha", "albedo", "N", "Depth", "variance", "samples", "object_id", "material_id",
             "crypto_object00", "crypto_object01", "crypto_object02",
             "crypto_material00", "crypto_material01", "crypto_material02"]:
    check(name in passes, f"Blender's Image node has the pass {name}")

# arbor's own matte of the tree, from the EXR (Cryptomatte 1.2: id = the manifest's hash as a float).
inp = oiio.ImageInput.open(aovs_exr)
spec = inp.spec()
pixels = inp.read_image(oiio.FLOAT)
inp.close()
channels = list(spec.channelnames)
manifest = {}
for attr in spec.extra_attribs:
    if attr.name.startswith("cryptomatte/") and attr.name.endswith("/name") and attr.value == "crypto_object":
        manifest = json.loads(spec.getattribute(attr.name[:-len("name")] + "manifest"))
names = [n for n in manifest if n != "ground"]
check(len(names) == 1, f"the manifest names one tree (got {list(manifest)})")
tree_name = names[0]
tree_id = struct.unpack("<f", struct.pack("<I", int(manifest[tree_name], 16)))[0]
expected = np.zeros((spec.height, spec.width))
for layer in ["crypto_object00", "crypto_object01", "crypto_object02"]:
    for id_c, cover_c in (("R", "G"), ("B", "A")):
        ids = pixels[:, :, channels.index(f"{layer}.{id_c}")]
        cover = pixels[:, :, channels.index(f"{layer}.{cover_c}")]
        expected += np.where(ids == tree_id, cover, 0.0)
check(expected.max() > 0.99 and (expected > 0.0).sum() > 50, "arbor's matte of the tree covers pixels")

crypto = nodes.new("CompositorNodeCryptomatteV2")
crypto.source = "IMAGE"
crypto.image = img
crypto.layer_name = "crypto_object"
crypto.matte_id = tree_name
viewer = nodes.new("CompositorNodeViewer")
composite = nodes.new("CompositorNodeComposite")
links.new(image_node.outputs["Combined"], crypto.inputs["Image"])
links.new(crypto.outputs["Matte"], viewer.inputs["Image"])
links.new(crypto.outputs["Matte"], composite.inputs["Image"])
scene_data = bpy.context.scene
scene_data.render.engine = "CYCLES"
scene_data.cycles.samples = 1
scene_data.cycles.device = "CPU"
scene_data.render.resolution_x = spec.width
scene_data.render.resolution_y = spec.height
scene_data.render.resolution_percentage = 100
scene_data.render.use_compositing = True
scene_data.view_settings.view_transform = "Standard"
scene_data.render.image_settings.file_format = "OPEN_EXR"
scene_data.render.image_settings.color_depth = "32"
matte_exr = os.path.join(work, "matte.exr")
scene_data.render.filepath = matte_exr
bpy.ops.render.render(write_still=True)
inp = oiio.ImageInput.open(matte_exr)
got = inp.read_image(oiio.FLOAT)[:, :, 0]
inp.close()
diff = np.abs(got - expected).max()
check(diff < 1e-4, f"Blender's Cryptomatte matte of {tree_name} equals arbor's coverage (max difference {diff:.2e})")

# 4. An OBJ exported y-up stands upright in Blender, with its materials.
stats = json.loads(run("grow", f"{source}/species/quaking_aspen.toml", "--stats", "--json").stdout)
obj = os.path.join(work, "aspen.obj")
run("grow", f"{source}/species/quaking_aspen.toml", "-o", obj, "--up", "y")
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
bpy.ops.import_scene.obj(filepath=obj)
zs = []
for o in bpy.context.scene.objects:
    if o.type == "MESH":
        m = np.array(o.matrix_world)
        v = np.array([vert.co[:] + (1.0,) for vert in o.data.vertices])
        zs.append((v @ m.T)[:, 2])
zs = np.concatenate(zs)
check(abs(zs.min()) < 0.05, f"the tree's base is at z = 0 (got {zs.min():.3f})")
check(abs(zs.max() - stats["height"]) < 0.02 * stats["height"] + 0.05,
      f"it stands {zs.max():.2f} m tall, as grow --stats says ({stats['height']:.2f} m)")
materials = {m.name for m in bpy.data.materials}
check({"bark", "leaf"} <= materials, f"it has the bark and leaf materials (got {sorted(materials)})")
with open(obj[:-4] + ".mtl") as f:
    kd = None
    for line in f:
        if line.startswith("newmtl"):
            current = line.split()[1]
        if line.startswith("Kd") and current == "bark":
            kd = [float(x) for x in line.split()[1:4]]
bark = bpy.data.materials["bark"]
base = bark.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value[:3]
check(kd is not None and np.allclose(base, kd, atol=1e-3), f"the bark's colour is the .mtl's Kd {kd} (got {list(base)})")

print(f"clients: {len(failures)} failed")
sys.exit(1 if failures else 0)
