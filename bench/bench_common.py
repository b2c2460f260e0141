"""What the end-to-end benchmark scripts share: a timed run of a command, and their arguments."""
import argparse
import subprocess
import time


def timed(cmd, stdout=subprocess.PIPE):
    """Wall time of one run of cmd and its standard output; exits naming the command if it fails."""
    t0 = time.perf_counter()
    out = subprocess.run(cmd, stdout=stdout, stderr=subprocess.PIPE, text=True)
    elapsed = time.perf_counter() - t0
    if out.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} exited with {out.returncode}: {out.stderr}")
    return elapsed, out.stdout


def arguments(default_repeat):
    """--build DIR, --repeat N, --quick (one run each): returns (build folder, repeats)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build")
    ap.add_argument("--repeat", type=int, default=default_repeat)
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    return a.build, (1 if a.quick else a.repeat), a.quick
