"""The sensitivity error-bar figure's row matching (``workbench.report.errorbars._comparable``)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from workbench.report.errorbars import _comparable


def test_comparable_rows_with_missing_cells():
    # series-parallel tables hold NaN in the motion columns a row does not use (e.g. p.pose.pivot);
    # pandas 3's astype(str) kept them as float and the signature join raised TypeError
    g = pd.DataFrame({
        "p.geometry.rod_diameter": [0.004, 0.006, 0.006, 0.008],
        "p.pose.axis": ["x", "x", "rz", "x"],
        "p.pose.pivot": [np.nan, np.nan, np.nan, np.nan],
    })
    out = _comparable(g, "p.geometry.rod_diameter", ["p.pose.axis", "p.pose.pivot"])
    assert list(out.index) == [0, 1, 3]  # the rz row has no counterpart at 4 / 8 mm
