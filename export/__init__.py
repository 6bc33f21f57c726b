"""embroact.export: everything that leaves the program.

Machine files (:mod:`~embroact.export.machine.formats`), stitch preview SVG
(:mod:`~embroact.export.pictures.stitches`), bend charts, side views, 3D meshes, reports and
the ``embroact`` command line (:mod:`~embroact.export.cli.main`). This package's
``__init__`` imports nothing, so that ``embroact --help`` stays fast; import the
modules you need.
"""

__version__ = "0.1.0"
"""The package version, written only here: pyproject.toml reads it (``[tool.setuptools.dynamic]``), the
package metadata and ``embroact.__version__`` carry it, ``embroact --version`` and report.json's
``generator`` show it."""
