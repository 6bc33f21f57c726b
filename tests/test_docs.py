"""The repository cites only documents it holds.

Every tracked file is scanned for citations of the model and machine pages that used to
live outside the repository, and for references to ``docs/<page>.md`` (with an optional
section number or ``#anchor``); each cited page, section and anchor must exist. README's
and the docs pages' own Markdown links must resolve too.
"""
from __future__ import annotations

import math
import re
import subprocess
from functools import cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
#: Folders never scanned when the tree is walked without git (environments, caches, outputs).
_SKIP_DIRS = {".git", ".venv", ".venv-ci", "__pycache__", ".hypothesis", ".pytest_cache", "build", "dist", "out"}
_TEXT_SUFFIXES = {".py", ".md", ".toml", ".txt", ".cfg", ".ini", ".sh", ".csv", ".json", ".html", ".svg", ""}

# Spelled in two parts so that this file does not cite them itself.
_EXTERNAL = re.compile(r"\b(?:" + "MODEL" + r"|" + "EMBROIDERY" + r"|HOUSE-STYLE)\.md\b")
#: ``docs/model.md``, optionally followed by ``section 4``, ``sections 2-3``, ``sections 10 and 11`` or ``#anchor``.
_DOC_REF = re.compile(
    r"docs/(?P<page>[A-Za-z0-9_-]+)\.md"
    r"(?:#(?P<anchor>[A-Za-z0-9_-]+)"
    r"|,?\s+sections?\s+(?P<sections>\d+(?:\s*(?:-|,|and)\s*\d+)*))?"
)
_LINK = re.compile(r"\]\((?P<target>[^)\s]+)\)")


def _tracked_files() -> list[Path]:
    try:
        out = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
        files = [ROOT / p for p in out.decode("utf-8").split("\0") if p]
    except (OSError, subprocess.CalledProcessError):  # no git (e.g. an unpacked sdist): walk the tree
        files = [p for p in ROOT.rglob("*") if p.is_file() and not any(
            part in _SKIP_DIRS or part.endswith(".egg-info") for part in p.relative_to(ROOT).parts)]
    return sorted(p for p in files if p.is_file() and p.suffix in _TEXT_SUFFIXES)


@cache
def _text(path: Path) -> str:
    return path.read_text(encoding="utf-8", errors="replace")


def _slug(heading: str) -> str:
    """GitHub's anchor for a Markdown heading: lower case, punctuation dropped, spaces to hyphens."""
    kept = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return kept.replace(" ", "-")


@cache
def _headings(page: Path) -> tuple[tuple[str, ...], frozenset[int]]:
    """(anchors, numbered sections) of a Markdown page; sections are the ``## N.`` headings."""
    titles = re.findall(r"^#{1,6}\s+(.+?)\s*$", _text(page), flags=re.M)
    numbers = {int(m.group(1)) for t in titles if (m := re.match(r"(\d+)\.\s", t))}
    return tuple(_slug(t) for t in titles), frozenset(numbers)


def _section_numbers(spec: str) -> set[int]:
    nums: set[int] = set()
    for part in re.split(r"\s*(?:,|and)\s*", spec):
        lo, _, hi = part.partition("-")
        nums.update(range(int(lo), int(hi or lo) + 1))
    return nums


def _broken_refs(path: Path) -> list[str]:
    bad = []
    for m in _DOC_REF.finditer(_text(path)):
        page = DOCS / f"{m['page']}.md"
        where = f"{path.relative_to(ROOT)}: {m.group(0)!r}"
        if not page.is_file():
            bad.append(f"{where}: no such page")
            continue
        anchors, numbers = _headings(page)
        if m["anchor"] and m["anchor"] not in anchors:
            bad.append(f"{where}: no heading with anchor #{m['anchor']}")
        if m["sections"] and not _section_numbers(m["sections"]) <= numbers:
            bad.append(f"{where}: {page.name} has sections {sorted(numbers)}")
    return bad


def _broken_links(path: Path) -> list[str]:
    """Relative Markdown links of a .md file whose target file or anchor does not exist."""
    bad = []
    for m in _LINK.finditer(_text(path)):
        target = m["target"]
        if re.match(r"[a-z]+:", target):  # https:, mailto:
            continue
        file_part, _, anchor = target.partition("#")
        dest = (path.parent / file_part).resolve() if file_part else path
        if not dest.exists():
            bad.append(f"{path.relative_to(ROOT)}: link {target!r}: no such file")
        elif anchor and dest.suffix == ".md" and anchor not in _headings(dest)[0]:
            bad.append(f"{path.relative_to(ROOT)}: link {target!r}: no such heading")
    return bad


def test_slug_matches_github_anchors():
    assert _slug("3. Inflation phase (P < P0)") == "3-inflation-phase-p--p0"
    assert _slug("4. DST (Tajima)") == "4-dst-tajima"
    assert _section_numbers("2-3") == {2, 3} and _section_numbers("10 and 11") == {10, 11}


def test_the_model_and_machine_pages_exist():
    for name in ("model", "machine"):
        anchors, numbers = _headings(DOCS / f"{name}.md")
        assert numbers == set(range(1, max(numbers) + 1)), f"docs/{name}.md sections are not numbered 1..n"


def test_no_file_cites_documents_outside_the_repository():
    files = _tracked_files()
    assert ROOT / "README.md" in files
    hits = [f"{p.relative_to(ROOT)}:{n}: {line.strip()}"
            for p in files for n, line in enumerate(_text(p).splitlines(), 1) if _EXTERNAL.search(line)]
    assert not hits, "cite docs/model.md or docs/machine.md instead:\n" + "\n".join(hits)


def test_every_cited_docs_page_and_section_exists():
    bad = [b for p in _tracked_files() for b in _broken_refs(p)]
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize("page", ["README.md", "docs/model.md", "docs/machine.md", "benchmarks/README.md"])
def test_markdown_links_resolve(page):
    path = ROOT / page
    bad = _broken_links(path)
    assert not bad, "\n".join(bad)


_CODE_PATH = re.compile(r"`((?:patterns|predict|export|benchmarks|examples|tests|docs)/[\w/.-]+\.(?:py|md|toml|svg|csv))`")
_CODE_NAME = re.compile(r"`((?:patterns|predict|export)(?:\.[A-Za-z_]\w*)+)")


def _resolves(dotted: str) -> bool:
    """True when ``embroact.<dotted>`` is a module or an attribute chain of one."""
    import importlib

    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(["embroact", *parts[:cut]]))
        except ImportError:
            continue
        for name in parts[cut:]:
            if not hasattr(obj, name):
                return False
            obj = getattr(obj, name)
        return True
    return False


@pytest.mark.parametrize("page", ["docs/model.md", "docs/machine.md"])
def test_code_the_docs_name_exists(page):
    text = _text(ROOT / page)
    missing = [p for p in _CODE_PATH.findall(text) if not (ROOT / p).exists()]
    missing += [n for n in _CODE_NAME.findall(text) if not _resolves(n)]
    assert not missing, f"{page} names code that does not exist: {missing}"


def test_readme_links_to_the_docs_pages():
    targets = {m["target"].partition("#")[0] for m in _LINK.finditer(_text(ROOT / "README.md"))}
    assert {"docs/model.md", "docs/machine.md"} <= targets
    for t in targets:
        if t.startswith("docs/") and t.endswith(".md"):
            assert (ROOT / t).is_file(), t


# -- the pages' numbers are the code's -----------------------------------------------------
def _fenced(page: str, lang: str) -> list[str]:
    """Bodies of the page's fenced code blocks whose info string is ``lang`` ("" for plain fences)."""
    blocks, body, info = [], None, ""
    for line in _text(ROOT / page).splitlines():
        if line.startswith("```"):
            if body is None:
                body, info = [], line[3:].strip()
            else:
                if info == lang:
                    blocks.append("\n".join(body) + "\n")
                body = None
        elif body is not None:
            body.append(line)
    return blocks


def test_model_worked_example_snippet_agrees_with_embroact(capsys):
    """The page's plain-Python P(90 deg) (printed form, central differences) against pressure_at."""
    from embroact.predict.curve import ActuatorModel, pressure_at

    (snippet,) = _fenced("docs/model.md", "python")
    exec(compile(snippet, "docs/model.md", "exec"), {})
    by_hand = float(capsys.readouterr().out)
    m = ActuatorModel("zigzag", length_mm=100.0, r0_mm=(7 + 2 * math.hypot(3.5, 3.0)) / (2 * math.pi), beta0_deg=0.0,
                      outer_radius_mm=1.5, inner_radius_mm=1.0, g_e_mpa=0.13, g_mpa=2.7, p0_kpa=85.0)
    assert by_hand == 187.65
    assert float(pressure_at(m, [90.0]).pressure_kpa[0]) == pytest.approx(by_hand, abs=0.005)


def test_model_worked_example_table_is_what_predict_prints(capsys):
    from embroact.export.cli.main import main

    command = next(c for c in _fenced("docs/model.md", "sh") if "--width-mm 7" in c).strip()
    assert main(command.split()[1:]) == 0
    printed = [" ".join(line.split()) for line in capsys.readouterr().out.splitlines()]
    table = next(b for b in _fenced("docs/model.md", "") if b.lstrip().startswith("pressure_kpa"))
    header, *rows = [" ".join(line.split()) for line in table.strip().splitlines()]
    assert any(line.startswith(header) for line in printed), (header, printed)  # later columns may be added
    assert rows and all(row in printed for row in rows), (rows, printed)


def test_model_page_headline_numbers():
    """P0 from geometry, the neutral angle, the thick-wall ceiling and the paper set's w = 5 mm bend."""
    from embroact.patterns.params import Tube
    from embroact.predict import tubelaws
    from embroact.predict.calibration import model_for
    from embroact.predict.curve import curve
    from embroact.predict.derived import derive_from_values
    from embroact.predict.sleeve import neutral_angle_deg, sleeve_radius_mm

    text = _text(DOCS / "model.md")
    p0 = [float(tubelaws.pressure_kpa(sleeve_radius_mm(w, 1.5), Tube())) for w in (5, 7, 9)]
    assert "25.3 / 84.5 / 172.1 kPa" in text and [round(v, 1) for v in p0] == [25.3, 84.5, 172.1]
    assert "**33.37 deg**" in text and round(float(neutral_angle_deg(7, 1.5)), 2) == 33.37
    assert "**52.71 kPa**" in text and round(float(tubelaws.thick_wall_limit_kpa(Tube())), 2) == 52.71
    d = derive_from_values("zigzag", width_mm=5, interval_mm=1, angle_deg=0, length_mm=100, tube=Tube())
    c = curve(model_for(d).model, [250.0])
    assert "**2032.4 deg** at 250 kPa, status `COILED`" in text
    assert (round(float(c.theta_deg[0]), 1), c.as_dict()["status"]) == (2032.4, ["COILED"])


def test_model_page_paper_set_numbers():
    """The zigzag folds and the G the paper's w = 5 mm measurement would need with the default tube."""
    from embroact.patterns.params import Tube
    from embroact.predict.calibration import model_for
    from embroact.predict.curve import lockup, pressure_at
    from embroact.predict.derived import derive_from_values

    text = " ".join(_text(DOCS / "model.md").split())
    models = {w: model_for(derive_from_values("zigzag", width_mm=w, interval_mm=1, angle_deg=0, length_mm=100,
                                              tube=Tube())).model for w in (5, 7, 9)}
    folds = {w: lockup(m) for w, m in models.items()}
    assert [(round(t), round(p, 1)) for t, p in folds.values()] == [(2430, 250.7), (1889, 509.3), (1532, 538.8)]
    assert "at 2430 deg (250.7 kPa) for `w = 5 mm`, 1889 deg (509.3 kPa) for 7 mm, 1532 deg (538.8 kPa)" in text
    m = models[5]
    # P - P0 is proportional to G: the G that puts theta at 290 kPa
    need = [(290.0 - m.p0_kpa) * m.g_mpa / (float(pressure_at(m, [t]).pressure_kpa[0]) - m.p0_kpa) for t in (155, 310)]
    assert [round(g, 2) for g in need] == [3.10, 1.85]
    assert "`G` = 3.10 MPa if it were a whole-strip angle" in text and "or 1.85 MPa if it were the" in text


def test_the_readme_worked_example_runs_as_written(tmp_path, monkeypatch, capsys):
    """The worked example's single-actuator commands, as the README prints them, exit 0, and the check of the file
    the first one writes finds nothing (it once checked the file against the tube without the origin: 7 errors)."""
    import shlex

    from embroact.export.cli.main import main

    block = _text(ROOT / "README.md").split("## Worked example", 1)[1].split("```sh", 1)[1].split("```", 1)[0]
    lines = [ln for ln in block.splitlines() if ln.startswith("embroact ")]
    runs = lines[:3]  # the ones on the example's own file (the later ones build, fit and predict from fits)
    assert [ln.split()[1] for ln in runs] == ["cross", "predict", "check"]
    monkeypatch.chdir(tmp_path)
    for ln in runs:
        capsys.readouterr()
        assert main(shlex.split(ln)[1:]) == 0, ln
    assert capsys.readouterr().out.strip() == "cross.dst: embroidery file, format dst, 1 tube(s): no findings"
