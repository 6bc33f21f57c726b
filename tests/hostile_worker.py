"""Run many command lines in one process under a memory ceiling; report each as a JSON line.

Used by tests/test_hostile_*.py: ``python hostile_worker.py CEILING_BYTES`` reads a JSON
list of cases ``{"id", "argv", "cwd"}`` on stdin, sets ``RLIMIT_AS`` (the address space,
so a case that tries to allocate past the ceiling fails there instead of swapping), and
runs ``embroact.export.cli.main.main(argv)`` for each case in its directory with stdout
and stderr captured. Before each case it prints ``{"start": id}``, after it
``{"id", "code", "out", "err", "s"}`` (``code`` is ``"crash: ..."`` when something other
than an exit code came out), so a case that kills the process is named by the last start
line. One process for all cases: the import cost (numpy, shapely, pystitch) is paid once.
"""
from __future__ import annotations

import contextlib
import io
import json
import os
import resource
import sys
import time


def _run(case: dict) -> dict:
    from embroact.export.cli.main import main

    out, err = io.StringIO(), io.StringIO()
    os.chdir(case.get("cwd") or ".")
    t = time.perf_counter()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(case["argv"])
    except BaseException as exc:  # noqa: BLE001 - every escape is a finding
        code = f"crash: {type(exc).__name__}: {str(exc)[:300]}"
    return {"id": case["id"], "code": code, "out": out.getvalue()[-2000:], "err": err.getvalue()[-2000:],
            "s": time.perf_counter() - t}


def main() -> None:
    if os.environ.get("EMBROACT_TEST_KINDS") == "1":  # as tests/conftest.py: the suite with a third kind
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import kind_parallel

        kind_parallel.register_parallel()
    ceiling = int(sys.argv[1])
    resource.setrlimit(resource.RLIMIT_AS, (ceiling, ceiling))
    cases = json.loads(sys.stdin.read())
    real = sys.stdout
    for case in cases:
        print(json.dumps({"start": case["id"]}), file=real, flush=True)
        print(json.dumps(_run(case)), file=real, flush=True)


if __name__ == "__main__":
    main()
