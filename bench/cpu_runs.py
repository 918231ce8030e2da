#!/usr/bin/env python3
"""Summarises interleaved timing runs for the shell benches (startup.sh, aerial.sh).

    python3 bench/cpu_runs.py RUNS OUT.json

RUNS holds one "name seconds" line per run (CPU seconds). The script writes OUT.json with this
machine's name and cores and every run, and prints each name's range and median.
"""
import json
import os
import statistics
import sys


def main():
    runs = {}
    with open(sys.argv[1]) as f:
        for line in f:
            name, seconds = line.split()
            runs.setdefault(name, []).append(float(seconds))
    with open(sys.argv[2], "w") as f:
        json.dump({"machine": os.uname().nodename, "cores": os.cpu_count(), "unit": "CPU s",
                   "runs": runs}, f, indent=1)
    for name, v in runs.items():
        print(f"{name:7s} {min(v):.2f}-{max(v):.2f} CPU s, median {statistics.median(v):.2f}")


if __name__ == "__main__":
    main()
