"""The pattern kinds by name and one-line description, without loading the registry.

:mod:`embroact.patterns.kinds` (the registry) imports the parameter classes and with them
``dataclasses`` and ``typing``: half of ``embroact --help``'s time over a bare ``import
argparse``. The command line lists the kinds' quick commands from here instead.

Examples
--------
>>> from embroact.patterns.kindnames import BUILTIN_KINDS, kind_descriptions
>>> list(BUILTIN_KINDS)
['zigzag', 'cross']
>>> kind_descriptions()["cross"]
'one cross-pattern actuator'
"""
from __future__ import annotations

import sys

__all__ = ["BUILTIN_KINDS", "kind_descriptions"]

#: name -> description of the kinds embroact registers itself, in registration order
#: (:mod:`embroact.patterns.kinds` registers them with these descriptions).
BUILTIN_KINDS = {"zigzag": "one zigzag actuator", "cross": "one cross-pattern actuator"}


def kind_descriptions() -> dict[str, str]:
    """name -> description of every registered pattern kind, in registration order.

    A kind is registered or removed only through :mod:`embroact.patterns.kinds`; until that
    module is loaded its registry would hold :data:`BUILTIN_KINDS`, so those are the answer
    and the registry stays unloaded (``embroact --help``). Once it is loaded (a command, a
    plug-in registering a kind), its registry is read.

    Returns
    -------
    dict of str to str
        The description is ``""`` where a kind gives none.

    Examples
    --------
    >>> import embroact.patterns.kinds
    >>> kind_descriptions() == {k.name: k.description for k in embroact.patterns.kinds.PATTERN_KINDS}
    True
    """
    registry = sys.modules.get(f"{__package__}.kinds")
    if registry is None:
        return dict(BUILTIN_KINDS)
    return {k.name: k.description for k in registry.PATTERN_KINDS}
