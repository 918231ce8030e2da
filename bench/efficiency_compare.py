#!/usr/bin/python3
"""Path-tracing efficiency of arbor builds on one scene, interleaved (issue 27's levers).

    /usr/bin/python3 bench/efficiency_compare.py SCENE.toml NAME=ARBOR [NAME=ARBOR ...]
        [--rounds 2] [--spp-lo 16] [--spp-hi 64] [--width 240 --height 180]
        [--out bench/results/efficiency_compare.json]

Each build (an `arbor` executable; copies outside the build tree need $OCIO) renders SCENE at
spp_lo with seed 1 and at spp_hi with seeds 1 and 2, on 2 threads; rounds alternate the builds'
order. From the CPU seconds of each process (getrusage of the children):
- cost of a sample pass: (mean CPU(spp_hi) - CPU(spp_lo)) / (spp_hi - spp_lo), start-up left out;
- variance at spp_hi: the mean over pixels and channels of (A - B)^2 / 2 for the two seeds;
- efficiency: 1 / (variance x cost of spp_hi samples).
Prints each render's figures and each build's efficiencies; the ratio of two builds' ranges is
the lever's gain. The variance is the same in every round (renders are deterministic); the
cost is what this shared machine makes noisy, so give ranges over rounds.
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def render(arbor, args, spp, seed, out):
    c0 = child_cpu()
    subprocess.run([arbor, "render", args.scene, "-o", out, "--spp", str(spp), "--seed",
                    str(seed), "--threads", "2", "--width", str(args.width), "--height",
                    str(args.height)], check=True, capture_output=True)
    return child_cpu() - c0


def pixels(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)[:, :, :3].astype(np.float64)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("builds", nargs="+", help="NAME=PATH_TO_ARBOR")
    p.add_argument("--rounds", type=int, default=2)
    p.add_argument("--spp-lo", type=int, default=16)
    p.add_argument("--spp-hi", type=int, default=64)
    p.add_argument("--width", type=int, default=240)
    p.add_argument("--height", type=int, default=180)
    p.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                 "results", "efficiency_compare.json"))
    args = p.parse_args()
    builds = [b.split("=", 1) for b in args.builds]
    if any(len(b) != 2 for b in builds):
        sys.exit("efficiency_compare: each build is NAME=PATH_TO_ARBOR")
    runs = {name: [] for name, _ in builds}
    with tempfile.TemporaryDirectory() as tmp:
        lo, a, b = (os.path.join(tmp, n) for n in ("lo.exr", "a.exr", "b.exr"))
        for r in range(args.rounds):
            for name, arbor in (builds if r % 2 == 0 else builds[::-1]):
                cpu_lo = render(arbor, args, args.spp_lo, 1, lo)
                cpu_a = render(arbor, args, args.spp_hi, 1, a)
                cpu_b = render(arbor, args, args.spp_hi, 2, b)
                x, y = pixels(a), pixels(b)
                per_pass = (0.5 * (cpu_a + cpu_b) - cpu_lo) / (args.spp_hi - args.spp_lo)
                var = float(np.mean((x - y) ** 2) / 2.0)
                run = {"round": r, "cpu_s_per_pass": per_pass, "variance": var,
                       "efficiency": 1.0 / (var * per_pass * args.spp_hi),
                       "mean": float((0.5 * (x + y)).mean())}
                runs[name].append(run)
                print(f"efficiency_compare: {name}: {per_pass:.4f} CPU-s a pass, variance "
                      f"{var:.4e}, efficiency {run['efficiency']:.0f}, mean {run['mean']:.5f}",
                      flush=True)
    for name, rs in runs.items():
        e = [x["efficiency"] for x in rs]
        print(f"efficiency_compare: {name}: efficiency {min(e):.0f}-{max(e):.0f}")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    json.dump({"scene": args.scene, "builds": dict(builds), "spp_lo": args.spp_lo,
               "spp_hi": args.spp_hi, "width": args.width, "height": args.height, "runs": runs},
              open(args.out, "w"), indent=1)


if __name__ == "__main__":
    main()
