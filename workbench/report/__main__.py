"""``python -m workbench.report data/<study>``."""

import sys

from .build import main

sys.exit(main())
