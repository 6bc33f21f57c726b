"""Picture titles that fit their picture: measured in the bold sans-serif they are drawn in, wrapped or shortened.

Widths come from the Helvetica-Bold metrics (Arial and Liberation Sans, what browsers and
librsvg draw for ``font-family:Helvetica,Arial,sans-serif``, have the same advances), in
thousandths of the font size.  :func:`fit_title` tries the title on one line at its size,
then at a smaller size, then wrapped at its separators ("; ", ", ", spaces) onto at most
``max_lines`` lines, the last one shortened with an ellipsis when even that is too long.

Examples
--------
>>> round(text_width_px("MMM", 10.0), 2)  # 3 x 0.833 em
24.99
>>> fit_title("Predicted bend angle", 300.0)
FittedTitle(lines=('Predicted bend angle',), font_px=15.0)
>>> fit_title("three-actuators: predicted bend; tube paper law, r_f 1.5", 200.0, max_lines=3)
FittedTitle(lines=('three-actuators: predicted bend;', 'tube paper law, r_f 1.5'), font_px=12.0)
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["FittedTitle", "fit_title", "text_width_px"]

# Helvetica-Bold advances [1/1000 em] of the printable ASCII characters, space (32) to tilde (126)
_ASCII = (278, 333, 474, 556, 556, 889, 722, 238, 333, 333, 389, 584, 278, 333, 278, 278,
          556, 556, 556, 556, 556, 556, 556, 556, 556, 556, 333, 333, 584, 584, 584, 611,
          975, 722, 722, 722, 722, 667, 611, 778, 722, 278, 556, 722, 611, 833, 722, 778,
          667, 778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 333, 278, 333, 584, 556,
          333, 556, 611, 556, 611, 556, 333, 611, 611, 278, 278, 556, 278, 889, 611, 611,
          611, 611, 389, 556, 333, 611, 556, 778, 556, 556, 500, 389, 280, 389, 584)
_OTHER = {"\u00b0": 400, "\u2026": 1000, "\u00b2": 333, "\u00b3": 333}
_WIDE = 778  # any other character: as wide as a capital O (a safe guess for accented and CJK letters is wider)

ELLIPSIS = "\u2026"
_SEPARATORS = ("; ", ", ", " ")


@dataclass(frozen=True, slots=True)
class FittedTitle:
    """A title as drawn: its lines and their font size.

    Attributes
    ----------
    lines : tuple of str
        One or more lines, top to bottom.
    font_px : float
        Font size [px].

    Examples
    --------
    >>> fit_title("short", 200.0)
    FittedTitle(lines=('short',), font_px=15.0)
    """

    lines: tuple[str, ...]
    font_px: float


def text_width_px(text: str, font_px: float) -> float:
    """Width [px] of ``text`` in bold Helvetica (or Arial) at ``font_px``.

    Parameters
    ----------
    text : str
        One line.
    font_px : float
        Font size [px].

    Returns
    -------
    float

    Examples
    --------
    >>> text_width_px("MM", 10.0)
    16.66
    """
    units = 0
    for ch in text:
        o = ord(ch)
        units += _ASCII[o - 32] if 32 <= o < 127 else _OTHER.get(ch, _WIDE)
    return units * font_px / 1000.0


def _pieces(text: str) -> list[str]:
    """``text`` cut after each separator (the coarsest one present that cuts it), separators kept."""
    for sep in _SEPARATORS:
        parts = text.split(sep)
        if len(parts) > 1:
            return [p + sep for p in parts[:-1]] + [parts[-1]]
    return [text]


def _wrap(text: str, width_px: float, font_px: float) -> list[str]:
    """Greedy lines no wider than ``width_px``, breaking at the coarsest separators first."""
    lines: list[str] = []
    line = ""
    for piece in _pieces(text):
        if text_width_px((line + piece).rstrip(), font_px) <= width_px:
            line += piece
            continue
        if line:
            lines.append(line.rstrip())
        if text_width_px(piece.rstrip(), font_px) <= width_px or piece == text:
            line = piece
        else:  # a piece too long on its own: wrap it at finer separators
            sub = _wrap(piece.rstrip(), width_px, font_px)
            lines += sub[:-1]
            line = sub[-1] + piece[len(piece.rstrip()):]
    lines.append(line.rstrip())
    return lines


def _shorten(line: str, width_px: float, font_px: float) -> str:
    """``line`` cut (after a list item, else at a space, else anywhere) so that it and an ellipsis fit."""
    while line and text_width_px(line + " " + ELLIPSIS, font_px) > width_px:
        body = line.rstrip(",; ")
        item = max(body.rfind(", "), body.rfind("; "))
        cut = item if item > len(body) // 2 else body.rfind(" ")
        line = body[:cut] if cut > 0 else body[:-1]
    return line.rstrip(",; ") + (" " + ELLIPSIS if " " in line else ELLIPSIS)


def fit_title(text: str, width_px: float, *, font_px: float = 15.0, small_px: float = 12.0,
              max_lines: int = 2) -> FittedTitle:
    """The title ``text`` fitted into ``width_px``.

    Parameters
    ----------
    text : str
        The title.
    width_px : float
        Room for it [px].
    font_px : float
        Size when it fits on one line.
    small_px : float
        Smaller size, tried on one line, then for wrapped lines.
    max_lines : int
        Most lines; the last is shortened with an ellipsis when the title needs more.

    Returns
    -------
    FittedTitle

    Examples
    --------
    >>> fit_title("a fairly long title that will not fit on one line", 120.0)
    FittedTitle(lines=('a fairly long title that', 'will not fit on one …'), font_px=12.0)
    """
    for size in (font_px, small_px):
        if text_width_px(text, size) <= width_px:
            return FittedTitle((text,), size)
    lines = _wrap(text, width_px, small_px)
    if len(lines) > max_lines:
        lines = lines[:max_lines - 1] + [" ".join(lines[max_lines - 1:])]
    lines = [line if text_width_px(line, small_px) <= width_px else _shorten(line, width_px, small_px)
             for line in lines]
    return FittedTitle(tuple(lines), small_px)
