"""Geometric design rules on stitch plans and sewing layouts (see :mod:`.layout`)."""
from .layout import *  # noqa: F401,F403
from .layout import __all__, _PathIndex  # noqa: F401
