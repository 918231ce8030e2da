#!/usr/bin/python3
"""arbor against Blender Cycles on the same triangles (issue 27's yardstick).

    /usr/bin/python3 bench/cycles/yardstick.py [--arbor build/app/arbor] [--rounds 3]
        [--spp-lo 16] [--spp-hi 64] [--adaptive] [--out bench/results/cycles_yardstick.json]

Needs Debian's `blender` (3.4) and the python3 OpenImageIO and numpy packages
(`tools/install-deps.sh --clients` installs all three); it is never run by CI. The scene: the default scene's Quaking Aspen (seed 7) exported by `arbor grow -o tree.obj`,
the default scene's camera, a sun of irradiance 3 at elevation 38 and azimuth 150 with its
0.53-degree disk, a constant sky, a Lambertian ground, Lambertian bark, leaves as Lambertian
reflection plus Lambertian transmission (the same reflectance on both faces, no cuticle), 8
bounces, 2 threads, 240x180. bench/cycles/cycles_scene.py builds it in Cycles.

Method (CPU seconds of each child process from getrusage; rounds interleave the renderers and
alternate which goes first):
- cost per sample pass: (CPU(spp_hi) - CPU(spp_lo)) / (spp_hi - spp_lo), which leaves out each
  renderer's start-up (Blender's start, OBJ import and BVH build; arbor's OBJ read and BVH);
  start-up is the intercept;
- variance at spp_hi: the mean over pixels and channels of (A - B)^2 / 2 for two seeds;
- efficiency: 1 / (variance x cost of spp_hi samples); its ratio arbor / Cycles is the goal's
  measure (>= 1);
- agreement: the two renderers' image means per channel (both seeds) and per quarter image;
- --adaptive: each renderer's adaptive sampling against an arbor reference of 2048 spp (seed 99):
  the 95th percentile and the mean over pixels of max_c |x - ref| / max(|ref|, 0.01), and the
  render's CPU seconds less its start-up. Cycles at its default threshold 0.01 and arbor at
  several noise_threshold values; arbor's time at Cycles' p95 error is interpolated log-log.
"""
import argparse
import json
import math
import os
import re
import resource
import shutil
import subprocess
import sys
import time

import numpy as np
import OpenImageIO as oiio

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

SCENE = {
    "width": 240, "height": 180, "threads": 2, "max_depth": 8, "fov": 40.0,
    "camera_position": [13.0, -17.0, 2.2], "camera_look_at": [0.0, 0.0, 6.2],
    "sun_elevation": 38.0, "sun_azimuth": 150.0, "sun_irradiance": 3.0,
    "sun_angular_diameter": 0.53, "sky_color": [0.12, 0.18, 0.30],
    "ground_albedo": [0.16, 0.14, 0.10],
}


def vec(v):
    return "[" + ", ".join(repr(float(x)) for x in v) + "]"


def arbor_scene(cfg):
    return f"""# Written by bench/cycles/yardstick.py: the scene bench/cycles/cycles_scene.py builds in Cycles.
[render]
width = {cfg['width']}
height = {cfg['height']}
spp = 16
seed = 1
integrator = "path"
max_depth = {cfg['max_depth']}
[camera]
position = {vec(cfg['camera_position'])}
look_at = {vec(cfg['camera_look_at'])}
up = [0.0, 0.0, 1.0]
fov = {cfg['fov']}
[sun]
elevation = {cfg['sun_elevation']}
azimuth = {cfg['sun_azimuth']}
irradiance = {cfg['sun_irradiance']}
angular_diameter = {cfg['sun_angular_diameter']}
[sky]
model = "constant"
color = {vec(cfg['sky_color'])}
[ground]
enabled = true
albedo = {vec(cfg['ground_albedo'])}
[[mesh]]
path = "{cfg['obj']}"
up = "z"
[mesh.material.bark]
kind = "diffuse"
albedo = {vec(cfg['bark_albedo'])}
[mesh.material.leaf]
kind = "leaf"
reflectance = {vec(cfg['leaf_reflectance'])}
back_reflectance = {vec(cfg['leaf_reflectance'])}
transmittance = {vec(cfg['leaf_transmittance'])}
cuticle_ior = 1.0
[output]
colorspace = "Linear Rec.709 (sRGB)"
pixel_type = "float"
"""


def mtl_colours(path):
    """The bark's and the leaf's colours from the .mtl arbor wrote beside the OBJ."""
    colours, name = {}, None
    for line in open(path):
        f = line.split()
        if f and f[0] == "newmtl":
            name = f[1]
        elif f and f[0] in ("Kd", "Tf") and name:
            colours[(name, f[0])] = [float(x) for x in f[1:4]]
    return colours[("bark", "Kd")], colours[("leaf", "Kd")], colours[("leaf", "Tf")]


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd, log, env=None):
    c0, w0 = child_cpu(), time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    cpu, wall = child_cpu() - c0, time.perf_counter() - w0
    with open(log, "a") as f:
        f.write(" ".join(cmd) + "\n" + p.stdout + "\n")
    if p.returncode != 0:
        sys.exit(f"yardstick: {' '.join(cmd)} failed (exit {p.returncode}); see {log}")
    return cpu, wall, p.stdout


class Renderers:
    def __init__(self, args, work):
        self.args, self.work = args, work
        self.log = os.path.join(work, "log.txt")

    def arbor(self, spp, seed, threshold=0.0, name=None):
        out = os.path.join(self.work, name or f"arbor_{spp}_{seed}.exr")
        cmd = [self.args.arbor, "render", os.path.join(self.work, "arbor.toml"), "-o", out,
               "--spp", str(spp), "--seed", str(seed), "--threads", str(SCENE["threads"])]
        if threshold > 0:
            scene = os.path.join(self.work, f"arbor_t{threshold}.toml")
            text = open(os.path.join(self.work, "arbor.toml")).read()
            text = text.replace("[render]\n", f"[render]\nnoise_threshold = {threshold}\n"
                                "min_spp = 16\n", 1)
            open(scene, "w").write(text)
            cmd[2] = scene
        cpu, wall, _ = run(cmd, self.log)
        return {"cpu_s": cpu, "wall_s": wall, "exr": out}

    def cycles(self, spp, seed, threshold=0.0, name=None):
        out = os.path.join(self.work, name or f"cycles_{spp}_{seed}.exr")
        cmd = [self.args.blender, "-b", "--factory-startup", "--python",
               os.path.join(ROOT, "bench", "cycles", "cycles_scene.py"), "--",
               os.path.join(self.work, "config.json"), out, str(spp), str(seed), str(threshold)]
        # Blender reads $OCIO too: it keeps its own configuration (arbor's has no "Standard" view).
        env = {k: v for k, v in os.environ.items() if k != "OCIO"}
        cpu, wall, text = run(cmd, self.log, env)
        inner = json.loads(re.search(r"^yardstick: (.*)$", text, re.M).group(1))
        return {"cpu_s": cpu, "wall_s": wall, "render_cpu_s": inner["render_cpu_s"], "exr": out}


def pixels(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)[:, :, :3].astype(np.float64)


def errors(img, ref):
    e = (np.abs(img - ref) / np.maximum(np.abs(ref), 0.01)).max(axis=2).ravel()
    return float(np.percentile(e, 95)), float(e.mean())


def fixed(args, r):
    rounds = {"arbor": [], "cycles": []}
    for k in range(args.rounds):
        order = ["arbor", "cycles"] if k % 2 == 0 else ["cycles", "arbor"]
        for who in order:
            f = getattr(r, who)
            lo, hi1, hi2 = f(args.spp_lo, 1), f(args.spp_hi, 1), f(args.spp_hi, 2)
            a, b = pixels(hi1["exr"]), pixels(hi2["exr"])
            slope = (0.5 * (hi1["cpu_s"] + hi2["cpu_s"]) - lo["cpu_s"]) / (args.spp_hi - args.spp_lo)
            var = float(np.mean((a - b) ** 2) / 2.0)
            rounds[who].append({
                "cpu_s_lo": lo["cpu_s"], "cpu_s_hi": [hi1["cpu_s"], hi2["cpu_s"]],
                "cpu_s_per_sample_pass": slope, "startup_cpu_s": lo["cpu_s"] - slope * args.spp_lo,
                "variance": var, "efficiency": 1.0 / (var * slope * args.spp_hi),
                "mean": (0.5 * (a + b)).mean(axis=(0, 1)).tolist(),
                "quarter_means": quarter_means(0.5 * (a + b)),
            })
            print(f"yardstick: round {k} {who}: {slope:.4f} CPU-s per pass, start-up "
                  f"{rounds[who][-1]['startup_cpu_s']:.2f} CPU-s, variance {var:.3e}", flush=True)
    return rounds


def quarter_means(img):
    h, w = img.shape[:2]
    return [float(img[y * h // 2:(y + 1) * h // 2, x * w // 2:(x + 1) * w // 2].mean())
            for y in (0, 1) for x in (0, 1)]


def summary(rounds):
    px = SCENE["width"] * SCENE["height"]
    out = {}
    for who, rs in rounds.items():
        slopes = [x["cpu_s_per_sample_pass"] for x in rs]
        out[who] = {
            "samples_per_cpu_s": [px / s for s in slopes],
            "variance": [x["variance"] for x in rs],
            "efficiency": [x["efficiency"] for x in rs],
            "startup_cpu_s": [x["startup_cpu_s"] for x in rs],
        }
    a, c = rounds["arbor"], rounds["cycles"]
    out["ratios"] = {
        "samples_per_cpu_s": [y["cpu_s_per_sample_pass"] / x["cpu_s_per_sample_pass"] for x, y in zip(a, c)],
        "variance": [x["variance"] / y["variance"] for x, y in zip(a, c)],
        "efficiency": [x["efficiency"] / y["efficiency"] for x, y in zip(a, c)],
        "image_mean": (np.mean([x["mean"] for x in a], axis=0) /
                       np.mean([y["mean"] for y in c], axis=0)).tolist(),
        "quarter_means": (np.mean([x["quarter_means"] for x in a], axis=0) /
                          np.mean([y["quarter_means"] for y in c], axis=0)).tolist(),
    }
    return out


def adaptive(args, r, rounds):
    ref_path = os.path.join(r.work, f"reference_{args.ref_spp}.exr")
    if not os.path.exists(ref_path):
        r.arbor(args.ref_spp, 99, name=os.path.basename(ref_path))
    ref = pixels(ref_path)
    startup = {who: float(np.median([x["startup_cpu_s"] for x in rs])) for who, rs in rounds.items()}
    res = {"reference_spp": args.ref_spp, "cycles": [], "arbor": []}
    for k in range(args.rounds):
        c = r.cycles(args.adaptive_spp, 1, 0.01, name="cycles_adaptive.exr")
        p95, mean = errors(pixels(c["exr"]), ref)
        res["cycles"].append({"threshold": 0.01, "cpu_s": c["cpu_s"] - startup["cycles"],
                              "p95_error": p95, "mean_error": mean})
        for t in args.arbor_thresholds:
            a = r.arbor(args.adaptive_spp, 1, t, name=f"arbor_adaptive_{t}.exr")
            p95, mean = errors(pixels(a["exr"]), ref)
            res["arbor"].append({"threshold": t, "round": k, "cpu_s": a["cpu_s"] - startup["arbor"],
                                 "p95_error": p95, "mean_error": mean})
        print(f"yardstick: adaptive round {k}: cycles {res['cycles'][-1]}", flush=True)
    ratios = []
    for k, cyc in enumerate(res["cycles"]):
        pts = sorted((math.log(x["p95_error"]), math.log(x["cpu_s"]))
                     for x in res["arbor"] if x["round"] == k)
        e = math.log(cyc["p95_error"])
        lo = max((p for p in pts if p[0] <= e), default=None)
        hi = min((p for p in pts if p[0] >= e), default=None)
        if lo is None or hi is None:
            ratios.append(None)
            continue
        f = 0.0 if hi[0] == lo[0] else (e - lo[0]) / (hi[0] - lo[0])
        ratios.append(math.exp(lo[1] + f * (hi[1] - lo[1])) / cyc["cpu_s"])
    res["arbor_time_over_cycles_at_equal_p95"] = ratios
    return res


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--arbor", default=os.path.join(ROOT, "build", "app", "arbor"))
    p.add_argument("--blender", default="blender")
    p.add_argument("--species", default=os.path.join(ROOT, "species", "quaking_aspen.toml"))
    p.add_argument("--tree-seed", type=int, default=7)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--spp-lo", type=int, default=16)
    p.add_argument("--spp-hi", type=int, default=64)
    p.add_argument("--adaptive", action="store_true")
    p.add_argument("--adaptive-spp", type=int, default=1024)
    p.add_argument("--arbor-thresholds", type=float, nargs="+", default=[0.08, 0.12, 0.18, 0.27])
    p.add_argument("--fixed-from", help="take the fixed-spp rounds (and so each renderer's "
                   "start-up) from this earlier result instead of rendering them again")
    p.add_argument("--ref-spp", type=int, default=2048)
    p.add_argument("--work", default="/tmp/arbor_cycles_yardstick")
    p.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "cycles_yardstick.json"))
    args = p.parse_args()
    if shutil.which(args.blender) is None:
        sys.exit("yardstick: blender is not installed (apt install blender); nothing measured")
    os.makedirs(args.work, exist_ok=True)
    obj = os.path.join(args.work, "tree.obj")
    run([args.arbor, "grow", args.species, "--seed", str(args.tree_seed), "-o", obj],
        os.path.join(args.work, "log.txt"))
    bark, leaf_r, leaf_t = mtl_colours(os.path.join(args.work, "tree.mtl"))
    cfg = dict(SCENE, obj=obj, bark_albedo=bark, leaf_reflectance=leaf_r, leaf_transmittance=leaf_t)
    json.dump(cfg, open(os.path.join(args.work, "config.json"), "w"), indent=1)
    open(os.path.join(args.work, "arbor.toml"), "w").write(arbor_scene(cfg))
    r = Renderers(args, work=args.work)
    rounds = json.load(open(args.fixed_from))["rounds"] if args.fixed_from else fixed(args, r)
    result = {"machine": os.uname().nodename, "date": time.strftime("%Y-%m-%d"),
              "arbor": args.arbor, "scene": cfg, "spp_lo": args.spp_lo, "spp_hi": args.spp_hi,
              "rounds": rounds, "summary": summary(rounds)}
    if args.adaptive:
        result["adaptive"] = adaptive(args, r, rounds)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    json.dump(result, open(args.out, "w"), indent=1)
    s = result["summary"]["ratios"]
    fmt = lambda v: "–".join(f"{x:.2f}" for x in (min(v), max(v)))
    print(f"yardstick: arbor / Cycles: samples per CPU-s {fmt(s['samples_per_cpu_s'])}, "
          f"variance {fmt(s['variance'])}, efficiency {fmt(s['efficiency'])}; image means "
          + " ".join(f"{x:.4f}" for x in s["image_mean"]))
    if args.adaptive:
        print("yardstick: adaptive, arbor's CPU time at Cycles' p95 error / Cycles': "
              + str(result["adaptive"]["arbor_time_over_cycles_at_equal_p95"]))
    print(f"yardstick: wrote {args.out}")


if __name__ == "__main__":
    main()
