"""Every name ``import embroact`` gives, and every public method of its classes, is documented
in numpydoc form: Parameters (when it takes any), Returns (functions that return a value) and
a runnable Examples section (classes too). The examples themselves run in tests/test_doctests.py."""
import inspect

import pytest

import embroact


def _public_api():
    for name in sorted(embroact.__all__):
        if name == "__version__":
            continue
        obj = getattr(embroact, name)
        if inspect.isclass(obj) and issubclass(obj, BaseException):
            continue  # errors: a one-line docstring says when they are raised
        yield name, obj
        if inspect.isclass(obj):
            for attr, value in vars(obj).items():
                function = value.__func__ if isinstance(value, (classmethod, staticmethod)) else value
                if not attr.startswith("_") and inspect.isfunction(function):
                    yield f"{name}.{attr}", function


def _sections(doc: str) -> set[str]:
    lines = doc.splitlines()
    return {lines[i].strip() for i in range(len(lines) - 1)
            if lines[i + 1].strip() and set(lines[i + 1].strip()) == {"-"}}


API = list(_public_api())


def test_the_walk_covers_the_main_entry_points():
    names = {n for n, _ in API}
    assert {"analyse", "load_design", "build_plan", "check_design", "write", "build", "curve",
            "StitchPlan.select", "DesignAnalysis.curves"} <= names


@pytest.mark.parametrize("name,obj", API, ids=[n for n, _ in API])
def test_numpydoc_sections(name, obj):
    doc = inspect.getdoc(obj) or ""
    have = _sections(doc)
    need = {"Examples"}
    if not inspect.isclass(obj):
        params = [p for p in inspect.signature(obj).parameters if p not in ("self", "cls")]
        if params:
            need.add("Parameters")
        returns = inspect.signature(obj).return_annotation
        if returns not in (None, "None"):
            need.add("Returns")
    missing = sorted(need - have)
    assert not missing, f"{name}: docstring lacks {', '.join(missing)}"
    assert ">>> " in doc.split("Examples", 1)[-1], f"{name}: its Examples section has no runnable example"


#: Modules whose every public name (``__all__``) and method is documented to the same standard.
DOCUMENTED_MODULES = ("embroact.patterns.kinds", "embroact.predict.kinds", "embroact.patterns.intervals",
                      "embroact.predict.branch", "embroact.predict.tubelaws")


def _module_api():
    import importlib

    for mod in DOCUMENTED_MODULES:
        m = importlib.import_module(mod)
        for name in m.__all__:
            obj = getattr(m, name)
            if not (inspect.isfunction(obj) or inspect.isclass(obj)):
                continue  # constants and registries: a #: comment or a docstring line
            if inspect.isclass(obj) and issubclass(obj, BaseException):
                continue
            yield f"{mod}.{name}", obj
            if inspect.isclass(obj):
                for attr, value in vars(obj).items():
                    function = value.__func__ if isinstance(value, (classmethod, staticmethod)) else value
                    if not attr.startswith("_") and inspect.isfunction(function):
                        yield f"{mod}.{name}.{attr}", function


MODULE_API = list(_module_api())


@pytest.mark.parametrize("name,obj", MODULE_API, ids=[n for n, _ in MODULE_API])
def test_documented_modules_have_numpydoc_sections(name, obj):
    test_numpydoc_sections(name, obj)
