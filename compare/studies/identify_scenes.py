"""The shipped scenes identified from their traces: `identify` on each scene's displacement, beside the model I
parameters the scene was built with (compare.analysis.extract).

    python -m compare.studies.identify_scenes [--duration S] [SCENE ...]

Default: pads_friction_patches for its scenario's duration. Prints the ranking and, for model I's family, the level
L = alpha^2 v f_kin^2 / (12 pi N a c^2) (eq. A11) and a from the extracted parameters against the fitted ones.
"""
import argparse

import numpy as np

import frictionnoise as fn
from compare.analysis.extract import model_I_parameters, spring_block_params
from compare.analysis.families import FAMILIES


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("scenes", nargs="*", default=["pads_friction_patches"])
    ap.add_argument("--duration", type=float, default=None)
    a = ap.parse_args(argv)
    for name in a.scenes:
        tr = fn.run_scene(name, duration=a.duration)
        dt = float(np.median(np.diff(tr.t)))
        v = float((tr.x[-1] - tr.x[0]) / (tr.t[-1] - tr.t[0]))
        print(f"{name}: {tr.t[-1] - tr.t[0]:.1f} s at {1 / dt:.0f} Hz, v = {v:.4g} m/s")
        ranking = fn.identify(tr.x, dt, v)
        for m in ranking:
            shown = {k: (p if isinstance(p, str) else f"{p[0]:.3g} +- {p[1]:.2g}") for k, p in m.parameters.items()}
            print(f"  {m.model:13s} {m.verdict:17s} p = {m.p_value:.2g}  {shown}")
        try:
            built, _ = FAMILIES["model_I"].from_model(spring_block_params(model_I_parameters(tr)))
        except (ValueError, KeyError) as e:
            print(f"  (no model I parameters extracted: {e})")
            continue
        fit = next(m for m in ranking if m.model == "model_I")
        for k in ("L", "a", "omega_c"):
            got = fit.parameters[k]
            within = "" if isinstance(got, str) else (" within" if abs(got[0] - built[k]) <= got[1] else " outside")
            print(f"  model I {k}: built {built[k]:.3g}, fitted {got if isinstance(got, str) else f'{got[0]:.3g} +- {got[1]:.2g}'}"
                  f"{within}")


if __name__ == "__main__":
    main()
