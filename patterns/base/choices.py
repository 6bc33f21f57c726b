"""Named options: one helper that turns a user's string into an enum member or says which are valid.

Every algorithm or setting chosen by name (a pattern, a tube law, where P0 comes from, an
energy form) is an :class:`enum.Enum` whose values are the accepted strings; unknown names are
rejected with the list of valid ones, never silently mapped to a default.

Examples
--------
>>> import enum
>>> class Form(str, enum.Enum):
...     STABLE = "stable"
...     PRINTED = "printed"
>>> check_choice("form", "stable", Form)
<Form.STABLE: 'stable'>
>>> check_choice("form", Form.PRINTED, Form).value
'printed'
>>> try:
...     check_choice("form", "bogus", Form)
... except ValueError as exc:
...     print(exc)
form must be one of 'stable', 'printed', got 'bogus'
"""
from __future__ import annotations

import enum
from typing import TypeVar

from .errors import ParameterError

__all__ = ["check_choice", "choice_values"]

E = TypeVar("E", bound=enum.Enum)


def choice_values(choices: type[enum.Enum]) -> tuple[str, ...]:
    """The accepted strings of an enum, in declaration order.

    Parameters
    ----------
    choices : Enum subclass
        An enum whose member values are the accepted strings.

    Returns
    -------
    tuple of str
        Every member's value, as a string.

    Examples
    --------
    >>> import enum
    >>> choice_values(enum.Enum("Side", {"LEFT": "left", "RIGHT": "right"}))
    ('left', 'right')
    """
    return tuple(str(m.value) for m in choices)


def check_choice(name: str, value: object, choices: type[E]) -> E:
    """The member of ``choices`` named by ``value`` (a member or its string value).

    Parameters
    ----------
    name : str
        Parameter name for the message.
    value : object
        A member of ``choices`` or one of their values.
    choices : Enum subclass
        The enum to pick from.

    Returns
    -------
    Enum member
        ``value`` itself, or the member whose value equals it.

    Raises
    ------
    ParameterError
        ``value`` is neither; the message lists the valid values.

    Examples
    --------
    >>> import enum
    >>> check_choice("side", "left", enum.Enum("Side", {"LEFT": "left", "RIGHT": "right"})).name
    'LEFT'
    """
    if isinstance(value, choices):
        return value
    for member in choices:
        if value == member.value:
            return member
    valid = ", ".join(repr(v) for v in choice_values(choices))
    raise ParameterError(f"{name} must be one of {valid}, got {value!r}")
