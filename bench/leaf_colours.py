#!/usr/bin/env python3
"""Checks the shipped species' leaf colours against measured leaf optics (issue 29).

    python3 bench/leaf_colours.py [SPECIES_DIR (species/)]

The measured references, in linear Rec. 709 (arbor's scene_linear) under D65:
- a PROSPECT-5 leaf (Jacquemoud & Baret 1990, Feret et al. 2008; the model is calibrated on the
  LOPEX93 and ANGERS measurements) of N 2.1, Cab 40 µg/cm², Car 10, Cbrown 0.1, Cw 0.015,
  Cm 0.009, its reflectance and transmittance at 10 nm as computed by the model's reference
  implementation (opticleaf.ipgp.fr), integrated here against CIE 1931 (the multi-lobe fit of
  Wyman, Sloan and Shirley 2013) and a 6504 K Planckian for D65;
- the ColorChecker's "foliage" patch (a painted match to a leaf): sRGB (87, 108, 67), decoded;
- autumn leaves, as schematic spectra read off the measured ones (piecewise linear in
  wavelength): yellow, chlorophyll gone and carotenoids left (Merzlyak et al. 1999, Physiol.
  Plantarum 106: 135–141): 0.06 to 480 nm, 0.30 at 530, 0.42 at 570, 0.48 from 600; red,
  anthocyanins absorbing the green (Gitelson, Merzlyak and Chivkunova 2001, Photochem. Photobiol.
  74: 38–45): 0.05 to 580 nm, 0.30 at 640, 0.40 from 680; brown, dead and tannin-stained: 0.05
  at 400 nm, 0.15 at 550, 0.28 at 650, 0.35 at 780.
Prints each species' adaxial reflectance, abaxial reflectance and transmittance with the ratios
that make a leaf read as a leaf — red over green and blue over green (its saturation) and green's
level — against the references, and writes bench/results/leaf_colours.json.
"""
import json
import os
import re
import sys

import numpy as np

LAM = np.arange(400, 781, 10)
PROSPECT_R = np.array([
    .0413, .0422, .0437, .0451, .0458, .0462, .0465, .0466, .0467, .0475, .0521, .0671, .0983,
    .1301, .1435, .1488, .1453, .1279, .1093, .0991, .0945, .0865, .0768, .0737, .0673, .0567,
    .0506, .0468, .0504, .0702, .1640, .2789, .3740, .4457, .4888, .5092, .5193, .5247, .5267])
PROSPECT_T = np.array([
    .0001, .0001, .0002, .0002, .0002, .0004, .0008, .0012, .0014, .0024, .0066, .0185, .0414,
    .0640, .0733, .0773, .0761, .0651, .0528, .0460, .0431, .0376, .0306, .0285, .0236, .0150,
    .0095, .0044, .0043, .0207, .0947, .1805, .2496, .3010, .3321, .3480, .3570, .3627, .3658])


def lobe(x, mu, s1, s2):
    s = np.where(x < mu, s1, s2)
    return np.exp(-0.5 * ((x - mu) / s) ** 2)


def cie1931(l):
    x = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) \
        - 0.065 * lobe(l, 501.1, 20.4, 26.2)
    y = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1)
    z = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8)
    return np.stack([x, y, z])


XYZ_TO_709 = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415],
                       [0.0557, -0.2040, 1.0570]])


def linear_709(spectrum):
    """A reflectance spectrum's colour, white-balanced so that a perfect reflector is (1, 1, 1)."""
    l = np.arange(380.0, 781.0)
    d65 = 1.0 / (l ** 5 * (np.exp(1.4388e7 / (l * 6504.0)) - 1.0))
    cmf = cie1931(l) * d65
    r = np.interp(l, LAM, spectrum)
    return (XYZ_TO_709 @ (cmf @ r)) / (XYZ_TO_709 @ cmf.sum(axis=1))


def srgb_decode(v):
    v = np.asarray(v) / 255.0
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def ratios(c):
    return {"rgb": [round(float(x), 4) for x in c], "red/green": round(float(c[0] / c[1]), 3),
            "blue/green": round(float(c[2] / c[1]), 3), "green": round(float(c[1]), 4)}


def species_leaves(folder):
    out = {}
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".toml"):
            continue
        text = open(os.path.join(folder, name)).read()
        leaf = {}
        for key in ("reflectance", "back_reflectance", "transmittance"):
            m = re.search(r"(?m)^" + key + r"\s*=\s*\[([^\]]*)\]", text)
            if m:
                leaf[key] = np.array([float(x) for x in m.group(1).split(",")])
        if leaf:
            out[name[:-5]] = leaf
    return out


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..",
                                                                "species")
    def schematic(points):
        x, y = zip(*points)
        return np.interp(LAM, x, y)

    refs = {"PROSPECT-5 reflectance": linear_709(PROSPECT_R),
            "autumn yellow": linear_709(schematic([(400, .06), (480, .06), (530, .30), (570, .42),
                                                   (600, .48), (780, .48)])),
            "autumn red": linear_709(schematic([(400, .05), (580, .05), (640, .30), (680, .40),
                                                (780, .40)])),
            "autumn scarlet": linear_709(schematic([(400, .03), (500, .03), (580, .05),
                                                    (620, .20), (650, .38), (680, .45),
                                                    (780, .45)])),
            "autumn brown": linear_709(schematic([(400, .05), (550, .15), (650, .28),
                                                  (780, .35)])),
            "PROSPECT-5 transmittance": np.maximum(linear_709(PROSPECT_T), 0.0),
            "ColorChecker foliage": srgb_decode([87, 108, 67])}
    result = {"references": {k: ratios(v) for k, v in refs.items()}, "species": {}}
    for k, v in result["references"].items():
        print(f"{k:28s} {v}")
    for name, leaf in species_leaves(folder).items():
        result["species"][name] = {k: ratios(v) for k, v in leaf.items()}
        r = result["species"][name]["reflectance"]
        print(f"{name:28s} R {r['rgb']} red/green {r['red/green']} blue/green {r['blue/green']}")
    out = os.path.join(os.path.dirname(__file__), "results", "leaf_colours.json")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    json.dump(result, open(out, "w"), indent=1)


if __name__ == "__main__":
    main()
