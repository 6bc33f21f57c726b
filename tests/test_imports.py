"""Heavy imports stay lazy: what a fresh interpreter has loaded after a light entry point."""
import json
import subprocess
import sys

import pytest

HEAVY_FOR_HELP = ("numpy", "shapely", "trimesh", "scipy")


def _loaded_after(code: str, candidates) -> list[str]:
    probe = f"{code}\nimport json, sys\nprint(json.dumps(sorted(m for m in {tuple(candidates)!r} if m in sys.modules)))"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_a_fresh_interpreter_loads_none_of_them():
    # the control: otherwise the checks below could pass or fail for reasons of the environment
    assert _loaded_after("pass", HEAVY_FOR_HELP) == []


def test_import_patterns_loads_neither_trimesh_nor_scipy():
    assert _loaded_after("import embroact.patterns", ("trimesh", "scipy")) == []


@pytest.mark.parametrize("argv", [["--help"], ["zigzag", "--help"], ["--version"]])
def test_help_loads_no_numpy_shapely_trimesh_scipy(argv):
    code = ("import contextlib, io\nfrom embroact.export.cli.main import main\n"
            f"with contextlib.redirect_stdout(io.StringIO()):\n    code = main({argv!r})\nassert code == 0, code")
    assert _loaded_after(code, HEAVY_FOR_HELP) == []


@pytest.mark.parametrize("module", ["embroact.patterns.base.errors", "embroact.patterns", "embroact.predict",
                                    "embroact"])
def test_package_and_error_imports_load_no_numpy(module):
    # the packages' names load their modules on first use (lazy_loader)
    assert _loaded_after(f"import {module}", HEAVY_FOR_HELP) == []


def test_generator_names_stay_functions_after_their_modules_load():
    # zigzag, cross and measure share their modules' names: importing a module that imports
    # them (design) must not replace the package's function by the module
    code = ("import embroact.patterns.design, embroact.patterns as p, inspect\n"
            "from embroact.patterns import zigzag, cross, measure\n"
            "assert all(inspect.isfunction(f) for f in (zigzag, cross, measure, p.zigzag, p.cross, p.measure))")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_help_leaves_the_kind_registry_unloaded():
    # the registry imports the parameter classes, and with them dataclasses and typing (the larger part of
    # `embroact --help` over a bare `import argparse`); --help lists the kinds from patterns.kindnames
    assert _loaded_after("pass", ("dataclasses", "embroact.patterns.kinds")) == []
    code = ("import contextlib, io\nfrom embroact.export.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n    code = main(['--help'])\nassert code == 0, code")
    assert _loaded_after(code, ("ast", "dataclasses", "embroact.patterns.kinds")) == []


def test_the_package_reads_its_stub_when_a_name_is_asked_for():
    # __init__.pyi is parsed with ast (3 ms of --help) at the first public name, not at `import embroact`
    assert _loaded_after("pass", ("ast",)) == []
    assert _loaded_after("import embroact", ("ast",)) == []
    code = "import embroact\nassert 'analyse' in embroact.__all__ and '__version__' in embroact.__all__"
    assert _loaded_after(code, ("ast",)) == ["ast"]


def test_commands_without_the_registry_are_those_it_registers():
    code = ("import json\nfrom embroact.export.cli.main import commands\nbefore = commands()\n"
            "import embroact.patterns.kinds as kinds\n"
            "print(json.dumps([before, commands(), [k.name for k in kinds.PATTERN_KINDS]]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    before, after, registered = json.loads(out.stdout.strip().splitlines()[-1])
    assert before == after
    assert list(before)[:len(registered)] == registered == ["zigzag", "cross"]


def test_a_kind_registered_later_is_a_command():
    from embroact.export.cli.main import commands
    from embroact.patterns.kinds import PATTERN_KINDS, PatternKind, register
    from embroact.patterns.params import ZigzagParams

    register(PatternKind("plugin_kind", ZigzagParams, "embroact.patterns.zigzag", "width_mm", description="a test"))
    try:
        assert commands()["plugin_kind"] == ("cmd_generate", "generate a test and write its machine file")
    finally:
        PATTERN_KINDS.remove("plugin_kind")
    assert "plugin_kind" not in commands()


def test_a_target_bend_with_a_set_name_loads_no_file_reader(tmp_path):
    # --calibration paper-2025 names a set, no file: the calibration-file reader (and csv with it) and the
    # drawing reader stay unloaded; a calibration file loads its reader
    design = ["design", "--bend-deg", "-40", "--at-kpa", "250", "--pattern", "cross", "-o", str(tmp_path / "d.toml")]
    readers = ("csv", "embroact.export.files.calibfile", "embroact.export.files.svgfile")

    def loaded(argv):
        code = ("import contextlib, io\nfrom embroact.export.cli.main import main\n"
                f"with contextlib.redirect_stdout(io.StringIO()):\n    code = main({argv!r})\nassert code == 0, code")
        return _loaded_after(code, readers)

    assert loaded(design) == []
    from embroact.export.files.calibfile import write_calibration
    from embroact.predict.calibration import PAPER_2025

    write_calibration(tmp_path / "lab.toml", PAPER_2025)
    assert loaded(design + ["--calibration", str(tmp_path / "lab.toml")]) == ["csv", "embroact.export.files.calibfile"]
