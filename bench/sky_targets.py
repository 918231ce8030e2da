#!/usr/bin/env python3
"""Published clear-sky bands for the sky models (issue 28): the CIE standard clear sky (type 12,
CIE S 011/E:2003 = ISO 15469:2004: gradation a = -1, b = -0.32; indicatrix c = 10, d = -3,
e = 0.45) scaled so that its horizontal irradiance is the ESRA clear-sky model's diffuse
irradiance (Rigollier, Bauer & Wald 2000, Solar Energy 68: the beam B_n = I0 exp(-0.8662 TL m
dR(m)) with Kasten & Young 1989's air mass and the paper's Rayleigh optical thickness fits; the
diffuse D = I0 Trd(TL) Fd(h, TL)), divided by the beam, for Linke turbidity 2 and 3, and converted
to luminance ratios with a diffuse-to-beam luminous efficacy ratio of 1.15 to 1.30 (clear-sky
diffuse light about 120-130 lm/W, beam about 100).

Prints, for sun elevations 10, 25, 40 and 60 degrees, the band (min-max over those choices) of
the zenith and the horizon (3 degrees up) 90 and 180 degrees from the sun as ratios of sky
luminance to the direct sun's normal illuminance (per sr), and the diffuse fraction of the
horizontal illuminance; writes bench/results/sky_targets.json.

    python3 bench/sky_targets.py
"""
import json
import math
import os

I0 = 1361.0  # W/m2, the solar constant (its value cancels in every ratio)
CIE_12 = (-1.0, -0.32, 10.0, -3.0, 0.45)


def air_mass(h):
    """Kasten & Young 1989, elevation h in degrees."""
    return 1.0 / (math.sin(math.radians(h)) + 0.50572 * (h + 6.07995) ** -1.6364)


def rayleigh_thickness(m):
    """ESRA's integral Rayleigh optical thickness (Kasten 1996's fit as Rigollier et al. give it)."""
    if m <= 20.0:
        return 1.0 / (6.625928 + 1.92969 * m - 0.170073 * m**2 + 0.011517 * m**3 - 0.000285 * m**4)
    return 1.0 / (10.4 + 0.718 * m)


def esra(h, tl):
    """Beam normal and diffuse horizontal irradiance of the ESRA clear sky."""
    m = air_mass(h)
    beam = I0 * math.exp(-0.8662 * tl * m * rayleigh_thickness(m))
    trd = -1.5843e-2 + 3.0543e-2 * tl + 3.797e-4 * tl * tl
    a0 = 2.6463e-1 - 6.1581e-2 * tl + 3.1408e-3 * tl * tl
    if a0 * trd < 2e-3:
        a0 = 2e-3 / trd
    a1 = 2.0402 + 1.8945e-2 * tl - 1.1161e-2 * tl * tl
    a2 = -1.3025 + 3.9231e-2 * tl + 8.5079e-3 * tl * tl
    s = math.sin(math.radians(h))
    return beam, I0 * trd * (a0 + a1 * s + a2 * s * s)


def cie_relative(z, chi, zs, sky=CIE_12):
    """L(z, chi) / L_zenith of a CIE standard sky: zenith angle z, angle chi from the sun."""
    a, b, c, d, e = sky
    gradation = lambda x: 1.0 + a * math.exp(b / max(math.cos(x), 1e-9))
    indicatrix = lambda x: 1.0 + c * (math.exp(d * x) - math.exp(d * math.pi / 2)) + e * math.cos(x) ** 2
    return indicatrix(chi) * gradation(z) / (indicatrix(zs) * gradation(0.0))


def from_sun(z, azimuth, zs):
    c = math.cos(z) * math.cos(zs) + math.sin(z) * math.sin(zs) * math.cos(azimuth)
    return math.acos(max(-1.0, min(1.0, c)))


def ratios(h, tl, efficacy_ratio, n=90):
    zs = math.radians(90.0 - h)
    beam, diffuse = esra(h, tl)
    integral = 0.0  # of the relative luminance x cos z over the sky
    for i in range(n):
        z = (i + 0.5) / n * math.pi / 2
        for j in range(2 * n):
            a = (j + 0.5) / (2 * n) * 2 * math.pi
            integral += cie_relative(z, from_sun(z, a, zs), zs) * math.cos(z) * math.sin(z)
    integral *= (math.pi / 2 / n) * (2 * math.pi / (2 * n))
    zenith = diffuse / integral
    def at(elevation, azimuth):
        z = math.radians(90.0 - elevation)
        return zenith * cie_relative(z, from_sun(z, math.radians(azimuth), zs), zs)
    k = efficacy_ratio / beam
    fraction = diffuse * efficacy_ratio / (diffuse * efficacy_ratio + beam * math.sin(math.radians(h)))
    return {"zenith": zenith * k, "horizon_90": at(3.0, 90.0) * k,
            "horizon_180": at(3.0, 180.0) * k, "diffuse_fraction": fraction}


def main():
    out = {"source": __doc__.split("\n\n")[0], "bands": {}}
    for h in (10, 25, 40, 60):
        runs = [ratios(h, tl, k) for tl in (2.0, 3.0) for k in (1.15, 1.30)]
        band = {q: [min(r[q] for r in runs), max(r[q] for r in runs)] for q in runs[0]}
        out["bands"][str(h)] = band
        print(f"sun {h:2d}: " + ", ".join(f"{q} {b[0]:.4f}-{b[1]:.4f}" for q, b in band.items()))
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results", "sky_targets.json")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
