"""The studio's save: the design file as the user wrote it, with only the edited fields changed.

The studio edits a *form* (the design-file dict, :func:`~embroact.export.studio.form.design_form`).
Saving a design read from a file does not write that form out: :func:`edited_toml` parses
the file's text with tomlkit (which keeps comments, order, spacing and number spelling) and
changes only the keys whose value differs between the form the file gave and the form now,
so ``path = "drawing.svg#tube1"`` stays a reference and every comment stays where it was.
A file saved into another folder gets its relative references (drawings, calibration
files) rewritten to point at the same files from there (:func:`moved_references`).
tomlkit is part of the studio extra (``pip install embroact[studio]``).

Examples
--------
>>> text = '# my design\\nname = "d"  # kept\\n[[actuator]]\\nname = "A"\\nwidth_mm = 7  # rail spacing\\n'
>>> before = {"name": "d", "actuator": [{"name": "A", "width_mm": 7}]}
>>> after = {"name": "d", "actuator": [{"name": "A", "width_mm": 8.0}]}
>>> print(edited_toml(text, before, after), end="")
# my design
name = "d"  # kept
[[actuator]]
name = "A"
width_mm = 8.0  # rail spacing
"""
from __future__ import annotations

import os
from pathlib import Path

__all__ = ["changes", "edited_toml", "moved_references"]

_Key = tuple  # a key path: str for a table key, int for an index into an array of tables


def _leaves(value, prefix: _Key = ()) -> dict:
    """Flat {key path: value} of a form; tables and arrays of tables are walked, other values are leaves."""
    if isinstance(value, dict):
        out: dict = {}
        for k, v in value.items():
            out.update(_leaves(v, (*prefix, k)))
        return out
    if isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
        out = {}
        for i, v in enumerate(value):
            out.update(_leaves(v, (*prefix, i)))
        return out
    return {prefix: value}


def changes(before: dict, after: dict) -> list[tuple[_Key, object]]:
    """The key paths whose value differs between two forms, with the new value (None: removed).

    Parameters
    ----------
    before, after : dict
        Two design forms.

    Returns
    -------
    list of (tuple, object)

    Examples
    --------
    >>> changes({"a": 1, "t": {"b": 2, "c": 3}}, {"a": 1, "t": {"b": 5}})
    [(('t', 'b'), 5), (('t', 'c'), None)]
    """
    old, new = _leaves(before), _leaves(after)
    out = [(k, v) for k, v in new.items() if k not in old or old[k] != v or type(old[k]) is not type(v)]
    out += [(k, None) for k in old if k not in new]
    return out


def _container(doc, key: _Key):
    """The table holding ``key``'s last part, made where missing."""
    import tomlkit

    node = doc
    for part in key[:-1]:
        if isinstance(part, int):
            node = node[part]
        else:
            if part not in node:
                node[part] = tomlkit.table()
            node = node[part]
    return node


def _assign(table, key, value) -> None:
    """``table[key] = value``, keeping the comment at the end of the old value's line."""
    import tomlkit

    item = tomlkit.item(value)
    old = table[key] if key in table else None
    trivia = getattr(old, "trivia", None)
    if trivia is not None:
        for attr in ("indent", "comment_ws", "comment", "trail"):
            setattr(item.trivia, attr, getattr(trivia, attr))
    table[key] = item


def edited_toml(text: str, before: dict, after: dict, *, src_dir: str | os.PathLike | None = None,
                dst_dir: str | os.PathLike | None = None) -> str:
    """``text`` (a design file) with the fields that differ between ``before`` and ``after`` set.

    Parameters
    ----------
    text : str
        The design file's TOML text, as read.
    before : dict
        The form the file gave when it was read.
    after : dict
        The form now.
    src_dir, dst_dir : path, optional
        The folder the file was read from and the one it is written to: relative references
        are rewritten by :func:`moved_references` where they differ.

    Returns
    -------
    str
        The same text but for the changed values (and removed keys); comments kept.

    Examples
    --------
    >>> text = 'name = "demo"  # kept\\n[tube]\\nouter_radius_mm = 1.5\\n'
    >>> print(edited_toml(text, {"name": "demo", "tube": {"outer_radius_mm": 1.5}},
    ...                   {"name": "demo", "tube": {"outer_radius_mm": 1.6}}), end="")
    name = "demo"  # kept
    [tube]
    outer_radius_mm = 1.6
    """
    import tomlkit

    doc = tomlkit.parse(text)
    for key, value in changes(before, after):
        table = _container(doc, key)
        if value is None:
            if key[-1] in table:
                del table[key[-1]]
        else:
            _assign(table, key[-1], value)
    if src_dir is not None and dst_dir is not None:
        moved_references(doc, src_dir, dst_dir)
    return tomlkit.dumps(doc)


def moved_references(doc, src_dir: str | os.PathLike, dst_dir: str | os.PathLike) -> None:
    """Point the relative file references of a design file's ``doc`` (actuator ``path = "FILE.svg#id"``,
    ``model.calibration`` files) from ``dst_dir`` at the files they named from ``src_dir`` (in place).

    Parameters
    ----------
    doc : mapping
        A design file's parsed TOML (a dict or a tomlkit document), changed in place.
    src_dir, dst_dir : str or os.PathLike
        The folder the file was read from and the one it is written to.

    Examples
    --------
    >>> import tempfile
    >>> src = Path(tempfile.mkdtemp()); (src / "d.svg").write_text("<svg/>"); (src / "out").mkdir()
    6
    >>> doc = {"actuator": [{"path": "d.svg#t"}, {"path": "M 0 0 L 1 0"}]}
    >>> moved_references(doc, src, src / "out"); [a["path"] for a in doc["actuator"]]
    ['../d.svg#t', 'M 0 0 L 1 0']
    """
    from ..files.svgfile import is_svg_ref, split_ref

    src, dst = Path(src_dir).resolve(), Path(dst_dir).resolve()
    if src == dst:
        return

    def moved(ref: str) -> str:
        file, name = split_ref(ref)
        if os.path.isabs(file) or not (src / file).is_file():
            return ref
        rel = Path(os.path.relpath(src / file, dst)).as_posix()
        return rel + (f"#{name}" if name is not None else "")

    acts = doc.get("actuator", [])
    for a in acts if isinstance(acts, list) else ():
        if not isinstance(a, dict):
            continue
        if is_svg_ref(a.get("path")) and moved(str(a["path"])) != a["path"]:
            _assign(a, "path", moved(str(a["path"])))
        model = a.get("model")
        if isinstance(model, dict) and isinstance(model.get("calibration"), str):
            if moved(str(model["calibration"])) != model["calibration"]:
                _assign(model, "calibration", moved(str(model["calibration"])))
