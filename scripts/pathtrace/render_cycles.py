"""Renders a cloud volume written by `skyrender export-volume` with Blender's Cycles, as the
path-traced reference for the raymarch (docs/cloud-model.md, "Path-traced reference").

    blender -b --factory-startup --python scripts/pathtrace/render_cycles.py -- \
        --vdb cloud.vdb --out cycles.exr [--world sky.exr | --nishita] \
        [--lights both|sun|sky|ground] [--samples 128] [--bounces 128] [--seed 1]

Everything comes from the grid's metadata, so the scene is the one skyrender rendered:
- the medium: the grid "density" is the extinction per metre; scattering = extinction (no
  absorption, as the raymarch assumes), the phase function the raymarch's dual-lobe
  Henyey-Greenstein as a mix of two Volume Scatter closures (g and g_back, weights 1 - w and
  w), with as many volume bounces as --bounces (multiple scattering in full). An export of
  several nested boxes (issue 46's field: grids "density", "density_1", ..., each holding its
  share of the field) becomes one volume object a grid, all with the same medium, each read
  from its own grid and marched at its own voxel; Cycles adds the densities of overlapping
  volumes, so it sees the field once;
- the sun: a sun lamp in the grid's sun direction with the sun's angular size and the
  illuminance the raymarch uses at the clouds. skyrender's units have illuminance 1 = pi x
  radiance 1 (shaders/common/lighting_shared.h); Cycles' sun strength is irradiance, and a
  white diffuse surface under strength S has radiance S / pi, so strength = pi x illuminance.
  The raymarch lights each altitude of a layer with the sun's light through the air down to
  it (a 3 degree sun: a third of the middle's at the base, 1.7 times at the top); the lamp
  takes the top's light and sheets of air that only the sun's shadow rays see take it down to
  each altitude's (sun_profile.py; --sun-profile flat: the middle's everywhere, as before);
- the sky: with --world, our own sky: an equirectangular EXR that skyrender rendered of the
  same scene with no clouds and no sun or moon disc (compare.sh: `camera.projection:
  equirectangular`, heading 90 so the image's centre is east, Blender's +x), the ground below
  the horizon as our composite draws it. Its R, G, B are radiance in skyrender's unit, which
  is Cycles' background radiance at strength 1 (the sun lamp carries the disc's light, so
  the world must not). With --nishita, Blender's own Nishita sky texture (Cycles world,
  single scattering) for the same sun elevation and azimuth, from the same altitude (the
  grid's light_altitude_m, where our world is rendered from), air, dust and ozone at their
  defaults and no sun disc: an independent check of the sky's colour. Its values are
  W/(m2 sr) weighted by the CIE functions (Blender's sky model), so strength 683 / 1e4 turns
  them into skyrender's radiance (1 = 1e4 cd/m2). Without --world or --nishita, the old
  constant world: radiance ambient_top above the horizon and ambient_bottom below (the
  palette's ambient the raymarch used so far);
- --lights sun or sky keeps only the sun lamp or only the world (both by default): light is
  additive, so the two renders split the cloud's light into sunlight and skylight; ground
  keeps only the world below the horizontal (the ground and the air in front of it), which
  says how much of the skylight comes from below;
- the camera: at the origin of the grid's frame (the camera's east-north-up, metres) with
  skyrender's view axes, vertical field of view and image size.
The film is transparent (opaque with --world-only, which drops the cloud), so the EXR holds the cloud alone, premultiplied (RGB the light the
cloud sends to the camera, A its opacity): what skyrender's `clouds` layer holds. No
denoising, no clamping, fixed seed.
"""
import argparse
import math
import os
import sys

import bpy
import mathutils
import pyopenvdb

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sun_profile import sun_profile  # noqa: E402  (beside this script; Blender runs it by path)


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_cycles.py")
    p.add_argument("--vdb", required=True, action="append",
                   help="the export (its first grid's metadata sets the light and camera); "
                        "repeated: more exports that do not overlap it (a field's clouds toward "
                        "the sun outside the view's boxes)")
    p.add_argument("--out", required=True)
    p.add_argument("--samples", type=int, default=128)
    p.add_argument("--bounces", type=int, default=128)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--world", help="equirectangular EXR of our sky (default: the constant ambient)")
    p.add_argument("--nishita", action="store_true",
                   help="Blender's Nishita sky texture as the world, for the grid's sun and altitude")
    p.add_argument("--lights", choices=("both", "sun", "sky", "ground"), default="both",
                   help="which light sources shine: both, the sun lamp only, the world only, "
                        "the world below the horizontal only")
    p.add_argument("--sun-profile", choices=("layers", "flat"), default="layers",
                   help="layers: the sun's light through the air at each altitude of the layer, "
                        "as the raymarch takes it (the default); flat: one illuminance, the "
                        "layer middle's, everywhere (the reference before issue 46's ninth "
                        "session)")
    p.add_argument("--step-rate", type=float, default=1.0,
                   help="Cycles' volume step as a fraction of the voxel (checks the marching's bias)")
    p.add_argument("--world-only", action="store_true",
                   help="no cloud and an opaque film: the camera sees the world itself (checks "
                        "the world's orientation and units against skyrender's own view)")
    return p.parse_args(argv)


def grids(path):
    """The density grids of an export, {name: metadata}, "density" first."""
    found = {g.name: dict(g.metadata) for g in pyopenvdb.readAllGridMetadata(path)
             if g.name == "density" or g.name.startswith("density_")}
    if "density" not in found:
        raise SystemExit(f"error: {path}: no grid named 'density' (not written by skyrender export-volume?)")
    return dict(sorted(found.items(), key=lambda kv: int(kv[1].get("grid_index", 0))))


def metadata(path):
    return grids(path)["density"]


def volume_material(m, grid="density"):
    mat = bpy.data.materials.new("cloud_" + grid)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    density = nt.nodes.new("ShaderNodeAttribute")
    density.attribute_name = grid
    forward = nt.nodes.new("ShaderNodeVolumeScatter")
    back = nt.nodes.new("ShaderNodeVolumeScatter")
    forward.inputs["Anisotropy"].default_value = m["phase_g"]
    back.inputs["Anisotropy"].default_value = m["phase_g_back"]
    for node in (forward, back):
        node.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        nt.links.new(density.outputs["Fac"], node.inputs["Density"])
    mix = nt.nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = m["phase_back_weight"]
    nt.links.new(forward.outputs[0], mix.inputs[1])
    nt.links.new(back.outputs[0], mix.inputs[2])
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(mix.outputs[0], out.inputs["Volume"])
    return mat


def air_sheet(scene, name, z0, z1, half, sigma):
    """A box from z0 to z1, half metres wide each way, of air that absorbs sigma (RGB, per
    metre) along shadow rays only (sun_profile.py): its object is visible to shadow rays
    alone, and its density is gated by Light Path's Is Shadow Ray besides."""
    mesh = bpy.data.meshes.new(name)
    verts = [(x, y, z) for z in (z0, z1) for y in (-half, half) for x in (-half, half)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    mesh.from_pydata(verts, [], faces)
    mesh.update()
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.cycles.homogeneous_volume = True
    nt = mat.node_tree
    nt.nodes.clear()
    density = max(sigma)
    absorb = nt.nodes.new("ShaderNodeVolumeAbsorption")
    # Cycles: sigma_a = density x (1 - colour), per channel.
    absorb.inputs["Color"].default_value = tuple(1.0 - c / density for c in sigma) + (1.0,)
    path = nt.nodes.new("ShaderNodeLightPath")
    gate = nt.nodes.new("ShaderNodeMath")
    gate.operation = "MULTIPLY"
    gate.inputs[1].default_value = density
    nt.links.new(path.outputs["Is Shadow Ray"], gate.inputs[0])
    nt.links.new(gate.outputs[0], absorb.inputs["Density"])
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(absorb.outputs[0], out.inputs["Volume"])
    mesh.materials.append(mat)
    obj = bpy.data.objects.new(name, mesh)
    obj.visible_camera = False
    obj.visible_diffuse = False
    obj.visible_glossy = False
    obj.visible_transmission = False
    obj.visible_volume_scatter = False
    obj.visible_shadow = True
    scene.collection.objects.link(obj)
    return obj


def render(scene, path):
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def add_images(sun, sky, out):
    """out = the sun's render plus the sky's (RGB: the light each sends; A: the cloud's
    opacity, the same cloud in both, so their mean), and the two parts removed."""
    import os
    import numpy as np
    import OpenImageIO as oiio
    a, b = oiio.ImageBuf(sun), oiio.ImageBuf(sky)
    pa, pb = a.get_pixels(oiio.FLOAT), b.get_pixels(oiio.FLOAT)
    if pa is None or pb is None or pa.shape != pb.shape:
        raise SystemExit(f"error: cannot add {sun} and {sky}: {a.geterror() or b.geterror()}")
    total = pa + pb
    total[..., 3] = 0.5 * (pa[..., 3] + pb[..., 3])
    spec = a.spec()
    spec.set_format(oiio.FLOAT)
    result = oiio.ImageBuf(spec)
    result.set_pixels(oiio.ROI(0, spec.width, 0, spec.height, 0, 1, 0, spec.nchannels),
                      np.ascontiguousarray(total, dtype=np.float32))
    if not result.write(out + ".part.exr", "float"):
        raise SystemExit(f"error: cannot write {out}: {result.geterror()}")
    os.replace(out + ".part.exr", out)
    os.remove(sun)
    os.remove(sky)


def black_world():
    w = bpy.data.worlds.new("black")
    w.use_nodes = True
    w.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    return w


def link_world(nt, color, background, below_only):
    """Feeds `color` to the world's background and the background to its output; with
    `below_only`, only below the horizontal (in a world shader "Generated" is the view
    direction: the colour is kept where its z < 0)."""
    out = nt.nodes.new("ShaderNodeOutputWorld")
    if below_only:
        coords = nt.nodes.new("ShaderNodeTexCoord")
        xyz = nt.nodes.new("ShaderNodeSeparateXYZ")
        below = nt.nodes.new("ShaderNodeMath")
        below.operation = "LESS_THAN"
        below.inputs[1].default_value = 0.0
        mask = nt.nodes.new("ShaderNodeMixRGB")
        mask.blend_type = "MULTIPLY"
        mask.inputs["Fac"].default_value = 1.0
        nt.links.new(coords.outputs["Generated"], xyz.inputs[0])
        nt.links.new(xyz.outputs["Z"], below.inputs[0])
        nt.links.new(color, mask.inputs["Color1"])
        nt.links.new(below.outputs[0], mask.inputs["Color2"])
        color = mask.outputs["Color"]
    nt.links.new(color, background.inputs["Color"])
    nt.links.new(background.outputs[0], out.inputs["Surface"])


def sky_world(path, below_only=False):
    # Cycles maps a direction d to the equirectangular u = 0.5 - atan2(d.y, d.x) / 2 pi and
    # v = elevation / pi + 0.5 (v up): the image's centre looks along +x, azimuth grows to the
    # right (clockwise seen from above, as skyrender's does) and the top row is the zenith.
    # compare.sh renders our sky with heading 90 (east, our +x) at the centre, so no rotation;
    # it checks that with --world-only against skyrender's own perspective view of the sky.
    w = bpy.data.worlds.new("our_sky")
    w.use_nodes = True
    nt = w.node_tree
    nt.nodes.clear()
    image = bpy.data.images.load(path)
    image.colorspace_settings.name = "Linear"  # scene-linear Rec.709, Blender 3.4's name
    texture = nt.nodes.new("ShaderNodeTexEnvironment")
    texture.image = image
    texture.interpolation = "Linear"
    texture.projection = "EQUIRECTANGULAR"
    background = nt.nodes.new("ShaderNodeBackground")
    background.inputs["Strength"].default_value = 1.0
    link_world(nt, texture.outputs["Color"], background, below_only)
    # Importance-sample the map: the aureole around a low sun is small and bright.
    w.cycles.sampling_method = "MANUAL"
    w.cycles.sample_map_resolution = max(image.size[0], 256)
    return w


def nishita_world(m, below_only=False):
    # Blender 3.4's sky texture puts its sun at azimuth sun_rotation, clockwise from +y (north)
    # seen from above, as ours is measured (checked by rendering it toward each azimuth).
    w = bpy.data.worlds.new("nishita")
    w.use_nodes = True
    nt = w.node_tree
    nt.nodes.clear()
    sky = nt.nodes.new("ShaderNodeTexSky")
    sky.sky_type = "NISHITA"
    sky.sun_disc = False
    sky.sun_elevation = math.radians(m["sun_elevation_deg"])
    sky.sun_rotation = math.radians(m["sun_azimuth_deg"])
    sky.altitude = float(m["light_altitude_m"])
    sky.air_density = sky.dust_density = sky.ozone_density = 1.0
    background = nt.nodes.new("ShaderNodeBackground")
    # W/(m2 sr), CIE-weighted, to skyrender's unit of 1e4 cd/m2: 683 lm/W / 1e4.
    background.inputs["Strength"].default_value = 683.0 / 1.0e4
    link_world(nt, sky.outputs["Color"], background, below_only)
    w.cycles.sampling_method = "MANUAL"
    w.cycles.sample_map_resolution = 1024
    return w


def constant_world(m):
    w = bpy.data.worlds.new("sky")
    w.use_nodes = True
    nt = w.node_tree
    nt.nodes.clear()
    # In a world shader "Generated" is the view direction; its z says above or below.
    coords = nt.nodes.new("ShaderNodeTexCoord")
    xyz = nt.nodes.new("ShaderNodeSeparateXYZ")
    above = nt.nodes.new("ShaderNodeMath")
    above.operation = "GREATER_THAN"
    above.inputs[1].default_value = 0.0
    mix = nt.nodes.new("ShaderNodeMixRGB")
    top, bottom = m["ambient_top"], m["ambient_bottom"]
    mix.inputs["Color1"].default_value = (bottom[0], bottom[1], bottom[2], 1.0)
    mix.inputs["Color2"].default_value = (top[0], top[1], top[2], 1.0)
    background = nt.nodes.new("ShaderNodeBackground")
    background.inputs["Strength"].default_value = 1.0
    out = nt.nodes.new("ShaderNodeOutputWorld")
    nt.links.new(coords.outputs["Generated"], xyz.inputs[0])
    nt.links.new(xyz.outputs["Z"], above.inputs[0])
    nt.links.new(above.outputs[0], mix.inputs["Fac"])
    nt.links.new(mix.outputs["Color"], background.inputs["Color"])
    nt.links.new(background.outputs[0], out.inputs["Surface"])
    return w


def main():
    args = parse_args()
    m = metadata(args.vdb[0])
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.unit_settings.system = "METRIC"
    scene.unit_settings.scale_length = 1.0

    # The volume, in the grid's own transform (metres in the camera's east-north-up frame,
    # which is Blender's x, y, z): one object a grid, each reading its own grid of the file
    # (Cycles loads only the grids a shader asks for) and marched at its own voxel.
    if not args.world_only:
        parts = [(i, path, name, g) for i, path in enumerate(args.vdb)
                 for name, g in grids(path).items()]
        for i, path, name, g in parts:
            volume = bpy.data.volumes.new(f"cloud_{i}_{name}")
            volume.filepath = path
            volume.render.space = "WORLD"
            # One grid: automatic (its voxel, as before issue 46); several: each its own, not
            # the finest of the file's.
            volume.render.step_size = float(g["voxel_m"]) if len(parts) > 1 else 0.0
            # Several: no voxel is empty space however thin. Blender's default clipping (0.001)
            # leaves voxels below it out of the volume's bounds, and a grid that holds its
            # share of the far field's thin haze would lose it where nothing denser is near.
            if len(parts) > 1:
                volume.render.clipping = 0.0
            volume.render.precision = "FULL"
            volume.materials.append(volume_material(m, name))
            obj = bpy.data.objects.new(f"cloud_{i}_{name}", volume)
            # Blender 3.4 places a voxel's value half a voxel further along x, y and z than
            # OpenVDB's transform does (a 4-voxel cube of voxel centres 0.5..3.5 rendered
            # centred at 2.5 on all three axes, measured): move the object back by half a voxel
            # so Cycles' cloud lies where skyrender's does (issue 46; before, the far field's
            # 250 m voxels put its clouds a third of a pixel up and right).
            obj.location = tuple(-0.5 * float(g["voxel_m"]) for _ in range(3))
            scene.collection.objects.link(obj)

    # The sun: its lamp shines along its local -z, so +z points at the sun.
    sheets, sun_objects = [], []
    if args.lights in ("both", "sun"):
        metas = [g for path in args.vdb for g in grids(path).values()]
        e, sheets = sun_profile(m, metas, args.sun_profile == "flat")
        if sheets:
            # Wide enough for the sun's path from the lowest sheet to the highest, past every box.
            reach = max(abs(float(c)) for g in metas for k in ("box_min_m", "box_max_m")
                        for c in g[k][:2])
            rise = sheets[-1][1] - sheets[0][0]
            half = 2.0 * reach + rise / math.tan(math.radians(float(m["sun_elevation_deg"]))) + 1.0e4
            for k, (z0, z1, sigma) in enumerate(sheets):
                if max(sigma) > 0.0:
                    sun_objects.append(air_sheet(scene, f"sun_air_{k}", z0, z1, half, sigma))
        peak = max(e)
        light = bpy.data.lights.new("sun", "SUN")
        # With sheets the sun reaches the clouds through shadow rays alone (sun_profile.py).
        light.cycles.use_multiple_importance_sampling = not sheets
        light.energy = math.pi * peak
        light.color = tuple(c / peak for c in e) if peak > 0 else (1.0, 1.0, 1.0)
        light.angle = 2.0 * math.radians(m["sun_angular_radius_deg"])
        sun = bpy.data.objects.new("sun", light)
        sun.rotation_mode = "QUATERNION"
        sun.rotation_quaternion = mathutils.Vector(m["sun_direction"]).to_track_quat("Z", "Y")
        scene.collection.objects.link(sun)
        sun_objects.append(sun)
    if args.world and args.nishita:
        sys.exit("error: --world and --nishita are two worlds: give one")
    if args.lights == "sun":
        scene.world = black_world()
    elif args.world:
        scene.world = sky_world(args.world, below_only=args.lights == "ground")
    elif args.nishita:
        scene.world = nishita_world(m, below_only=args.lights == "ground")
    elif args.lights == "ground":
        sys.exit("error: --lights ground needs --world or --nishita")
    else:
        scene.world = constant_world(m)

    # The camera: Blender's camera looks along its -z with +y up and +x right.
    cam = bpy.data.cameras.new("camera")
    width, height = int(m["camera_width"]), int(m["camera_height"])
    cam.sensor_fit = "VERTICAL"
    cam.sensor_height = 24.0
    tan_v = math.tan(0.5 * math.radians(m["camera_vertical_fov_deg"]))
    cam.lens = 0.5 * cam.sensor_height / tan_v
    cam.clip_start = 0.1
    cam.clip_end = 1.0e6
    camera = bpy.data.objects.new("camera", cam)
    right = mathutils.Vector(m["camera_right"]).normalized()
    up = mathutils.Vector(m["camera_up"]).normalized()
    forward = mathutils.Vector(m["camera_forward"]).normalized()
    rotation = mathutils.Matrix((right, up, -forward)).transposed()  # columns: x, y, z
    camera.matrix_world = rotation.to_4x4()
    scene.collection.objects.link(camera)
    scene.camera = camera

    scene.render.engine = "CYCLES"
    scene.render.resolution_x = width
    scene.render.resolution_y = height
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = not args.world_only
    scene.render.threads_mode = "AUTO"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args.samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.seed = args.seed
    c.max_bounces = args.bounces
    c.volume_bounces = args.bounces
    c.diffuse_bounces = 0
    c.glossy_bounces = 0
    c.transmission_bounces = 0
    # Cycles counts a shadow ray's crossings of volume bounds as transparent hits and takes a
    # ray with more than this many as blocked: the field's nested boxes and shadow exports,
    # and two faces of each of the sun's air sheets (sun_profile.py).
    c.transparent_max_bounces = 64 + 2 * len(sheets)
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.volume_step_rate = args.step_rate
    c.volume_max_steps = 4096
    c.caustics_reflective = True
    c.caustics_refractive = True
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.image_settings.exr_codec = "ZIP"
    if sheets and args.lights == "both" and not args.world_only:
        # The sun through its sheets under a black world, then the world alone (sun_profile.py).
        sky = scene.world
        scene.world = black_world()
        render(scene, args.out + ".sun.exr")
        scene.world = sky
        for obj in sun_objects:
            obj.hide_render = True
        render(scene, args.out + ".sky.exr")
        add_images(args.out + ".sun.exr", args.out + ".sky.exr", args.out)
    else:
        render(scene, args.out)
    world = "none" if args.lights == "sun" else (
        args.world or ("Nishita" if args.nishita else "constant ambient"))
    profile = f"sun through {len(sheets)} air sheets" if sheets else "flat sun"
    print(f"wrote {args.out} ({width}x{height}, {args.samples} samples, {args.bounces} bounces, "
          f"lights {args.lights}, world {world}, {profile})")


main()
