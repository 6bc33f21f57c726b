"""Write the small synthetic demo data sets in ``examples/data/`` (fixed seed, same bytes every run).

They imitate the paper's experiment (docs/model.md section 11): pressure up in 10 kPa steps,
then down again, with a hysteresis loop; angles come from embroact's model with known
parameters plus Gaussian noise, so ``embroact fit`` has a known answer to find.

* ``zigzag_w7_loop.csv``   zigzag w = 7 mm: loading G = 2.7 MPa, P0 = 85 kPa;
  unloading G = 2.3 MPa, P0 = 70 kPa; noise 1 deg.
* ``cross_a45_loop.csv``   cross w = 7 mm, alpha0 = 45 deg (bends negative): loading
  G = 1.3 MPa, P0 = 170 kPa; unloading G = 1.1 MPa, P0 = 150 kPa; noise 1 deg.
* ``zigzag_w7_markers.csv`` the zigzag loop as motion-capture frames: the paper's layout,
  14 markers, 7 per side 10 mm apart from the clamped end, on the uniformly bent 100 mm
  strip (so their marker sum reads half of the bend angle, docs/model.md section 11);
  the strip hangs along -z and bends toward +x (the fabric's back); noise 0.05 mm.
  ``embroact fit --markers`` compares them with the layout's reading.

Run: ``python examples/make_demo_data.py [OUT_DIR]`` (default: ``examples/data``).
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from embroact.export.files.atomic import write_text_atomic
from embroact.patterns.params import Tube
from embroact.predict.curve import ActuatorModel, curve
from embroact.predict.derived import derive_from_values

SEED = 20251023
MARKER_SPACING_MM = 10.0
LENGTH_MM = 100.0
SIDE_GAP_MM = 8.0
LOOPS = {
    # name: (pattern, angle_deg, interval_mm, (G, P0) loading, (G, P0) unloading, top pressure)
    "zigzag_w7": ("zigzag", 0.0, 1.0, (2.7, 85.0), (2.3, 70.0), 250.0),
    "cross_a45": ("cross", 45.0, 1.4, (1.3, 170.0), (1.1, 150.0), 300.0),
}


def _loop(rng, pattern, angle_deg, interval_mm, load, unload, top_kpa):
    d = derive_from_values(pattern, width_mm=7.0, interval_mm=interval_mm, angle_deg=angle_deg,
                           length_mm=100.0, tube=Tube())
    up = np.arange(0.0, top_kpa + 1.0, 10.0)
    down = np.arange(top_kpa - 10.0, -1.0, -10.0)
    branches = [("loading", up, load), ("unloading", down, unload)]
    rows = []
    for name, p, (g, p0) in branches:
        theta = curve(ActuatorModel.from_derived(d, g_mpa=g, p0_kpa=p0, calibration="demo"), p).theta_deg
        theta = theta + rng.normal(0.0, 1.0, p.size)
        rows += [(name, float(pi), float(ti)) for pi, ti in zip(p, theta)]
    return rows


def _bend_csv(rows) -> str:
    return "pressure_kpa,angle_deg,branch\n" + "".join(f"{p:.0f},{t:.2f},{b}\n" for b, p, t in rows)


def _markers(theta_deg, rng) -> np.ndarray:
    """14 markers (2 sides x 7, from the clamped end) on a uniform bend of theta over l0 = 100 mm."""
    s = MARKER_SPACING_MM * np.arange(7)  # arc length of each marker from the clamp [mm]
    turn = np.radians(theta_deg) * s / LENGTH_MM  # tangent angle at each marker, from -z toward +x
    # the arc's points, (1 - cos)/kappa along +x and sin/kappa along -z, written without 0/0 at kappa = 0
    x = s * np.sin(turn / 2.0) * np.sinc(turn / (2.0 * np.pi))
    z = -s * np.sinc(turn / np.pi)
    side = np.stack([x, np.zeros(7), z], axis=1)
    both = np.vstack([side, side + [0.0, SIDE_GAP_MM, 0.0]])
    return both + rng.normal(0.0, 0.05, both.shape)


def _marker_csv(rows, rng) -> str:
    cols = [f"m{i}_{ax}" for i in range(1, 15) for ax in "xyz"]
    lines = ["pressure_kpa,branch," + ",".join(cols)]
    for b, p, t in rows:
        m = _markers(t, rng).ravel()
        lines.append(f"{p:.0f},{b}," + ",".join(f"{v:.3f}" for v in m))
    return "\n".join(lines) + "\n"


def main(out_dir: str = "examples/data") -> None:
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(SEED)
    loops = {name: _loop(rng, *spec) for name, spec in LOOPS.items()}
    for name, rows in loops.items():
        write_text_atomic(out / f"{name}_loop.csv", _bend_csv(rows))
    write_text_atomic(out / "zigzag_w7_markers.csv", _marker_csv(loops["zigzag_w7"], rng))
    print(f"wrote {len(loops) + 1} demo data sets to {out}")


if __name__ == "__main__":
    main(*sys.argv[1:2])
