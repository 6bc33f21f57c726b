"""``python -m embroact`` runs the command line (the same as ``embroact``)."""
import sys

from .export.cli.main import main

sys.exit(main())
