"""``python -m workbench.report data/<study>``."""

import sys

from .command import main

sys.exit(main())
