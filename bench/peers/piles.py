#!/usr/bin/env python3
"""A pile's speed over several tilt patterns: compare.py's pile of side³ tilted boxes, its tilts
drawn with other primes, each run by rbsim_peer (and Bullet's bullet_peer when built), interleaved.

    /usr/bin/python3 bench/peers/piles.py [--build build] [--side 6] [--duration 1.0]
        [--patterns 4] [--rounds 2] [--against DIR]

Why: a pile's outcome (which columns topple, when a sway stops) depends on rounding, and its
cost with it — one scene's before/after can mislead by ±10 %, where the same change measured
over several patterns of the same pile does not. --against DIR runs rbsim_peer a second time
with DIR first on LD_LIBRARY_PATH (a copy of another build's libmassprops_dynamics.so: the
library before a change), for a before/after in the same rotation. Prints a Markdown table with
each pattern's steps/s (medians over the rounds) and the ratios' mean.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare import pile_scene  # noqa: E402

PRIMES = (7919, 7907, 104729, 15485863, 1299709, 49979687)


def steps_per_second(binary, scene, env=None):
    p = subprocess.run([binary, scene, "--dt", "0.001"], capture_output=True, text=True, env=env)
    if p.returncode != 0:
        raise RuntimeError("%s %s: %s" % (os.path.basename(binary), scene, p.stderr.strip()))
    return json.loads(p.stdout.strip().splitlines()[-1])["steps_per_second"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--side", type=int, default=6, help="side³ boxes (6: 216, 10: 1000)")
    ap.add_argument("--duration", type=float, default=1.0, help="simulated seconds")
    ap.add_argument("--patterns", type=int, default=4, choices=range(1, len(PRIMES) + 1))
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--against", help="a folder with another build's libmassprops_dynamics.so")
    args = ap.parse_args()
    bench = os.path.join(args.build, "bench")
    engines = [("rbsim", os.path.join(bench, "rbsim_peer"), None)]
    if args.against:
        env = dict(os.environ, LD_LIBRARY_PATH=os.path.abspath(args.against))
        engines.append(("rbsim (--against)", os.path.join(bench, "rbsim_peer"), env))
    if os.path.exists(os.path.join(bench, "bullet_peer")):
        engines.append(("Bullet", os.path.join(bench, "bullet_peer"), None))
    times = {}
    with tempfile.TemporaryDirectory() as tmp:
        scenes = []
        for prime in PRIMES[:args.patterns]:
            path = os.path.join(tmp, "pile_%d.json" % prime)
            with open(path, "w") as f:
                json.dump(pile_scene(args.side, args.duration, prime), f)
            scenes.append((prime, path))
        for _ in range(args.rounds):
            for prime, path in scenes:
                for name, binary, env in engines:
                    times.setdefault((prime, name), []).append(steps_per_second(binary, path, env))
    print("pile of %d boxes, %g s, 1 ms steps, one thread; steps/s (median of %d rounds)\n" %
          (args.side ** 3, args.duration, args.rounds))
    names = [name for name, _, _ in engines]
    print("| tilt prime | " + " | ".join(names) + " | " +
          " | ".join("rbsim / %s" % n for n in names[1:]) + " |")
    print("|---" * (2 * len(names)) + "|")
    ratios = {n: [] for n in names[1:]}
    for prime, _ in scenes:
        med = {n: statistics.median(times[(prime, n)]) for n in names}
        for n in names[1:]:
            ratios[n].append(med["rbsim"] / med[n])
        print("| %d | " % prime + " | ".join("%.4g" % med[n] for n in names) + " | " +
              " | ".join("%.2f" % (med["rbsim"] / med[n]) for n in names[1:]) + " |")
    for n in names[1:]:
        print("\nrbsim / %s: mean %.2f (%.2f–%.2f)" % (n, statistics.mean(ratios[n]), min(ratios[n]),
                                                     max(ratios[n])))


if __name__ == "__main__":
    main()
