"""compare_table on hand-made result tables with known answers."""

import numpy as np
import pandas as pd
import pytest

from workbench.compare import add_derived_columns, compare_table

L = 0.5


def arc(kappa, n=33):
    s = np.linspace(0.0, L, n)
    r, z = (1 - np.cos(kappa * s)) / kappa, np.sin(kappa * s) / kappa
    return s, np.column_stack([r, np.zeros(n), z])


def rot_y(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def row(case, model, s, p, R, **extra):
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p[-1]
    r = {
        "case_id": case, "model": model, "status": "ok", "error": "", "wall_time": 0.1,
        "p.load.bend_angle": 2.0 * L, "p.robot.q": 2.0, "p.robot.EI": 4.0, "robot_length": L,
        "tip_x": p[-1, 0], "tip_y": p[-1, 1], "tip_z": p[-1, 2], "tip_frame": T.ravel().tolist(),
        "length_change": 0.0, "tip_twist": 0.0, "stations": s.tolist(), "positions": p.ravel().tolist(),
        "tendon_tensions": [5.0, 0.0],
    }
    r.update(extra)
    return r


@pytest.fixture
def table():
    k = 2.0
    s, p = arc(k)
    R_cc = rot_y(k * L)
    shift = np.array([0.003, 0.0, -0.004])
    alpha = np.radians(7.0)
    rows = [
        row("a", "cc", s, p, R_cc, length_change=-0.01),
        # shifted arc: tip and shape errors 5 mm everywhere, same orientation and curvature
        row("a", "ancf", s, p + shift, R_cc, length_change=-0.004, **{"x.tendon_stretch_mean": 0.002}),
        # same arc rotated rigidly about the base y axis, reported at fewer stations
        row("a", "spring_link", s[::8], (p @ rot_y(alpha).T)[::8], rot_y(alpha) @ R_cc),
        # a failed run never appears in the metrics
        {"case_id": "b", "model": "ancf", "status": "failed", "error": "boom", "robot_length": L},
        row("b", "cc", s, p, R_cc),
    ]
    return pd.DataFrame(rows)


def test_known_errors(table):
    m = compare_table(table)
    assert set(zip(m.reference, m.model)) == {("cc", "ancf"), ("cc", "spring_link"), ("ancf", "spring_link")}
    a = m[(m.reference == "cc") & (m.model == "ancf")].iloc[0]
    assert a.tip_error == pytest.approx(0.005)
    assert a.tip_error_pct == pytest.approx(1.0)
    assert a.orientation_error_deg == pytest.approx(0.0, abs=1e-6)
    assert a.shape_error_max == pytest.approx(0.005)
    assert a.shape_error_rms == pytest.approx(0.005)
    assert a.kappa_ref_0 == pytest.approx(2.0, rel=1e-9)
    assert a.kappa_error_0 == pytest.approx(0.0, abs=1e-8)
    b = m[(m.reference == "cc") & (m.model == "spring_link")].iloc[0]
    assert b.orientation_error_deg == pytest.approx(7.0)
    assert b.tip_error == pytest.approx(2 * np.sin(np.radians(3.5)) * np.linalg.norm(arc(2.0)[1][-1]))
    assert b.kappa_0 == pytest.approx(2.0, rel=1e-9)  # fewer stations, same arc
    # rigid rotation: backbone points move by 2 |p| sin(alpha/2); the largest at the tip
    assert b.shape_error_max == pytest.approx(b.tip_error, rel=1e-12)


def test_compression_split_columns(table):
    m = compare_table(table)
    a = m[(m.reference == "cc") & (m.model == "ancf")].iloc[0]
    assert a.compression_virtual == pytest.approx(-0.01)
    assert a.compression_backbone == pytest.approx(-0.004)
    assert a.compression_tendon_stretch == pytest.approx(-0.002)
    assert a.compression_shape == pytest.approx(-0.004)
    # no stretch information for spring_link and no CC reference for the physics pair
    assert m[m.model == "spring_link"]["compression_shape"].isna().all()


def test_derived_columns_and_expression(table):
    m = compare_table(table, derived={"gamma2": "`p.robot.q` * robot_length**3 / `p.robot.EI`"})
    assert m["kappaL"].iloc[0] == pytest.approx(1.0)
    assert m["gamma2"].iloc[0] == pytest.approx(2.0 * L**3 / 4.0)
    assert "p.load.bend_angle" in m.columns
    with pytest.raises(ValueError, match="gamma3"):
        add_derived_columns(table, {"gamma3": "`p.nope` * 2"})
    # built-in gamma from *.q and *.EI columns
    assert add_derived_columns(table)["gamma"].iloc[0] == pytest.approx(2.0 * L**3 / 4.0)


def test_reference_only_and_missing_reference(table):
    m = compare_table(table, pairs="baseline")
    assert set(m.reference) == {"cc"}
    only_physics = compare_table(table[table.model != "cc"])
    assert set(zip(only_physics.reference, only_physics.model)) == {("ancf", "spring_link")}
    single = compare_table(table[table.model == "cc"])
    assert single.empty and "case_id" in single.columns


def test_bad_tables_raise(table):
    with pytest.raises(ValueError, match="status"):
        compare_table(table.drop(columns="status"))
    bad = table.copy()
    bad.at[1, "positions"] = [0.0, 1.0]
    with pytest.raises(ValueError, match="3 m values"):
        compare_table(bad)
    with pytest.raises(ValueError, match="pairs"):
        compare_table(table, pairs="some")


def test_section_ends_column_gives_per_section_curvature(table):
    t = table.copy()
    t["section_ends"] = [[0.2, L]] * len(t)
    m = compare_table(t)
    a = m[(m.reference == "cc") & (m.model == "ancf")].iloc[0]
    assert a.kappa_ref_0 == pytest.approx(2.0, rel=1e-9)
    assert a.kappa_ref_1 == pytest.approx(2.0, rel=1e-9)
    m2 = compare_table(table, section_ends=[0.1, 0.3, L])
    assert {"kappa_2", "kappa_error_2"} <= set(m2.columns)
