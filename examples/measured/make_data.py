"""Make the example's measured-style data set: ``measured.csv`` and ``truth.toml`` (one command, seeded).

    cd <repository> && python examples/measured/make_data.py

The "robot in the lab" is the Rao et al. 2021 two-section NiTi robot (preset ``rao_2021``) mounted
with its base horizontal, so that it sags under its own weight (about 7 % of its length unloaded),
with a stiffer backbone than the preset says (E + 10 %, both sections).  Its tip positions come from
the Cosserat rod (model ``cosserat``, continuous tendon routing) and are then "measured" the way a
lab would see them:

- in a tracker frame: ``p_tracker = R @ p_base + t`` with a rotation of 15 deg about a tilted axis
  and a translation of a few cm (:data:`TRUTH`);
- with Gaussian noise (0.2 mm per coordinate), written in mm with 3 decimals;
- with tensions read by load cells in counts (1 count = 2 mN) that read high by a constant: the
  tension in tendon ``i`` is ``count_i * 0.002 N + command_zero[i]`` (the calibration's
  ``command_zero``: what is added to each command to get the tension the robot feels).

Each row pulls one to three randomly chosen tendons with 0.2 .. 4 N; the others are slack (0 N, so
their cells read ``-command_zero[i]`` = 0.02 .. 0.06 N: never below zero, which the reader would
refuse).  Slack tendons are what makes the offsets identifiable: an offset acts only while its
tendon pulls (the calibration clips command plus offset at 0 N: a tendon cannot push), so it does
not act as a constant bend that the registration could absorb.  What stays invisible: an equal
tension added to all three (equally spaced) tendons of a section bends nothing, so a section's
offsets all set too *high* by the same amount change no tip (too low, they do: slack tendons stay
at 0 N while the pulled ones lose tension); the calibration flags that.  Everything is drawn from
one seeded generator up front, so any subset of rows can be regenerated (:func:`generate` with
``rows``); ``tests/measure/test_measure_example.py`` checks the committed file that way.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
if str(HERE.parents[1]) not in sys.path:
    sys.path.insert(0, str(HERE.parents[1]))  # run from a checkout without installing

SEED = 20261203
N_ROWS = 300
#: the settings the Cosserat rod is solved with (the same as ``measured.toml``'s ``[solver]``)
SOLVER = {"n_elements": 32}
COUNT = 0.002  # N per load-cell count
COMMAND_COLUMNS = [f"cell{i}" for i in range(1, 7)]
TIP_COLUMNS = ["tip_x", "tip_y", "tip_z"]

#: the generating values (SI unless the name says otherwise)
TRUTH = {
    "youngs_modulus": 1.1 * 54e9,  # Pa, both sections (preset rao_2021: 54 GPa, material niti)
    "command_zero": [-0.05, -0.03, -0.04, -0.06, -0.02, -0.044],  # N, per tendon (multiples of one count)
    "translation": [0.035, -0.020, 0.050],  # m, base origin in the tracker frame
    "rotation_axis": [1.0, 2.0, 2.0],  # tilted axis (normalised below)
    "rotation_angle_deg": 15.0,
    "noise_mm": 0.2,  # standard deviation per coordinate
}


def rotation_vector() -> np.ndarray:
    """The registration's rotation vector [rad] (axis times angle) of :data:`TRUTH`."""
    axis = np.asarray(TRUTH["rotation_axis"], dtype=float)
    return axis / np.linalg.norm(axis) * np.deg2rad(TRUTH["rotation_angle_deg"])


def rotation_matrix(rotvec: np.ndarray) -> np.ndarray:
    """Rodrigues' formula: the rotation matrix of a rotation vector [rad]."""
    angle = float(np.linalg.norm(rotvec))
    k = rotvec / angle
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(angle) * K + (1.0 - np.cos(angle)) * K @ K


def robot_params(youngs_modulus: float) -> dict:
    """The ``[robot]`` table of the robot in the lab (preset rao_2021, base horizontal, gravity on)."""
    return {"preset": "rao_2021", "base_orientation": "horizontal", "gravity": [0.0, 0.0, -9.81],
            "sections": [{"youngs_modulus": youngs_modulus}, {"youngs_modulus": youngs_modulus}]}


def draw(n_rows: int = N_ROWS, seed: int = SEED) -> tuple[np.ndarray, np.ndarray]:
    """Load-cell counts ``(n, 6)`` (int) and position noise ``(n, 3)`` [mm] of every row, seeded."""
    rng = np.random.default_rng(seed)
    zero = np.asarray(TRUTH["command_zero"])
    tension = np.zeros((n_rows, 6))
    for r in range(n_rows):
        loaded = rng.choice(6, size=rng.integers(1, 4), replace=False)
        tension[r, loaded] = rng.uniform(0.2, 4.0, loaded.size)
    counts = np.rint((tension - zero) / COUNT).astype(int)
    noise = rng.normal(0.0, TRUTH["noise_mm"], (n_rows, 3))
    return counts, noise


def tensions(counts: np.ndarray) -> np.ndarray:
    """The tension [N] the robot feels for load-cell counts: ``count * COUNT + command_zero`` (slack: exactly 0)."""
    t = counts * COUNT + np.asarray(TRUTH["command_zero"])
    return np.where(np.abs(t) < 1e-9, 0.0, t)


def generate(rows=None, n_rows: int = N_ROWS, seed: int = SEED) -> dict[str, np.ndarray]:
    """The data rows ``rows`` (default: all): counts, measured tip [mm] (noisy, tracker frame), base tip [m].

    Raises ``RuntimeError`` naming the row if the Cosserat rod does not converge.
    """
    from workbench.models import get_model
    from workbench.robot import LoadCase, TendonActuation
    from workbench.study.build import build_options, build_robot

    counts, noise = draw(n_rows, seed)
    idx = np.arange(n_rows) if rows is None else np.asarray(rows, dtype=int)
    robot = build_robot(robot_params(TRUTH["youngs_modulus"]))
    options = build_options(SOLVER)
    model = get_model("cosserat")
    base = np.empty((idx.size, 3))
    for k, r in enumerate(idx):
        res = model(robot, LoadCase(actuation=TendonActuation("tension", tuple(tensions(counts[r])))), options)
        if not res.solver.converged:
            raise RuntimeError(f"row {r}: the Cosserat rod did not converge")
        base[k] = res.tip_position
    R = rotation_matrix(rotation_vector())
    tracker_mm = (base @ R.T + np.asarray(TRUTH["translation"])) * 1e3 + noise[idx]
    return {"rows": idx, "counts": counts[idx], "tip_mm": np.round(tracker_mm, 3), "tip_base": base}


def write_csv(path: Path, data: dict[str, np.ndarray]) -> None:
    """``measured.csv``: one header line, counts as integers, positions in mm with 3 decimals."""
    lines = [",".join(COMMAND_COLUMNS + TIP_COLUMNS)]
    for c, p in zip(data["counts"], data["tip_mm"]):
        lines.append(",".join([str(int(v)) for v in c] + [f"{v:.3f}" for v in p]))
    path.write_text("\n".join(lines) + "\n")


def write_truth(path: Path, sag: float, length: float) -> None:
    """``truth.toml``: every generating value with its unit, in the calibration's parameter names."""
    rv = rotation_vector()
    z = TRUTH["command_zero"]
    lines = [
        "# The values examples/measured/make_data.py generated measured.csv with (do not edit: regenerate).",
        f"seed = {SEED}",
        f"rows = {N_ROWS}",
        'model = "cosserat"          # continuous tendon routing',
        f"solver = {{ n_elements = {SOLVER['n_elements']} }}",
        "",
        "[values]                    # calibration parameter name -> value [unit]",
        f'"robot.sections[0].youngs_modulus" = {{ value = {TRUTH["youngs_modulus"]:.6g}, unit = "Pa" }}',
        f'"robot.sections[1].youngs_modulus" = {{ value = {TRUTH["youngs_modulus"]:.6g}, unit = "Pa" }}',
        *[f'"command_zero[{i}]" = {{ value = {v}, unit = "N" }}' for i, v in enumerate(z)],
        *[f'"registration.translation[{j}]" = {{ value = {v}, unit = "m" }}'
          for j, v in enumerate(TRUTH["translation"])],
        *[f'"registration.rotation[{j}]" = {{ value = {v:.12g}, unit = "rad" }}' for j, v in enumerate(rv)],
        "",
        "[lab]",
        f"rotation_axis = {TRUTH['rotation_axis']}   # tilted axis (not normalised)",
        f"rotation_angle = {{ value = {TRUTH['rotation_angle_deg']}, unit = \"deg\" }}",
        f"noise = {{ value = {TRUTH['noise_mm']}, unit = \"mm\" }}   # Gaussian, per coordinate",
        f"count = {{ value = {COUNT}, unit = \"N\" }}          # one load-cell count",
        f"unloaded_sag = {{ value = {sag:.6g}, unit = \"m\", percent_of_length = {100 * sag / length:.3g} }}",
    ]
    path.write_text("\n".join(lines) + "\n")


def main() -> None:
    """Write ``measured.csv`` and ``truth.toml`` next to this script."""
    from workbench.models import get_model
    from workbench.robot import LoadCase
    from workbench.study.build import build_options, build_robot

    data = generate()
    write_csv(HERE / "measured.csv", data)
    robot = build_robot(robot_params(TRUTH["youngs_modulus"]))
    straight = get_model("cosserat")(robot, LoadCase(), build_options(SOLVER)).tip_position
    sag = float(np.hypot(straight[0], straight[1]))
    write_truth(HERE / "truth.toml", sag, robot.length)
    print(f"wrote {HERE / 'measured.csv'} ({N_ROWS} rows) and truth.toml; unloaded sag {sag * 1e3:.2f} mm "
          f"({100 * sag / robot.length:.2f} % of L)")


if __name__ == "__main__":
    main()
