"""The vibration sweep's answer from its task files: the rows, figure and answer of :mod:`compare.report.vibration`
(each shaken cell against its unshaken twin of the same seed, the line at omega_v removed from x(t) before the
spectrum), written as markdown and a PNG.

    for n in force_1000hz force_20hz force_2000hz velocity_1000hz velocity_20hz velocity_2000hz; do
        frictionnoise sweep scenarios/sweeps/vibration_sweep_$n.toml -o DIR/$n --serial; done
    python -m compare.studies.vibration_sweep --force DIR/force_* --velocity DIR/velocity_* \\
        [--png study-results/vibration_sweep.png]

``--gamma`` prints gamma alone per cell, each fit with its own 95 % interval: for a run of the sweep files with one
seed (their grid's ``seed = [0]``), which re-measures the exponents without the hours of three seeds.

The twins (amplitude 0) are in the 1000 Hz files; each drive's folders are read together.
"""
import argparse
from pathlib import Path

from compare.report.vibration import VibratedScene, answer, cells, load_tasks


def markdown(rows: list, sc: VibratedScene) -> str:
    """The rows as a markdown table (95 % Student-t intervals over the paired seeds)."""
    out = ["| f (Hz) | drive | A (um) | xi | A / (mu N/k0) | A / A_onset | C_x / twin | (Coulomb / twin)^2 | gamma | "
           "Coulomb / twin | rigid | linear pads | compliant | speed / twin | drive force / twin | pred. (rigid, compliant) | line (um) | seeds |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cf = r["constant_force"]
        pred = (f"speed {r['speed_rigid']:.3f}, {r['speed_compliant']:.3f}" if cf else
                f"force {r['drive_rigid']:.3f}, {r['drive_compliant']:.3f}; speed {r['speed_rigid']:.3f}, "
                f"{r['speed_compliant']:.3f}")
        out.append(
            f"| {r['frequency']:g} | {'force' if cf else 'velocity'} | {r['amplitude'] * 1e6:.3g} | {r['xi']:.3g} | "
            f"{r['amplitude'] / sc.deflection:.2g} | {r['amplitude'] / r['A_onset']:.2g} | "
            f"{r['C_ratio']:.3g} +- {r['C_ratio_ci']:.2g} | "
            f"{r['coulomb_sq']:.3g} +- {r['coulomb_sq_ci']:.2g} | "
            f"{r['gamma']:.2f} +- {r['gamma_ci']:.2f} (twin {r['gamma_twin']:.2f}) | "
            f"{r['coulomb']:.3f} +- {r['coulomb_ci']:.3f} | {r['coulomb_rigid']:.3f} | {r['coulomb_pads']:.3f} | "
            f"{r['coulomb_compliant']:.3f} | "
            f"{r['speed']:.4f} +- {r['speed_ci']:.4f} | {r['drive']:.4f} +- {r['drive_ci']:.4f} | {pred} | "
            f"{r['line'] * 1e6:.3g} | {r['seeds']} |")
    return "\n".join(out)


def gamma_markdown(groups: dict) -> str:
    """gamma of each shaken cell and of its twin as their fits give them: the record model's fit of each task's
    record with its own 95 % profile interval (the mean of the seeds' half-widths when a cell holds several), and
    the rise against the twin of the same seed, its mean over the seeds with a Student-t 95 % interval (blank for one
    seed). ``groups``: {drive name: rows}, the drive named by the folders the rows came from (one seed's twins cannot
    show whether the drive force varied)."""
    out = ["| f (Hz) | drive | A (um) | xi | A / A_onset | gamma (its 95 % half-width) | twin's gamma | "
           "rise against the twin (paired) | seeds |",
           "|---|---|---|---|---|---|---|---|---|"]
    for drive, rows in groups.items():
        for r in rows:
            g = r["gamma_rise"] if abs(r["gamma_rise"]) >= 0.005 else 0.0  # no "-0.00" for a rise that rounds to 0
            rise = f"{g:+.2f} +- {r['gamma_rise_ci']:.2f}" if r["gamma_rise_ci"] == r["gamma_rise_ci"] else f"{g:+.2f}"
            out.append(
                f"| {r['frequency']:g} | {drive} | {r['amplitude'] * 1e6:.3g} | {r['xi']:.3g} | "
                f"{r['amplitude'] / r['A_onset']:.2g} | {r['gamma']:.2f} +- {r['gamma_fit_err']:.2f} | "
                f"{r['gamma_twin']:.2f} | {rise} | {r['seeds']} |")
    return "\n".join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--force", nargs="+", default=[], help="task folders of the constant force drive")
    ap.add_argument("--velocity", nargs="+", default=[], help="task folders of the constant velocity drive")
    ap.add_argument("--png", type=Path, help="write the figure here")
    ap.add_argument("--gamma", action="store_true",
                    help="only gamma per cell with each fit's own interval (a run with one seed per cell)")
    a = ap.parse_args(argv)
    sc = VibratedScene()
    rows_force, rows_velocity = cells(load_tasks(a.force), sc), cells(load_tasks(a.velocity), sc)
    if a.gamma:
        print(gamma_markdown({"force": rows_force, "velocity": rows_velocity}))
        return
    rows = rows_force + rows_velocity
    print(markdown(rows, sc))
    print()
    print(answer(rows, sc).replace("&plusmn;", "+-"))
    if a.png is not None:
        from compare.report import plots

        plots.save_figure(plots.vibration_figure(rows), a.png)


if __name__ == "__main__":
    main()
