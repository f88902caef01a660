"""``python -m pointmass`` runs the command line (see ``pointmass.cli``)."""

import sys

from .cli import main

sys.exit(main())
