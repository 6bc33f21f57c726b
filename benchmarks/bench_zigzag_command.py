"""Benchmark: ``embroact zigzag ... -o x.dst`` against importing numpy, shapely and pystitch.

Target: the command takes at most ~1.3x the bare imports.  Run::

    python benchmarks/bench_zigzag_command.py [--runs 15]

Prints the median wall times of each and their ratio; exits 1 above the target.
"""
import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TARGET_RATIO = 1.3


def _median_s(argv, runs):
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=15)
    runs = ap.parse_args().runs
    out = Path(tempfile.mkdtemp()) / "x.dst"
    base = _median_s([sys.executable, "-c", "import numpy, shapely, pystitch"], runs)
    cmd = _median_s([sys.executable, "-m", "embroact.export", "zigzag", "--width-mm", "7", "--interval-mm", "1",
                     "--length-mm", "100", "-o", str(out)], runs)
    ratio = cmd / base
    print(f"imports {base * 1000:.0f} ms, zigzag command {cmd * 1000:.0f} ms, ratio {ratio:.2f} (target <= {TARGET_RATIO})")
    return 0 if ratio <= TARGET_RATIO else 1


if __name__ == "__main__":
    sys.exit(main())
