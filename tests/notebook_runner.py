"""Run a notebook's code cells in order, the way a kernel would, and print what each cell shows.

``python notebook_runner.py NOTEBOOK.ipynb`` executes every code cell in one namespace, in
the working directory it is started in. A cell ending in an expression displays it as Jupyter would: the
richest representation the value offers (``_repr_html_``, then ``_repr_svg_``), else its
``repr``. Prints one JSON object: per code cell its printed text, the MIME type shown and
the shown text. A failing cell raises, with the cell's number in the traceback's file name.
This is lighter than a Jupyter kernel (measured in tests/test_notebook.py's docstring).
"""
import ast
import contextlib
import io
import json
import sys

RICH = (("text/html", "_repr_html_"), ("image/svg+xml", "_repr_svg_"))


def _shown(value):
    for mime, method in RICH:
        fn = getattr(value, method, None)
        text = fn() if callable(fn) else None
        if text is not None:
            return mime, text
    return "text/plain", repr(value)


def run(cells):
    namespace, out = {"__name__": "__main__"}, []
    for k, source in enumerate(cells):
        tree = ast.parse(source, filename=f"<cell {k}>")
        last = tree.body.pop() if tree.body and isinstance(tree.body[-1], ast.Expr) else None
        stdout = io.StringIO()
        with contextlib.redirect_stdout(stdout):
            exec(compile(tree, f"<cell {k}>", "exec"), namespace)
            value = eval(compile(ast.Expression(last.value), f"<cell {k}>", "eval"), namespace) if last else None
        mime, text = _shown(value) if value is not None else (None, None)
        out.append({"stdout": stdout.getvalue(), "mime": mime, "shown": text})
    return out


def main(path):
    with open(path, encoding="utf-8") as f:
        nb = json.load(f)
    cells = ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code"]
    print(json.dumps(run(cells)))


if __name__ == "__main__":
    main(sys.argv[1])
