"""The material conformance suite: small Mitsuba 3 scenes, one per BSDF and texture kind lucent
reads from Mitsuba XML, and Mitsuba's own images of them.

    bench/peers/run.sh conformance write          # the scenes and their textures
    bench/peers/run.sh conformance refs           # Mitsuba's references (minutes)
    bench/peers/run.sh conformance compare        # lucent against them, a table

The scenes, textures and references live in crates/lucent-scene/tests/conformance/, where the
test `conformance` holds lucent's images to the references: every 8x8 block's mean and the
whole image's mean, per channel, within 2% (relative to the block's own mean, or to a tenth of
the image's mean where the block is darker than that). `refs` renders each scene with Mitsuba
3.9.1 `llvm_ad_rgb` at 16384 samples per pixel (rough glass at 65536), 64x64, box filter, and writes half-float EXRs
with a manifest (`references.json`) saying how each was made.
"""
import argparse
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path = [p for p in sys.path if os.path.abspath(p or ".") != HERE]
import numpy as np  # noqa: E402

ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
SUITE = os.path.join(ROOT, "crates", "lucent-scene", "tests", "conformance")
SIZE = 64
REF_SPP = 16384

# ----------------------------------------------------------------------------------------------
# Textures (written as 8-bit PNGs; deterministic).


def checker(n=64, cells=8):
    y, x = np.mgrid[0:n, 0:n]
    c = ((x * cells // n) + (y * cells // n)) % 2
    img = np.where(c[..., None] == 0, [0.85, 0.8, 0.7], [0.15, 0.25, 0.4])
    return img


def stripes(n=64):
    """Roughness: 0.05 to 0.6 across u, smooth."""
    x = np.linspace(0.0, 1.0, n)[None, :].repeat(n, 0)
    return (0.05 + 0.55 * x)[..., None].repeat(3, 2)


def bumps(n=64):
    """A height field of round bumps, in [0, 1]."""
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n
    h = 0.5 + 0.25 * (np.sin(2 * np.pi * 4 * x) + np.sin(2 * np.pi * 4 * y))
    return h[..., None].repeat(3, 2)


def normals(n=64):
    """The normal map of the bumps (their gradient), encoded as 0.5 + n/2."""
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n
    k = 0.35
    dx = k * np.cos(2 * np.pi * 4 * x)
    dy = k * np.cos(2 * np.pi * 4 * y)
    nrm = np.stack([-dx, -dy, np.ones_like(dx)], -1)
    nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    return 0.5 + 0.5 * nrm


def mask(n=64):
    """Opacity: a disc of 1 in a field of 0, with a soft ramp."""
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n
    r = np.hypot(x - 0.5, y - 0.5)
    return np.clip((0.4 - r) / 0.05, 0.0, 1.0)[..., None].repeat(3, 2)


def sky(w=64, h=32):
    """An environment (linear, for an EXR): a blue-to-white sky over a brown ground, a band
    of colour that changes around the horizon (so that a turn shows), and a soft sun."""
    y, x = (np.mgrid[0:h, 0:w] + 0.5) / np.array([h, w])[:, None, None]
    theta, phi = y * np.pi, x * 2 * np.pi
    up = np.clip(np.cos(theta), 0, 1)[..., None]
    img = up * np.array([0.3, 0.5, 1.0]) + (1 - up) * np.array([0.9, 0.9, 0.85])
    ground = (theta > np.pi / 2)[..., None]
    img = np.where(ground, np.array([0.25, 0.18, 0.1]), img)
    band = np.exp(-(((theta - np.pi / 2) / 0.25) ** 2))[..., None]
    img = img + band * 0.6 * np.stack([0.5 + 0.5 * np.sin(phi), 0.5 + 0.5 * np.cos(2 * phi), 0.5 - 0.5 * np.sin(phi)], -1)
    sun = np.exp(-(((theta - 0.7) ** 2 + (phi - 4.0) ** 2) / 0.02))[..., None]
    return img + sun * 30.0


def write_exr(path, img):
    import mitsuba as mi

    mi.Bitmap(img.astype(np.float32), pixel_format=mi.Bitmap.PixelFormat.RGB).write(path)


EXR_TEXTURES = {"sky.exr": sky}

TEXTURES = {
    "checker.png": checker,
    "roughness.png": stripes,
    "height.png": bumps,
    "normals.png": normals,
    "mask.png": mask,
}


def write_png(path, img):
    import mitsuba as mi

    data = np.clip(np.round(img * 255.0), 0, 255).astype(np.uint8)
    mi.Bitmap(data, pixel_format=mi.Bitmap.PixelFormat.RGB).write(path)


# ----------------------------------------------------------------------------------------------
# Scenes.

HEAD = """<scene version="3.0.0">
    <default name="spp" value="64"/>
    <integrator type="path"><integer name="max_depth" value="12"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="{fov}"/>
        <transform name="to_world"><lookat origin="{eye}" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="{size}"/><integer name="height" value="{size}"/>
            <rfilter type="box"/>
        </film>
    </sensor>
{lights}"""

# The sky and the sun. The sun is a small sphere, not a directional light: under a delta sun,
# glossy highlights and light refracted into rough glass (found only by light sampling through
# a narrow lobe) are too noisy for any sample count here; a sphere is found by both techniques
# and weighed by multiple importance sampling.
SKY_AND_SUN = """    <emitter type="constant"><rgb name="radiance" value="0.25"/></emitter>
    <shape type="sphere">
        <point name="center" x="5" y="9" z="7"/><float name="radius" value="1"/>
        <emitter type="area"><rgb name="radiance" value="40"/></emitter>
    </shape>
"""
# The sun as a directional light, for the cases without glossy highlights.
SKY_AND_DIRECTIONAL_SUN = """    <emitter type="constant"><rgb name="radiance" value="0.25"/></emitter>
    <emitter type="directional">
        <vector name="direction" x="-0.5" y="-0.9" z="-0.7"/>
        <rgb name="irradiance" value="3"/>
    </emitter>
"""
# The uniform sky of radiance 1 alone (the roughplastic floor of issue 18's report).
SKY = """    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
"""

# A checkered floor: something for mirrors to reflect and glass to bend.
FLOOR = """    <shape type="rectangle">
        <transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/><translate y="{y}"/></transform>
        <bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
            <rgb name="color0" value="0.6"/><rgb name="color1" value="0.15"/>
            <transform name="to_uv"><scale x="8" y="8"/></transform>
        </texture></bsdf>
    </shape>
"""

# The ball: a unit sphere on the floor, its pole turned to +y (so that anisotropic roughness,
# which follows the sphere's longitude, runs around the vertical axis).
BALL = FLOOR.format(y=-1) + """    <shape type="sphere">
        <transform name="to_world"><rotate x="1" angle="-90"/></transform>
        {bsdf}
    </shape>
</scene>
"""

# The plane: a 4x4 square tilted back 60 degrees, above the floor.
PLANE = FLOOR.format(y=-1.5) + """    <shape type="rectangle">
        <transform name="to_world"><scale value="2"/><rotate x="1" angle="-60"/></transform>
        {bsdf}
    </shape>
</scene>
"""

# The ball alone, for rough glass: the light it focuses onto a floor from the small sun is a
# caustic that path tracing finds only by chance.
LONE_BALL = BALL[BALL.index("    <shape type=\"sphere\">"):]

# The plane alone, for the mask: Mitsuba's shadow rays are stopped by the parts a mask cuts
# away and lucent's are not (docs/materials.md), so nothing lies in its shadow here.
LONE_PLANE = PLANE[PLANE.index("    <shape type=\"rectangle\">\n        <transform name=\"to_world\"><scale value=\"2\"/>"):]


def bitmap(name, file, raw=False, extra=""):
    flag = '<boolean name="raw" value="true"/>' if raw else ""
    return (
        f'<texture type="bitmap" name="{name}"><string name="filename" value="../textures/{file}"/>'
        f"{flag}{extra}</texture>"
    )


def rough(kind, dist, alpha, inner=""):
    return (
        f'<bsdf type="{kind}"><string name="distribution" value="{dist}"/>'
        f'<float name="alpha" value="{alpha}"/>{inner}</bsdf>'
    )


GOLD = '<string name="material" value="Au"/>'
COPPER = '<string name="material" value="Cu"/>'
BASE = '<rgb name="diffuse_reflectance" value="0.55, 0.35, 0.2"/>'

CASES = {}
CASES["diffuse"] = (BALL, '<bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.3, 0.2"/></bsdf>')
CASES["conductor-gold"] = (BALL, f'<bsdf type="conductor">{GOLD}</bsdf>')
for dist in ["beckmann", "ggx"]:
    for alpha in [0.1, 0.4]:
        CASES[f"roughconductor-{dist}-{alpha}"] = (BALL, rough("roughconductor", dist, alpha, COPPER if dist == "ggx" else GOLD))
        CASES[f"roughdielectric-{dist}-{alpha}"] = (LONE_BALL, rough("roughdielectric", dist, alpha))
        CASES[f"roughplastic-{dist}-{alpha}"] = (BALL, rough("roughplastic", dist, alpha, BASE))
for dist in ["beckmann", "ggx"]:
    CASES[f"roughconductor-{dist}-anisotropic"] = (
        BALL,
        f'<bsdf type="roughconductor"><string name="distribution" value="{dist}"/>'
        f'<float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.4"/>'
        f'<string name="material" value="Ag"/></bsdf>',
    )
CASES["roughplastic-ggx-0.2-floor"] = (
    LONE_PLANE,
    '<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/>'
    '<rgb name="diffuse_reflectance" value="0.55"/></bsdf>',
)
CASES["roughplastic-nonlinear"] = (
    BALL,
    '<bsdf type="roughplastic"><float name="alpha" value="0.2"/><boolean name="nonlinear" value="true"/>'
    '<rgb name="diffuse_reflectance" value="0.8, 0.4, 0.1"/></bsdf>',
)
CASES["dielectric"] = (BALL, '<bsdf type="dielectric"/>')
CASES["thindielectric"] = (PLANE, '<bsdf type="thindielectric"><float name="int_ior" value="1.7"/></bsdf>')
CASES["plastic"] = (BALL, f'<bsdf type="plastic">{BASE}</bsdf>')
CASES["plastic-nonlinear"] = (
    BALL,
    '<bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.8, 0.4, 0.1"/>'
    '<boolean name="nonlinear" value="true"/></bsdf>',
)
CASES["bitmap"] = (PLANE, f'<bsdf type="diffuse">{bitmap("reflectance", "checker.png")}</bsdf>')
CASES["checkerboard"] = (
    PLANE,
    '<bsdf type="diffuse"><texture type="checkerboard" name="reflectance">'
    '<rgb name="color0" value="0.8, 0.7, 0.2"/><rgb name="color1" value="0.1, 0.2, 0.5"/>'
    '<transform name="to_uv"><scale x="4" y="4"/></transform></texture></bsdf>',
)
CASES["textured-roughness"] = (
    PLANE,
    '<bsdf type="roughconductor"><string name="distribution" value="ggx"/>'
    f'{bitmap("alpha", "roughness.png", raw=True)}{GOLD}</bsdf>',
)
CASES["normalmap"] = (
    PLANE,
    f'<bsdf type="normalmap">{bitmap("normalmap", "normals.png", raw=True)}'
    f'<bsdf type="roughplastic"><float name="alpha" value="0.1"/>{BASE}</bsdf></bsdf>',
)
CASES["bumpmap"] = (
    PLANE,
    f'<bsdf type="bumpmap">{bitmap("height", "height.png", raw=True)}<float name="scale" value="0.05"/>'
    f'<bsdf type="roughplastic"><float name="alpha" value="0.1"/>{BASE}</bsdf></bsdf>',
)
CASES["blendbsdf"] = (
    BALL,
    '<bsdf type="blendbsdf"><float name="weight" value="0.35"/>'
    '<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.4, 0.6"/></bsdf>'
    f'{rough("roughconductor", "ggx", 0.2, GOLD)}</bsdf>',
)
CASES["blendbsdf-textured"] = (
    PLANE,
    f'<bsdf type="blendbsdf">{bitmap("weight", "checker.png", raw=True)}'
    '<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.4, 0.6"/></bsdf>'
    f'{rough("roughconductor", "ggx", 0.2, COPPER)}</bsdf>',
)
CASES["mask"] = (
    LONE_PLANE,
    f'<bsdf type="mask">{bitmap("opacity", "mask.png", raw=True)}'
    '<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.3, 0.3"/></bsdf></bsdf>',
)
CASES["twosided"] = (
    PLANE.replace('angle="-60"', 'angle="120"'),
    '<bsdf type="twosided"><bsdf type="roughconductor"><float name="alpha" value="0.2"/>'
    f"{GOLD}</bsdf>"
    '<bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.2, 0.1"/></bsdf></bsdf>',
)

# The principled BSDFs at several settings: a dielectric base, a brushed metal, every layer at
# once (clearcoat, sheen, tints, flatness), partly transmissive, textured, and the thin sheet.
CASES["principled"] = (
    BALL,
    '<bsdf type="principled"><rgb name="base_color" value="0.8, 0.3, 0.2"/></bsdf>',
)
CASES["principled-metal-anisotropic"] = (
    BALL,
    '<bsdf type="principled"><rgb name="base_color" value="0.9, 0.7, 0.3"/>'
    '<float name="metallic" value="1"/><float name="roughness" value="0.35"/>'
    '<float name="anisotropic" value="0.6"/></bsdf>',
)
CASES["principled-layers"] = (
    BALL,
    '<bsdf type="principled"><rgb name="base_color" value="0.2, 0.45, 0.7"/>'
    '<float name="roughness" value="0.4"/><float name="metallic" value="0.3"/>'
    '<float name="spec_tint" value="0.5"/><float name="sheen" value="1"/>'
    '<float name="sheen_tint" value="0.5"/><float name="flatness" value="0.5"/>'
    '<float name="clearcoat" value="1"/><float name="clearcoat_gloss" value="0.7"/>'
    '<float name="specular" value="0.7"/></bsdf>',
)
CASES["principled-transmissive"] = (
    BALL,
    '<bsdf type="principled"><rgb name="base_color" value="0.9, 0.8, 0.6"/>'
    '<float name="spec_trans" value="0.7"/><float name="roughness" value="0.3"/>'
    '<float name="eta" value="1.45"/></bsdf>',
)
CASES["principled-textured"] = (
    PLANE,
    f'<bsdf type="principled">{bitmap("base_color", "checker.png")}'
    f'{bitmap("roughness", "checker.png", raw=True)}<float name="metallic" value="0.5"/></bsdf>',
)
CASES["principledthin"] = (
    PLANE,
    '<bsdf type="principledthin"><rgb name="base_color" value="0.7, 0.5, 0.3"/>'
    '<float name="roughness" value="0.3"/><float name="spec_trans" value="0.4"/>'
    '<float name="diff_trans" value="0.8"/><float name="sheen" value="0.5"/>'
    '<float name="eta" value="1.4"/></bsdf>',
)

# The exact cylinder (Mitsuba's has no caps: its inside is seen through the top), placed by a
# to_world and checker-textured so that its texture coordinates are compared too. (A sphere
# scaled unevenly is not a case: Mitsuba warns and renders a sphere, lucent the ellipsoid.)
CYLINDER = FLOOR.format(y=-1) + """    <shape type="cylinder">
        <point name="p0" x="0" y="0" z="-1"/><point name="p1" x="0" y="0" z="0.6"/>
        <float name="radius" value="0.7"/>
        <transform name="to_world"><rotate x="1" angle="-90"/><rotate z="1" angle="15"/></transform>
        {bsdf}
    </shape>
</scene>
"""
CASES["shape-cylinder"] = (CYLINDER, f'<bsdf type="twosided"><bsdf type="diffuse">{bitmap("reflectance", "checker.png")}</bsdf></bsdf>')

# The sensors other than the pinhole: a diffuse ball seen through an orthographic view (its
# to_world's scale sizes the view) and through a thin lens focused on the ball's front.
DIFFUSE = '<bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.3, 0.2"/></bsdf>'
CASES["sensor-orthographic"] = (BALL, DIFFUSE)
CASES["sensor-thinlens"] = (BALL, DIFFUSE)
SENSORS = {
    "sensor-orthographic": """<sensor type="orthographic">
        <transform name="to_world"><scale x="1.8" y="1.8"/><lookat origin="0, 1.2, 4.2" target="0, 0, 0" up="0, 1, 0"/></transform>""",
    "sensor-thinlens": """<sensor type="thinlens">
        <float name="fov" value="28"/><float name="aperture_radius" value="0.12"/><float name="focus_distance" value="3.4"/>
        <transform name="to_world"><lookat origin="0, 1.2, 4.2" target="0, 0, 0" up="0, 1, 0"/></transform>""",
}
# The cases lit otherwise than by the sky and the spherical sun: smooth mirrors and glass (a
# small sun seen in a mirror, or focused by glass onto the floor, is found only by chance;
# a directional one is found by neither renderer) and the matte planes.
LIGHTS = {
    name: SKY_AND_DIRECTIONAL_SUN
    for name in [
        "diffuse",
        "conductor-gold",
        "dielectric",
        "thindielectric",
        "plastic",
        "plastic-nonlinear",
        "bitmap",
        "checkerboard",
        "mask",
        "twosided",
        "blendbsdf-textured",
        "sensor-orthographic",
        "sensor-thinlens",
    ]
}
LIGHTS["roughplastic-ggx-0.2-floor"] = SKY
# An image environment, turned: a glossy ball shows where its texels land, the floor what it
# sends.
CASES["emitter-envmap"] = (BALL, rough("roughconductor", "ggx", 0.1, COPPER))
LIGHTS["emitter-envmap"] = """    <emitter type="envmap">
        <string name="filename" value="../textures/sky.exr"/>
        <float name="scale" value="0.8"/>
        <transform name="to_world"><rotate y="1" angle="70"/><rotate x="1" angle="15"/></transform>
    </emitter>
"""


def scene_text(name):
    shape, bsdf = CASES[name]
    plane = "rectangle" in shape
    eye = "0, 2.5, 5.5" if plane else "0, 1.2, 4.2"
    fov = "42" if plane else "28"
    lights = LIGHTS.get(name, SKY_AND_SUN)
    head = HEAD.format(fov=fov, eye=eye, size=SIZE, lights=lights)
    if name in SENSORS:
        start = head.index("<sensor")
        end = head.index("\n", head.index("<transform name=\"to_world\">", start))
        head = head[:start] + SENSORS[name] + head[end:]
    return head + shape.format(bsdf=bsdf)


def write(_args):
    os.makedirs(os.path.join(SUITE, "scenes"), exist_ok=True)
    os.makedirs(os.path.join(SUITE, "textures"), exist_ok=True)
    for file, make in TEXTURES.items():
        write_png(os.path.join(SUITE, "textures", file), make())
    for file, make in EXR_TEXTURES.items():
        write_exr(os.path.join(SUITE, "textures", file), make())
    for name in CASES:
        with open(os.path.join(SUITE, "scenes", f"{name}.xml"), "w") as f:
            f.write(scene_text(name))
    print(f"wrote {len(CASES)} scenes and {len(TEXTURES)} textures to {SUITE}")


# ----------------------------------------------------------------------------------------------
# References.


def render_mitsuba(path, spp, seed=0):
    import drjit as dr
    import mitsuba as mi

    dr.set_thread_count(2)
    scene = mi.load_file(path, spp=spp)
    # Rendered in passes of 256 samples with their own seeds, to bound the LLVM wavefront.
    passes = max(1, spp // 256)
    acc = None
    for k in range(passes):
        img = np.array(mi.render(scene, spp=spp // passes, seed=seed + 7919 * k))
        acc = img if acc is None else acc + img
    return acc / passes


def refs(args):
    import mitsuba as mi

    mi.set_variant(args.variant)
    os.makedirs(os.path.join(SUITE, "references"), exist_ok=True)
    manifest_path = os.path.join(SUITE, "references.json")
    manifest = {}
    if os.path.exists(manifest_path):
        with open(manifest_path) as f:
            manifest = json.load(f)
    for name in args.only or CASES:
        scene = os.path.join(SUITE, "scenes", f"{name}.xml")
        with open(scene) as f:
            text = f.read()
        # Rough glass is the noisiest to converge (see LIGHTS): four times the samples.
        spp = args.spp * (4 if name.startswith("roughdielectric") else 1)
        key = {"spp": spp, "variant": args.variant, "mitsuba": mi.MI_VERSION, "scene": text}
        if not args.force and manifest.get(name, {}).get("key") == key:
            continue
        start = time.time()
        img = render_mitsuba(scene, spp, seed=1_000_003)
        out = os.path.join(SUITE, "references", f"{name}.exr")
        bitmap = mi.Bitmap(img.astype(np.float32), pixel_format=mi.Bitmap.PixelFormat.RGB)
        bitmap.convert(component_format=mi.Struct.Type.Float16).write(out)
        took = time.time() - start
        manifest[name] = {
            "key": key,
            "command": f"bench/peers/run.sh conformance refs --only {name} --spp {args.spp}",
            "spp": spp,
            "seconds": round(took, 2),
        }
        print(f"{name}: {took:.1f} s")
        with open(manifest_path, "w") as f:
            json.dump(manifest, f, indent=1, sort_keys=True)


# ----------------------------------------------------------------------------------------------
# Comparison (the same metric as the test).


def read_exr(path):
    import mitsuba as mi

    return np.array(mi.Bitmap(path).convert(component_format=mi.Struct.Type.Float32))[..., :3]


def block_error(img, ref, block=8):
    h, w, _ = ref.shape
    a = img.reshape(h // block, block, w // block, block, 3).mean((1, 3))
    b = ref.reshape(h // block, block, w // block, block, 3).mean((1, 3))
    floor = 0.1 * ref.mean(axis=(0, 1))
    blocks = np.abs(a - b) / np.maximum(b, floor)
    whole = np.abs(img.mean((0, 1)) - ref.mean((0, 1))) / ref.mean((0, 1))
    return blocks.max(), whole.max()


def compare(args):
    import subprocess
    import tempfile

    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    lucent = args.lucent or os.path.join(ROOT, "target", "release", "lucent")
    print(f"{'case':40} {'worst 8x8 block':>16} {'whole image':>12}")
    for name in args.only or CASES:
        scene = os.path.join(SUITE, "scenes", f"{name}.xml")
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "out.exr")
            cmd = [lucent, "render", scene, "--spp", str(args.spp), "-o", out, "--threads", "2"]
            subprocess.run(cmd, check=True, capture_output=True)
            img = read_exr(out)
        ref = read_exr(os.path.join(SUITE, "references", f"{name}.exr"))
        blocks, whole = block_error(img, ref)
        flag = "" if blocks <= 0.02 and whole <= 0.02 else "  <-- over 2%"
        print(f"{name:40} {100 * blocks:15.2f}% {100 * whole:11.2f}%{flag}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    sub.add_parser("write").set_defaults(run=write)
    r = sub.add_parser("refs")
    r.add_argument("--spp", type=int, default=REF_SPP)
    r.add_argument("--variant", default="llvm_ad_rgb")
    r.add_argument("--only", nargs="*")
    r.add_argument("--force", action="store_true")
    r.set_defaults(run=refs)
    c = sub.add_parser("compare")
    c.add_argument("--spp", type=int, default=256)
    c.add_argument("--lucent")
    c.add_argument("--only", nargs="*")
    c.set_defaults(run=compare)
    args = ap.parse_args()
    args.run(args)


if __name__ == "__main__":
    main()
