"""``embroact calibrate coupon``: the coupon builds, checks clean, decodes to its needle points in every
format (pystitch's readers), and its sheets list what the measurement and the fit need."""
import csv
import importlib
import io
import json
import math
import os
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from svg_text_boxes import text_boxes

from embroact.export.cli.main import main
from embroact.export.files.designfile import load_design
from embroact.export.machine.formats import FORMATS
from embroact.patterns.design import build_plan
from embroact.patterns.plan import Command as C
from embroact.predict.analysis import analyse
from embroact.predict.coupon import plan_coupon
from embroact.predict.rules import check_design
from embroact.predict.sleeve import neutral_angle_deg

pe = pytest.importorskip("pystitch")
ALL = sorted(FORMATS)


@pytest.fixture(scope="module")
def coupon_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("coupon")
    # the paper's two kinds (a kind a test registers, tests/kind_parallel.py, would add its own strips)
    assert main(["calibrate", "coupon", "--out", str(out), "--format", ",".join(ALL), "--patterns", "zigzag,cross"]) == 0
    return out


def _read_back(path, fmt):
    reader = importlib.import_module(f"pystitch.{fmt.capitalize()}Reader")
    with open(path, "rb") as fh:
        data = fh.read()
    return pe.EmbPattern.read_embroidery(reader, io.BytesIO(data), {"trim_at": None, "trim_distance": None,
                                                                    "clipping": False})


def test_coupon_spans_the_design_space():
    c = plan_coupon(("zigzag", "cross"))
    zig = [a.width_mm for a in c.actuators if a.pattern == "zigzag"]
    cross = [a.angle_deg for a in c.actuators if a.pattern == "cross"]
    assert zig == [5.0, 6.0, 7.0, 8.0, 9.0]  # 10/3 to 6 tube radii of the 1.5 mm tube, on the 0.2 mm grid
    neutral = float(neutral_angle_deg(7.0, 1.5))
    below, above = [a for a in cross if a < neutral], [a for a in cross if a > neutral]
    assert len(below) == len(above) == 3
    assert min(abs(a - neutral) for a in cross) >= 5.0  # band 3 deg + 2
    # each cross angle is one the pattern sews exactly: tan(alpha0) = n s / (2 w), n whole
    for a in cross:
        n = 2 * 7.0 * math.tan(math.radians(a)) / 1.4
        assert abs(n - round(n)) < 1e-4
    # every cross leg w / cos(alpha0) stays below the 12.1 mm machine maximum
    assert max(7.0 / math.cos(math.radians(a)) for a in cross) < 12.1
    assert [a.order for a in c.actuators] == list(range(1, 12))
    assert c.hoops == 2 and all(a.label.startswith(f"{a.order:02d} ") for a in c.actuators)


def test_coupon_builds_and_checks_clean(coupon_dir):
    names = sorted(os.listdir(coupon_dir))
    assert names == ["board.svg", "coupon-hoop1.toml", "coupon-hoop2.toml", "coupon.json", "fins-1.svg", "fins-2.svg", "hoop1",
                     "hoop2", "measurements.csv"]
    for h in (1, 2):
        files = sorted(os.listdir(coupon_dir / f"hoop{h}"))
        assert {"template.svg", "worksheet.txt", "worksheet.json", "preview.svg"} <= set(files)
        assert {f"coupon-hoop{h}.{fmt}" for fmt in ALL} <= set(files)
        design = load_design(coupon_dir / f"coupon-hoop{h}.toml")
        findings = check_design(analyse(design), format=ALL)
        assert not [f for f in findings if f.is_error]
        # only the model's own notes (the demonstration calibration's predictions) remain
        assert all(f.code.startswith("EA4") for f in findings), [f.code for f in findings]
        for fmt in ("dst", "pes"):
            assert main(["check", str(coupon_dir / f"hoop{h}" / f"coupon-hoop{h}.{fmt}")]) == 0


@pytest.mark.parametrize("fmt", ALL)
def test_coupon_files_decode_to_its_needle_points(coupon_dir, fmt):
    for h in (1, 2):
        plan = build_plan(load_design(coupon_dir / f"coupon-hoop{h}.toml"))
        want = np.asarray(plan.xy_mm[plan.commands == C.STITCH])
        back = _read_back(coupon_dir / f"hoop{h}" / f"coupon-hoop{h}.{fmt}", fmt)
        got = np.array([(x / 10.0, -y / 10.0) for x, y, c in back.stitches if (c & pe.COMMAND_MASK) == pe.STITCH])
        assert got.shape == want.shape
        # same points, in order, on the formats' 0.1 mm grid (the file's origin is its first point)
        assert np.abs((got - got[0]) - (want - want[0])).max() <= 0.1 + 1e-9


def test_measurement_sheet_rows(coupon_dir):
    with open(coupon_dir / "measurements.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    doc = json.loads((coupon_dir / "coupon.json").read_text())
    steps = doc["pressures_kpa"]
    assert steps[0] == 0 and steps[-1] == 300 and len(steps) == 13
    assert len(rows) == 11 * (2 * len(steps) - 1)
    first = [r for r in rows if r["actuator"] == "01 zigzag w5.0"]
    assert [r["branch"] for r in first].count("loading") == 13 and [r["branch"] for r in first].count("unloading") == 12
    assert [float(r["pressure_kpa"]) for r in first] == steps + steps[-2::-1]
    assert all(r["bend_deg"] == "" for r in rows)
    # every actuator named in the sheet is in its hoop's design file
    for r in rows[:: 2 * len(steps) - 1]:
        assert r["actuator"] in [a.name for a in load_design(coupon_dir / r["design"]).actuators]
    # marker ids: each actuator its own block of 11
    ids = [tuple(a["marker_ids"]) for a in doc["actuators"]]
    assert len({i for block in ids for i in block}) == 11 * 11 and min(min(b) for b in ids) == 8


def test_marker_sheets(coupon_dir):
    fins = [(coupon_dir / f"fins-{k}.svg").read_text() for k in (1, 2)]
    assert sum(f.count('class="marker"') for f in fins) == 11 * 11 and all('id="scale-bar"' in f for f in fins)
    assert sorted({int(i) for f in fins for i in re.findall(r'id="marker-(\d+)"', f)}) == list(range(8, 8 + 121))
    board = (coupon_dir / "board.svg").read_text()
    assert board.count('class="marker"') == 8 and 'id="scale-bar"' in board


#: Paper (width, height) [mm] and the border printers may leave blank on every side (most: 4-6.35 mm).
PAPERS_MM = {"A4": (210.0, 297.0), "Letter": (215.9, 279.4)}
PRINTER_MARGIN_MM = 6.35


def _mm(value: str) -> float:
    assert value.endswith("mm"), value
    return float(value[:-2])


def _ink_boxes(svg: str):
    """Boxes (x0, y0, x1, y1) of the text lines (tests/svg_text_boxes.py) and of every rect and line, untransformed
    (the marker sheets draw in page coordinates)."""
    boxes = [(b.x0, b.y0, b.x1, b.y1, b.text) for b in text_boxes(svg)[0]]
    for el in ET.fromstring(svg).iter():
        tag = el.tag.rsplit("}", 1)[-1]
        if tag == "rect":
            x, y = float(el.get("x", 0)), float(el.get("y", 0))
            boxes.append((x, y, x + float(el.get("width")), y + float(el.get("height")), "rect"))
        elif tag == "line":
            xs, ys = (float(el.get("x1")), float(el.get("x2"))), (float(el.get("y1")), float(el.get("y2")))
            boxes.append((min(xs), min(ys), max(xs), max(ys), "line"))
    return boxes


_NS = "{http://www.w3.org/2000/svg}"


def _template_sheets(coupon_dir):
    """(name, paper, svg) of each page of the hoops' tiled templates."""
    for path in sorted(coupon_dir.glob("hoop*/template-*.html")):
        paper = "A4" if path.name.endswith("a4.html") else "Letter"
        for k, svg in enumerate(re.findall(r"<svg\b.*?</svg>", path.read_text(), flags=re.S)):
            yield f"{path.parent.name}/{path.name} sheet {k + 1}", paper, svg


def _fits(name, w, h, papers):
    for pw, ph in papers:
        assert (w <= pw + 1e-9 and h <= ph + 1e-9) or (h <= pw + 1e-9 and w <= ph + 1e-9), (name, w, h, pw, ph)


def _inside_printable(name, boxes, w, h):
    """Nothing where a printer may not print: the page's outer PRINTER_MARGIN_MM (the page at the paper's corner)."""
    lo, hi_x, hi_y = PRINTER_MARGIN_MM, w - PRINTER_MARGIN_MM, h - PRINTER_MARGIN_MM
    for x0, y0, x1, y1, what in boxes:
        assert lo <= x0 and x1 <= hi_x and lo <= y0 and y1 <= hi_y, (name, what, (x0, y0, x1, y1), (w, h))


def _size(svg: str):
    root = ET.fromstring(svg)
    w, h = _mm(root.get("width")), _mm(root.get("height"))
    assert tuple(float(v) for v in root.get("viewBox").split()) == (0.0, 0.0, w, h)
    return w, h


def test_marker_sheets_fit_a4_and_letter(coupon_dir):
    """At 100 % on A4 and on Letter: each marker sheet no larger than the paper, every text line (its estimated
    extent), rect and line inside the part of the page printers print."""
    names = sorted(p.name for p in coupon_dir.glob("*.svg"))
    assert names == ["board.svg", "fins-1.svg", "fins-2.svg"]
    for name in names:
        svg = (coupon_dir / name).read_text()
        w, h = _size(svg)
        _fits(name, w, h, PAPERS_MM.values())
        _inside_printable(name, _ink_boxes(svg), w, h)


def test_template_sheets_fit_their_paper_and_show_every_label_whole(coupon_dir):
    """The hoops' tiled templates: each page its paper's size, the page's own text inside the printable part, and
    every label of the template whole (inside the tile) on at least one page."""
    whole, labels = {}, set()
    for name, paper, svg in _template_sheets(coupon_dir):
        w, h = _size(svg)
        _fits(name, w, h, [PAPERS_MM[paper]])
        root = ET.fromstring(svg)
        tile = next(g for g in root.iter(f"{_NS}g") if g.get("class") == "tile")
        clip = next(root.iter(f"{_NS}clipPath")).find(f"{_NS}rect")
        cx0, cy0 = float(clip.get("x")), float(clip.get("y"))
        cx1, cy1 = cx0 + float(clip.get("width")), cy0 + float(clip.get("height"))
        in_tile = {id(t) for t in tile.iter(f"{_NS}text")}
        elements = [t for t in root.iter(f"{_NS}text") if (t.text or "").strip()]
        boxes = text_boxes(svg)[0]
        assert len(boxes) == len(elements)
        own = [(b.x0, b.y0, b.x1, b.y1, b.text) for b, t in zip(boxes, elements) if id(t) not in in_tile]
        assert own, name  # the footer
        _inside_printable(name, own, w, h)
        for b, t in zip(boxes, elements):
            if id(t) in in_tile:
                key = (name.split(" sheet")[0], t.text, t.get("x"), t.get("y"))
                labels.add(key)
                if cx0 <= b.x0 and b.x1 <= cx1 and cy0 <= b.y0 and b.y1 <= cy1:
                    whole[key] = name
    assert labels and labels <= set(whole), sorted(labels - set(whole))[:5]


def test_sheet_text_wraps_and_sheets_paginate():
    """The most actuators a coupon holds (22): three sheets, every text line inside the 10 mm margins."""
    from embroact.export.photo.sheet import fins_svgs

    coupon = plan_coupon(("zigzag", "cross"), width_count=10, angle_count=12)
    sheets = fins_svgs(coupon)
    assert len(coupon.actuators) == 22 and len(sheets) == 3
    for svg in sheets:
        boxes, (cx0, cy0, cx1, cy1) = text_boxes(svg)
        assert (cx1, cy1) == (210.0, 279.4)
        assert all(10.0 - 1e-6 <= b.x0 and b.x1 <= cx1 - 10.0 and 10.0 - 1e-6 <= b.y0 and b.y1 <= cy1 - 10.0
                   for b in boxes)


def test_aruco_table_is_opencvs():
    cv2 = pytest.importorskip("cv2")
    from embroact.export.photo.arucobits import marker_cells

    d = cv2.aruco.getPredefinedDictionary(cv2.aruco.DICT_4X4_250)
    for i in range(250):
        img = cv2.aruco.generateImageMarker(d, i, 6)
        assert np.array_equal((img[1:5, 1:5] > 127).astype(int), np.array(marker_cells(i))), i


def test_bad_values_are_one_line(tmp_path, capsys):
    assert main(["calibrate", "coupon", "--out", str(tmp_path), "--patterns", "zigzag,spiral"]) == 2
    assert "patterns must list" in capsys.readouterr().err
    assert main(["calibrate", "coupon", "--out", str(tmp_path), "--angle-range-deg", "30:40"]) == 2
    assert "neutral angle" in capsys.readouterr().err
    assert main(["calibrate", "coupon", "--out", str(tmp_path), "--hoop-width-mm", "90"]) == 2
    assert os.listdir(tmp_path) == []
