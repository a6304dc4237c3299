"""Mitsuba 3's RGB colours of spectra: the reference table of crates/lucent-scene/src/mitsuba/spectrum.rs.

    target/peers-venv/bin/python bench/peers/spectra.py                 # the Rust table
    target/peers-venv/bin/python bench/peers/spectra.py --render 4096   # and a spectral render of the black bodies

For every spectrum below, as a BSDF's reflectance and as an emitter's radiance, the script loads
a tiny scene with Mitsuba 3.9.1 `scalar_rgb` (`mi.load_string`) and reads the colour Mitsuba made
of it back through `mi.traverse`; it prints them as a Rust table.

`<spectrum type="blackbody">` loads in the RGB variants but does not render there ("not
implemented for non-spectral modes"): its rows are the colour the spectral variants see, the
integral over 360-830 nm of Mitsuba's own black body (`scalar_spectral`, the plugin's `eval`)
against Mitsuba's CIE 1931 functions (`mi.cie1931_xyz`, and `mi.cie_d65` for the reflectance),
by the trapezoid rule every 0.01 nm, scaled by `MI_CIE_Y_NORMALIZATION` and turned to sRGB by
`mi.xyz_to_srgb`, clamped as the RGB variants clamp a list. `--render N` checks that against a
`scalar_spectral` render of a constant emitter (N samples per pixel, 16 x 16).
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path = [p for p in sys.path if os.path.abspath(p or ".") != HERE]
import numpy as np  # noqa: E402

# Mitsuba's Cornell box (cbox.xml): the walls' measured reflectances and the light.
CBOX_RED = "400:0.04, 404:0.046, 408:0.048, 412:0.053, 416:0.049, 420:0.05, 424:0.053, 428:0.055, 432:0.057, 436:0.056, 440:0.059, 444:0.057, 448:0.061, 452:0.061, 456:0.06, 460:0.062, 464:0.062, 468:0.062, 472:0.061, 476:0.062, 480:0.06, 484:0.059, 488:0.057, 492:0.058, 496:0.058, 500:0.058, 504:0.056, 508:0.055, 512:0.056, 516:0.059, 520:0.057, 524:0.055, 528:0.059, 532:0.059, 536:0.058, 540:0.059, 544:0.061, 548:0.061, 552:0.063, 556:0.063, 560:0.067, 564:0.068, 568:0.072, 572:0.08, 576:0.09, 580:0.099, 584:0.124, 588:0.154, 592:0.192, 596:0.255, 600:0.287, 604:0.349, 608:0.402, 612:0.443, 616:0.487, 620:0.513, 624:0.558, 628:0.584, 632:0.62, 636:0.606, 640:0.609, 644:0.651, 648:0.612, 652:0.61, 656:0.65, 660:0.638, 664:0.627, 668:0.62, 672:0.63, 676:0.628, 680:0.642, 684:0.639, 688:0.657, 692:0.639, 696:0.635, 700:0.642"
CBOX_GREEN = "400:0.092, 404:0.096, 408:0.098, 412:0.097, 416:0.098, 420:0.095, 424:0.095, 428:0.097, 432:0.095, 436:0.094, 440:0.097, 444:0.098, 448:0.096, 452:0.101, 456:0.103, 460:0.104, 464:0.107, 468:0.109, 472:0.112, 476:0.115, 480:0.125, 484:0.14, 488:0.16, 492:0.187, 496:0.229, 500:0.285, 504:0.343, 508:0.39, 512:0.435, 516:0.464, 520:0.472, 524:0.476, 528:0.481, 532:0.462, 536:0.447, 540:0.441, 544:0.426, 548:0.406, 552:0.373, 556:0.347, 560:0.337, 564:0.314, 568:0.285, 572:0.277, 576:0.266, 580:0.25, 584:0.23, 588:0.207, 592:0.186, 596:0.171, 600:0.16, 604:0.148, 608:0.141, 612:0.136, 616:0.13, 620:0.126, 624:0.123, 628:0.121, 632:0.122, 636:0.119, 640:0.114, 644:0.115, 648:0.117, 652:0.117, 656:0.118, 660:0.12, 664:0.122, 668:0.128, 672:0.132, 676:0.139, 680:0.144, 684:0.146, 688:0.15, 692:0.152, 696:0.157, 700:0.159"
CBOX_WHITE = "400:0.343, 404:0.445, 408:0.551, 412:0.624, 416:0.665, 420:0.687, 424:0.708, 428:0.723, 432:0.715, 436:0.71, 440:0.745, 444:0.758, 448:0.739, 452:0.767, 456:0.777, 460:0.765, 464:0.751, 468:0.745, 472:0.748, 476:0.729, 480:0.745, 484:0.757, 488:0.753, 492:0.75, 496:0.746, 500:0.747, 504:0.735, 508:0.732, 512:0.739, 516:0.734, 520:0.725, 524:0.721, 528:0.733, 532:0.725, 536:0.732, 540:0.743, 544:0.744, 548:0.748, 552:0.728, 556:0.716, 560:0.733, 564:0.726, 568:0.713, 572:0.74, 576:0.754, 580:0.764, 584:0.752, 588:0.736, 592:0.734, 596:0.741, 600:0.74, 604:0.732, 608:0.745, 612:0.755, 616:0.751, 620:0.744, 624:0.731, 628:0.733, 632:0.744, 636:0.731, 640:0.712, 644:0.708, 648:0.729, 652:0.73, 656:0.727, 660:0.707, 664:0.703, 668:0.729, 672:0.75, 676:0.76, 680:0.751, 684:0.739, 688:0.724, 692:0.73, 696:0.74, 700:0.737"
CBOX_LIGHT = "400:0, 500:8, 600:15.6, 700:18.4"

# (name, the `value` of the <spectrum>, or "blackbody:T" for the plugin at T kelvin).
SPECTRA = [
    ("cbox red", "CBOX_RED"),
    ("cbox green", "CBOX_GREEN"),
    ("cbox white", "CBOX_WHITE"),
    ("cbox light", "CBOX_LIGHT"),
    ("flat", "400:0.5, 700:0.5"),
    ("one value", "0.5"),
    ("narrow peak", "540:0, 545:1, 550:0"),
    ("beyond 360-830", "300:0.2, 500:0.8, 900:0.4"),
    ("from 500", "500:0.3, 600:0.9, 700:0.6"),
    ("out of gamut", "400:1, 500:1"),
    ("outside", "900:1, 1000:1"),
    ("blackbody 2700 K", "blackbody:2700"),
    ("blackbody 6500 K", "blackbody:6500"),
]


def value(text):
    return globals()[text] if text.startswith("CBOX_") else text


def rgb_variant_colours(mi, text):
    """(reflectance, radiance) of the <spectrum value=text>, as scalar_rgb loads them."""
    spectrum = f'<spectrum name="{{}}" value="{text}"/>'
    scene = mi.load_string(
        f"""<scene version="3.0.0">
    <shape type="rectangle" id="surface"><bsdf type="diffuse">{spectrum.format("reflectance")}</bsdf></shape>
    <emitter type="constant" id="light">{spectrum.format("radiance")}</emitter>
</scene>"""
    )
    params = mi.traverse(scene)
    colour = lambda key: [float(c) for c in np.broadcast_to(np.array(params[key]), 3)]  # noqa: E731
    return colour("surface.bsdf.reflectance.value"), colour("light.radiance.value")


def blackbody_colours(mi, kelvin):
    """(reflectance, radiance) of a black body at `kelvin`, as the spectral variants see it."""
    mi.set_variant("scalar_spectral")
    plugin = mi.load_dict({"type": "blackbody", "temperature": float(kelvin)})
    si = mi.SurfaceInteraction3f()
    wavelengths = np.linspace(360.0, 830.0, 47001)
    radiance = np.empty_like(wavelengths)
    for i in range(0, len(wavelengths), 4):
        chunk = list(wavelengths[i : i + 4])
        si.wavelengths = mi.Spectrum((chunk + [chunk[-1]] * 4)[:4])
        radiance[i : i + len(chunk)] = np.array(plugin.eval(si))[: len(chunk)]
    mi.set_variant("scalar_rgb")
    cmf = np.array([np.array(mi.cie1931_xyz(float(w))) for w in wavelengths])
    d65 = np.array([float(mi.cie_d65(float(w))) for w in wavelengths])
    out = []
    for weight, high in ((d65, 1.0), (np.ones_like(d65), np.inf)):
        xyz = np.trapezoid(cmf * (radiance * weight)[:, None], wavelengths, axis=0) * mi.MI_CIE_Y_NORMALIZATION
        rgb = np.array(mi.xyz_to_srgb(mi.Color3f(*xyz)))
        out.append([float(c) for c in np.clip(rgb, 0.0, high)])
    return out[0], out[1]


def spectral_render(mi, kelvin, spp):
    """The mean pixel of a scalar_spectral render of a constant black body emitter."""
    mi.set_variant("scalar_spectral")
    scene = mi.load_string(
        f"""<scene version="3.0.0">
    <emitter type="constant"><spectrum name="radiance" type="blackbody"><float name="temperature" value="{kelvin}"/></spectrum></emitter>
    <sensor type="perspective">
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/><rfilter type="box"/></film>
        <sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>
    </sensor>
    <integrator type="path"/>
</scene>"""
    )
    img = np.array(mi.render(scene, seed=7))
    mi.set_variant("scalar_rgb")
    return img.reshape(-1, img.shape[-1])[:, :3].mean(0)


def f32(x):
    s = np.format_float_positional(np.float32(x), unique=True, trim="-")
    return s if "." in s else s + ".0"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--render", type=int, metavar="SPP", help="also render the black bodies spectrally")
    args = ap.parse_args()

    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)  # the out-of-gamut case's clamping warnings
    rows = []
    for name, text in SPECTRA:
        if text.startswith("blackbody:"):
            kelvin = float(text.split(":")[1])
            reflectance, emitted = blackbody_colours(mi, kelvin)
            if args.render:
                mean = spectral_render(mi, kelvin, args.render)
                rel = np.abs(mean - emitted) / np.array(emitted)
                print(f"// {name}: spectral render {mean}, integral {emitted}, relative {rel}", file=sys.stderr)
        else:
            reflectance, emitted = rgb_variant_colours(mi, value(text))
        rows.append((name, text, reflectance, emitted))

    print(f"// Made by bench/peers/spectra.py (Mitsuba {mi.MI_VERSION}): the colours of each spectrum as a")
    print("// reflectance and as an emitted radiance (see the script for the black bodies).")
    print("#[rustfmt::skip]")
    print("const MITSUBA: &[(&str, &str, [f32; 3], [f32; 3])] = &[")
    for name, text, reflectance, emitted in rows:
        quoted = text if text.startswith("CBOX_") else f'"{text}"'
        cols = ", ".join(f"[{', '.join(f32(c) for c in colour)}]" for colour in (reflectance, emitted))
        print(f'    ("{name}", {quoted}, {cols}),')
    print("];")


if __name__ == "__main__":
    main()
