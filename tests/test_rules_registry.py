"""The rule registry, the couching rule EA307, the grid-exact record limit and the rules' scaling.

Expected numbers are derived by hand in the comments; scaling is asserted by counting
work (spatial queries, tube pairs compared, findings built), never by timing.
"""
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from dst_decoder import decode
from embroact.export.cli.main import main
from embroact.export.machine.encode import LongLegError, find_long_legs
from embroact.export.machine.formats import write
from embroact.patterns.base.findings import RULES, Inputs, Rule, RuleRegistry, Severity
from embroact.patterns.design import build_plan, design_from_dict
from embroact.patterns.plan import Command, Role, StitchPlan
from embroact.patterns.rules import GEOMETRY_RULES, Layout, RuleSettings, TubeLayout, check_geometry, check_layout
from embroact.patterns.rules import engine
from embroact.predict.rule_catalogue import all_rules, rules_table
from embroact.predict.sleeve_rules import DESIGN_RULES, SLEEVE_RULES

S, J, T, P = Command.STITCH, Command.JUMP, Command.TRIM, Command.STOP
ROOT = Path(__file__).resolve().parent.parent


def _tube(points, name="A"):
    return TubeLayout.from_path(name, points, outer_radius_mm=1.5, clearance_mm=0.3, end_margin_mm=0.0,
                                half_width_mm=3.5)


def _zig(n=10, x0=10.0):
    """Needle points x = x0 + i (1 mm interval), y = +-3.5 alternately: legs cross y = 0 at x0 + i + 0.5."""
    return [(x0 + i, 3.5 if i % 2 == 0 else -3.5) for i in range(n)]


def _codes(findings, code):
    return [f for f in findings if f.code == code]


# --------------------------------------------------------------------- registry
def test_every_rule_declared_once_with_its_check():
    rules = all_rules()
    codes = [r.code for r in rules]
    assert codes == sorted(set(codes)) and len(codes) == len(RULES)
    checked = {r.code for r in DESIGN_RULES}
    assert {r.code for r in GEOMETRY_RULES} | {r.code for r in SLEEVE_RULES} == checked
    for r in rules:
        assert r.title and r.description and r.fix and r.inputs
        # a rule with a check is run by the engine; the model rules (EA4xx) are checked by predict.rules
        assert (r.check is None) == (Inputs.MODEL in r.inputs) == r.code.startswith("EA4"), r.code
        assert (r.code in checked) == (r.check is not None), r.code
    assert RULES["EA307"].inputs_label == "designs, files" and RULES["EA206"].inputs_label == "designs"
    assert RULES["EA401"].inputs_label == "designs (model)"


def test_a_second_declaration_of_a_code_is_refused():
    reg = RuleRegistry()
    reg.declare(Rule("EA900", Severity.INFO, "a", "d", "f", Inputs.FILES))
    with pytest.raises(ValueError, match="rule EA900 is declared twice"):
        reg.declare(Rule("EA900", Severity.INFO, "b", "d", "f", Inputs.FILES))


def test_a_lookup_in_a_fresh_process_loads_the_geometric_rules():
    """Nothing imported but the registry: EA101 is found (patterns.rules is loaded on the miss); an
    unknown code still fails in one line naming the declared codes."""
    code = ("from embroact.patterns.base.findings import RULES\n"
            "f = RULES.finding('EA101', 'needle in the tube')\n"
            "print(f.severity.value, f.title, 'EA307' in RULES, len(RULES) >= 15)\n"
            "try:\n    RULES['EA999']\nexcept Exception as e:\n    print(type(e).__name__, e)\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    first, second = res.stdout.splitlines()
    assert first == f"error {RULES['EA101'].title} True True"
    assert second.startswith("ParameterError rule code must be one of EA101, EA102, ")


def test_readme_table_and_rules_listing_render_from_the_registry(capsys):
    table = rules_table()
    assert table in (ROOT / "README.md").read_text(encoding="utf-8")
    assert main(["check", "--rules"]) == 0
    assert capsys.readouterr().out == table
    assert table.count("\n") == len(all_rules()) + 2


def test_physics_rules_live_in_predict():
    # patterns' own checks know no sleeve: a width without sleeve is predict's finding (EA201)
    lay = Layout.from_points(_zig(), [S] * 10, [0] * 10, tubes=(TubeLayout.from_path(
        "A", [(5, 0), (25, 0)], outer_radius_mm=1.5, clearance_mm=0.3, end_margin_mm=0.0, half_width_mm=1.3),))
    assert not _codes(check_layout(lay), "EA201")
    from embroact.predict.sleeve_rules import check_layout as with_sleeve
    assert len(_codes(with_sleeve(lay), "EA201")) == 1
    src = "\n".join(p.read_text() for p in (ROOT / "patterns").rglob("*.py"))
    assert "predict" not in "".join(line for line in src.splitlines() if line.lstrip().startswith(("import", "from")))


# --------------------------------------------------------------------- EA307 couching
def test_ea307_tube_beside_the_stitches_is_not_held():
    lay = Layout.from_points(_zig(), [S] * 10, [-1] * 10, tubes=(_tube([(5, 10), (25, 10)]),))
    hits = _codes(check_layout(lay), "EA307")
    assert len(hits) == 1 and hits[0].is_error and hits[0].message.startswith("no leg crosses the tube of A")
    assert hits[0].xy_mm == (5.0, 10.0)


def test_ea307_gaps_at_the_ends_and_the_clean_case():
    # legs (10, 3.5) -> (11, -3.5) ...: crossings at x = 10.5 ... 18.5; each leg holds r_f cot(phi) =
    # 1.5 * 1/7 = 0.2143 mm on each side: held from 10.2857 to 18.7143 mm along y = 0.
    held_from, held_to = 10.5 - 1.5 / 7, 18.5 + 1.5 / 7
    # tube from x = 0 to 100: unheld 0 -> 10.29 (10.3 mm > 9 mm = 3 x 3 mm) and 18.71 -> 100 (81.3 mm)
    found = _codes(check_layout(Layout.from_points(_zig(), [S] * 10, [0] * 10, tubes=(_tube([(0, 0), (100, 0)]),))),
                   "EA307")
    assert sorted(f.xy_mm for f in found) == [(0.0, 0.0), (round(held_to, 4), 0.0)]
    msgs = sorted(f.message for f in found)
    assert f"not held for {held_from:.1f} mm, from 0.0 to {held_from:.1f} mm" in msgs[0]
    assert f"not held for {100 - held_to:.1f} mm, from {held_to:.1f} to 100.0 mm" in msgs[1]
    assert "longest allowed 9 mm = 3 x tube diameter" in msgs[0]
    # tube from x = 5 to 25: gaps 5.29 mm and 6.29 mm, both within 9 mm: held
    clean = Layout.from_points(_zig(), [S] * 10, [0] * 10, tubes=(_tube([(5, 0), (25, 0)]),))
    assert not _codes(check_layout(clean), "EA307")
    # a tighter tolerance (1.5 diameters = 4.5 mm) flags both ends again
    assert len(_codes(check_layout(clean, RuleSettings(couching_gap_factor=1.5)), "EA307")) == 2


def test_ea307_gap_inside_the_embroidery():
    # stitches x = 10..19, a jump to x = 40 (no thread), stitches 41..49, over one tube from x = 5 to 55:
    # held up to 18.5 + 1.5/7 and again from 41.5 - 1.5/7, i.e. s = 13.71 to 36.29 mm along the path
    # (22.57 mm) is not held
    xy = _zig() + _zig(x0=40.0)
    cmds = [S] * 10 + [J] + [S] * 9
    hits = _codes(check_layout(Layout.from_points(xy, cmds, [0] * 20, tubes=(_tube([(5, 0), (55, 0)]),))), "EA307")
    assert len(hits) == 1 and "not held for 22.6 mm, from 13.7 to 36.3 mm" in hits[0].message


def test_generated_designs_are_couched():
    for act in ({"pattern": "zigzag", "width_mm": 7, "interval_mm": 1},
                {"pattern": "cross", "width_mm": 7, "interval_mm": 1.4, "angle_deg": 70}):
        plan = build_plan(design_from_dict({"actuator": [dict(act, name="A1", length_mm=100)]}))
        assert not _codes(check_geometry(plan), "EA307"), act


def _dst(tmp_path):
    """A 100 mm zigzag whose file starts at its path's start (--origin 0,0): file frame = path frame."""
    out = tmp_path / "z.dst"
    assert main(["zigzag", "--width-mm", "7", "--interval-mm", "1", "--length-mm", "100", "-o", str(out),
                 "--origin", "0,0"]) == 0
    return out


@pytest.mark.parametrize("tube_path, code", [("0,10 100,10", 1), ("200,50 300,50", 1), ("0,0 100,0", 0)])
def test_check_file_finds_a_tube_that_is_not_couched(tmp_path, capsys, tube_path, code):
    out = _dst(tmp_path)
    capsys.readouterr()
    assert main(["check", str(out), "--tube-path", tube_path, "--json"]) == code
    doc = json.loads(capsys.readouterr().out)
    assert [f["code"] for f in doc["findings"] if f["severity"] == "error"] == (["EA307"] if code else [])


def test_files_get_the_default_machines_hoop(tmp_path, capsys):
    out = _dst(tmp_path)
    capsys.readouterr()
    # a tube path 300 mm long beyond the stitches does not move the hoop (centred on the records); a
    # tube file's [machine] table can shrink it: 50 mm < the 100 mm the zigzag spans -> EA306
    tubes = tmp_path / "t.toml"
    tubes.write_text('[[tube]]\npath_mm = "0,0 100,0"\n[machine]\nhoop_width_mm = 50.0\n', encoding="utf-8")
    assert main(["check", str(out), "--tube", str(tubes), "--json"]) == 1
    assert {f["code"] for f in json.loads(capsys.readouterr().out)["findings"]} == {"EA306"}
    from embroact.export.machine.filecheck import file_rule_settings, read_records
    s = file_rule_settings(read_records(out))
    assert (s.hoop_width_mm, s.hoop_height_mm, s.format) == (200.0, 200.0, "dst")


# --------------------------------------------------------------------- EA102 on the machine grid
def _leg_plan(x0, x1):
    return StitchPlan.from_records([
        (x0, 3.0, P, Role.CONTROL), (x0, 3.0, S, Role.TIE_IN), (x1, 3.0, S, Role.LEG),
        (x1, 3.0, T, Role.CONTROL), (x1, 3.0, Command.END, Role.CONTROL, -1)])


def test_ea102_is_judged_on_the_grid_the_writer_rounds_to(tmp_path):
    # -0.049 and 12.149 mm round to 0 and 121 units: a 12.1 mm record, the DST limit exactly
    fits = _leg_plan(-0.049, 12.149)
    assert not _codes(check_geometry(fits), "EA102") and find_long_legs(fits, 12.1) == ()
    write(fits, tmp_path / "fits.dst")
    stitches = [r for r in decode((tmp_path / "fits.dst").read_bytes()).records if r.kind == "stitch"]
    assert [(r.dx, r.dy) for r in stitches] == [(0, 0), (121, 0)]  # one record, as decoded independently
    # -0.051 rounds to -1 unit: 122 units = 12.2 mm: the rule and the writer both refuse it
    over = _leg_plan(-0.051, 12.149)
    hits = _codes(check_geometry(over), "EA102")
    assert [f.stitch_index for f in hits] == [2] and "|dx| 12.20 mm" in hits[0].message
    with pytest.raises(LongLegError):
        write(over, tmp_path / "over.dst")


# --------------------------------------------------------------------- scaling (counted, not timed)
def _grid_design(n, row_mm=15.0):
    acts = [{"name": f"A{i}", "pattern": "zigzag", "width_mm": 7, "interval_mm": 1, "length_mm": 40,
             "origin_mm": [(i % 10) * 110.0, (i // 10) * row_mm]} for i in range(n)]
    return design_from_dict({"actuator": acts})


def test_tube_queries_do_not_grow_with_the_number_of_tubes(monkeypatch):
    subjects = []
    real = engine.Subject.__init__

    def keep(self, *args, **kwargs):
        real(self, *args, **kwargs)
        subjects.append(self)

    monkeypatch.setattr(engine.Subject, "__init__", keep)
    pairs = {}
    settings = RuleSettings(hoop_width_mm=2000.0, hoop_height_mm=2000.0)
    for n in (10, 100):
        assert check_geometry(build_plan(_grid_design(n)), settings) == ()
        s = subjects[-1]
        # one query of all needle points against all laid tubes (EA101), one of all legs against all axes
        # (EA203, EA307): the same two queries for 10 and for 100 tubes
        assert (s.laid_tubes.queries, s.axes.queries) == (1, 1)
        # rows 7.5 mm apart: bands 3.5 + 3.5 mm leave 0.5 mm < the 1 mm clearance between vertical neighbours
        found = check_geometry(build_plan(_grid_design(n, row_mm=7.5)), settings)
        assert {f.code for f in found} == ({"EA304"} if n > 10 else set())
        pairs[n] = len(subjects[-1].shared("tube pairs", lambda: None))
    # laid tubes (40 mm + 2 x 30 mm margins) of neighbouring columns are 10 mm apart, beyond the 8 mm reach
    # of EA303/EA304: only vertical neighbours are compared, 10 columns x (rows - 1), not n (n - 1) / 2
    assert pairs == {10: 0, 100: 90}


def test_findings_past_the_cap_are_not_built(monkeypatch):
    n = 5000
    xy = np.column_stack([np.arange(n, dtype=float), np.zeros(n)])  # 5 m of records in a 200 mm hoop
    lay = Layout.from_points(xy, [S] * n, [-1] * n, tubes=())  # needle points (a run of jumps outside is one finding)
    built = []
    real = engine.Subject.point
    monkeypatch.setattr(engine.Subject, "point", lambda self, *a, **k: built.append(1) or real(self, *a, **k))
    hits = _codes(check_layout(lay, RuleSettings(hoop_width_mm=200.0, hoop_height_mm=200.0)), "EA306")
    # the hoop spans [2399.5, 2599.5]: 4800 records outside; 10 listed, one summary
    assert len(hits) == 11 and hits[-1].message.startswith("4790 more findings of this rule")
    assert len(built) == 11


def test_check_of_a_file_imports_no_scipy(tmp_path):
    out = _dst(tmp_path)
    code = ("import sys\nfrom embroact.export.cli.main import main\n"
            f"rc = main(['check', {str(out)!r}, '--tube-path', '0,0 100,0'])\n"
            "print(rc, sorted(m for m in sys.modules if m.split('.')[0] == 'scipy'))")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert res.stdout.strip().splitlines()[-1] == "0 []"


def test_density_grid_matches_brute_force_on_clusters():
    from embroact.patterns.spatial import needle_density

    rng = np.random.default_rng(11)
    pts = np.vstack([rng.normal(c, 0.3, size=(150, 2)) for c in ((0, 0), (2, 1), (-40, 900))])
    d = np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))
    for radius in (0.5, 0.2, 2.0):
        assert needle_density(pts, radius).tolist() == (d <= radius).sum(axis=1).tolist()
    assert math.isclose(needle_density(pts[:1]).sum(), 1)
