"""``python -m pliant.cad``: see :mod:`pliant.cad`."""

import sys

from .step_mesh import main

sys.exit(main())
