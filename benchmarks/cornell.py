"""cornell.py: the diffuse Cornell box that gi_vs_cycles.py renders with RayDrive and with
Cycles: one scene description, written out as RIB for RayDrive and built through bpy for
Cycles (imported by cycles_render.py inside Blender).

Coordinates are RIB's camera space (left-handed: x right, y up, z forward, camera at the
origin). Blender is right-handed with its camera looking down its -z: its scene is this
one with x negated (a mirror image, so its picture is the same picture), and its camera
is turned half a turn about y.

Radiometry: the RIB's surface (diffuse_gi.sl) is Ci = Kd Cs (diffuse(Nf) + trace(P, d))
with d cosine-distributed, and a point light of intensity I gives Cl = I / d^2. A
Lambertian surface of albedo Kd Cs under a point light of radiant intensity J reflects
Kd Cs J cos / (pi d^2), and cosine-weighted sampling makes its indirect part
Kd Cs E[L_in]: the two agree when J = pi I. Blender's point light of power P has
J = P / (4 pi), so P = 4 pi^2 I.
"""
import math

RES = 256
FOV = 50.0
LIGHT = (0.0, 0.9, 3.0)
INTENSITY = 1.0

WHITE = (0.75, 0.75, 0.75)
RED = (0.75, 0.15, 0.12)
GREEN = (0.15, 0.65, 0.15)


def _quad(a, b, c, d):
    return [a, b, c, d]


def _box(cx, cz, w, h, angle_deg):
    """The five visible faces of a w x w x h block standing on the floor (y = -1)."""
    a = math.radians(angle_deg)
    ca, sa = math.cos(a), math.sin(a)
    def p(x, y, z):
        return (cx + ca * x - sa * z, y, cz + sa * x + ca * z)
    r, y0, y1 = w / 2, -1.0, -1.0 + h
    c = [(-r, -r), (r, -r), (r, r), (-r, r)]
    faces = [[p(x, y1, z) for x, z in c]]  # top
    for i in range(4):
        (x0, z0), (x1, z1) = c[i], c[(i + 1) % 4]
        faces.append([p(x0, y0, z0), p(x1, y0, z1), p(x1, y1, z1), p(x0, y1, z0)])
    return faces


def load_mesh(path):
    """A triangle mesh from an OFF file, scaled and placed on the floor in the middle of
    the box (its longest side 1.2 units) in place of the two blocks: (points, triangles)."""
    with open(path) as f:
        words = f.read().split()
    if not words or words[0] != "OFF":
        raise ValueError(path + ": not an OFF file")
    nv, nf = int(words[1]), int(words[2])
    at = 4
    pts = []
    for _ in range(nv):
        pts.append(tuple(float(w) for w in words[at:at + 3]))
        at += 3
    tris = []
    for _ in range(nf):
        k = int(words[at])
        idx = [int(w) for w in words[at + 1:at + 1 + k]]
        at += 1 + k
        tris += [(idx[0], idx[i], idx[i + 1]) for i in range(1, k - 1)]
    lo = [min(p[i] for p in pts) for i in range(3)]
    hi = [max(p[i] for p in pts) for i in range(3)]
    s = 1.2 / max(hi[i] - lo[i] for i in range(3))
    mid = [(lo[i] + hi[i]) / 2 for i in range(3)]
    pts = [((p[0] - mid[0]) * s, -1.0 + (p[1] - lo[1]) * s, 3.0 + (p[2] - mid[2]) * s) for p in pts]
    return pts, tris


def quads(with_blocks=True):
    """(colour, [four corners]) of every face."""
    lo, hi, z0, z1 = -1.0, 1.0, 1.8, 4.0
    walls = [
        (WHITE, _quad((lo, lo, z0), (hi, lo, z0), (hi, lo, z1), (lo, lo, z1))),  # floor
        (WHITE, _quad((lo, hi, z0), (lo, hi, z1), (hi, hi, z1), (hi, hi, z0))),  # ceiling
        (WHITE, _quad((lo, lo, z1), (hi, lo, z1), (hi, hi, z1), (lo, hi, z1))),  # back
        (RED, _quad((lo, lo, z0), (lo, lo, z1), (lo, hi, z1), (lo, hi, z0))),    # left
        (GREEN, _quad((hi, lo, z0), (hi, hi, z0), (hi, hi, z1), (hi, lo, z1))),  # right
    ]
    if not with_blocks:
        return walls
    blocks = [(WHITE, f) for f in _box(0.35, 2.9, 0.6, 0.6, -18)]
    blocks += [(WHITE, f) for f in _box(-0.35, 3.3, 0.6, 1.2, 17)]
    return walls + blocks


def rib(image, samples, depth, shader_dir, mesh=None):
    """The scene as RIB: samples a pixel (PixelSamples s s with s^2 = samples, every pixel
    sampled to the limit: pixelerror 1e-6), traced rays up to depth bounces."""
    s = max(1, int(round(math.sqrt(samples))))
    out = [
        'Option "searchpath" "shader" ["%s:&"]' % shader_dir,
        'Option "render" "float pixelerror" [1e-6]',
        'Display "%s" "openexr" "rgba"' % image,
        "Format %d %d 1" % (RES, RES),
        "PixelSamples %d %d" % (s, s),
        'PixelFilter "box" 1 1',
        'Projection "perspective" "fov" [%g]' % FOV,
        "WorldBegin",
        'Attribute "trace" "maxspeculardepth" [%d]' % depth,
        'LightSource "pointlight" 1 "from" [%g %g %g] "intensity" [%g]' % (LIGHT + (INTENSITY,)),
        'Surface "diffuse_gi"',
    ]
    for colour, q in quads(mesh is None):
        pts = " ".join("%.6f %.6f %.6f" % v for v in q)
        out.append("Color [%g %g %g]" % colour)
        out.append('Polygon "P" [%s]' % pts)
    if mesh is not None:
        pts, tris = load_mesh(mesh)
        out.append("Color [%g %g %g]" % WHITE)
        out.append('PointsPolygons [%s] [%s] "P" [%s]' % (
            " ".join("3" for _ in tris), " ".join("%d %d %d" % t for t in tris),
            " ".join("%.6f %.6f %.6f" % p for p in pts)))
    out.append("WorldEnd")
    return "\n".join(out) + "\n"


def build_blender(bpy, samples, depth, threads, seed, mesh=None):
    """The same scene in a fresh Blender file, rendered by Cycles on the CPU: path tracing
    with depth diffuse bounces, no adaptive sampling, no denoising, no clamping,
    a one-pixel box filter (as the RIB's PixelFilter)."""
    from mathutils import Euler
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device = "CPU"
    cy.samples = samples
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.max_bounces = depth
    cy.diffuse_bounces = depth
    cy.glossy_bounces = cy.transmission_bounces = cy.volume_bounces = cy.transparent_max_bounces = 0
    cy.sample_clamp_direct = cy.sample_clamp_indirect = 0.0
    cy.caustics_reflective = cy.caustics_refractive = False
    cy.seed = seed
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    scene.render.threads_mode = "FIXED"
    scene.render.threads = threads
    scene.render.resolution_x = scene.render.resolution_y = RES
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    materials = {}
    faces_in = list(quads(mesh is None))
    if mesh is not None:
        materials_needed = [c for c, _ in faces_in] + [WHITE]
    else:
        materials_needed = [c for c, _ in faces_in]
    for colour in materials_needed:
        if colour not in materials:
            m = bpy.data.materials.new("c%d" % len(materials))
            m.use_nodes = True
            nodes = m.node_tree.nodes
            nodes.clear()
            bsdf = nodes.new("ShaderNodeBsdfDiffuse")
            bsdf.inputs["Color"].default_value = colour + (1.0,)
            bsdf.inputs["Roughness"].default_value = 0.0
            out = nodes.new("ShaderNodeOutputMaterial")
            m.node_tree.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
            materials[colour] = m
    verts, faces, face_mat, mats = [], [], [], list(materials)
    for colour, q in faces_in:
        faces.append(tuple(range(len(verts), len(verts) + 4)))
        verts += [(-x, y, z) for x, y, z in q]
        face_mat.append(mats.index(colour))
    if mesh is not None:
        pts, tris = load_mesh(mesh)
        base = len(verts)
        verts += [(-x, y, z) for x, y, z in pts]
        faces += [(base + a, base + b, base + c) for a, b, c in tris]
        face_mat += [mats.index(WHITE)] * len(tris)
    mesh = bpy.data.meshes.new("box")
    mesh.from_pydata(verts, [], faces)
    for m in mats:
        mesh.materials.append(materials[m])
    for poly, mi in zip(mesh.polygons, face_mat):
        poly.material_index = mi
    obj = bpy.data.objects.new("box", mesh)
    scene.collection.objects.link(obj)
    light = bpy.data.lights.new("point", "POINT")
    light.energy = 4.0 * math.pi ** 2 * INTENSITY
    light.shadow_soft_size = 0.0
    lo = bpy.data.objects.new("point", light)
    lo.location = (-LIGHT[0], LIGHT[1], LIGHT[2])
    scene.collection.objects.link(lo)
    cam = bpy.data.cameras.new("cam")
    cam.angle = math.radians(FOV)
    cam.clip_start = 0.01
    co = bpy.data.objects.new("cam", cam)
    co.rotation_euler = Euler((0.0, math.pi, 0.0))
    scene.collection.objects.link(co)
    scene.camera = co
    return scene
