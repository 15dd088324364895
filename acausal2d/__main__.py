"""``python -m acausal2d`` runs the command line (same as ``acausal2d``)."""
import sys

from .cli import main

sys.exit(main())
