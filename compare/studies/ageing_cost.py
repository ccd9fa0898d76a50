"""The ageing model's cost: the reference case (900 s at 1 kHz) and a work-precision table.

    .venv/bin/python -m compare.studies.ageing_cost

Reference case: AgeingParams() (model I's block, springs and renewals; F_N = 20 N, A = 0.12, B = 0.04,
D_c = 0.1 mm, ageing law), 900 s at 1 kHz, seed 0, default rtol 1e-6: wall and CPU time, best of 3, with the load.
Work-precision: 100 s of the same case at rtol 1e-4 ... 1e-7 against rtol 1e-9 (same seed, same renewals): the
largest error in zeta over the samples relative to zeta's rms, and the band-averaged C_x error per log band
(0.5-2000 rad/s). Writes study-results/ageing_cost.md.
"""
from __future__ import annotations

import os
import time
from pathlib import Path

import numpy as np

from compare.analysis.spectra import band_average, displacement_spectrum
from reduced_models import ageing as ag
from reduced_models import spring_block as sb
from compare.studies.study_page import write_page

OUT = Path("study-results") / "ageing_cost.md"


def main():
    p = ag.AgeingParams()
    ag.simulate(p, 1.0, 1e-3, seed=0)  # compile / load the cache
    L = ["# Ageing model: cost and work-precision", "",
         "Produced by `python -m compare.studies.ageing_cost`. Reference case: `AgeingParams()`, 900 s at 1 kHz, seed 0.",
         ""]
    rows = []
    for name, params, mod in (("ageing (default rtol 1e-6)", p, ag), ("ageing, slip law", ag.AgeingParams(law="slip"), ag),
                              ("ageing, renewal_state 10 ms", ag.AgeingParams(renewal_state=1e-2), ag),
                              ("model I (exact propagation), for scale", sb.SpringBlockParams(), sb)):
        best_w, best_c = np.inf, np.inf
        for _ in range(3):
            w0, c0, l0 = time.perf_counter(), time.process_time(), os.getloadavg()[0]
            tr = mod.simulate(params, 900.0, 1e-3, seed=0)
            best_w, best_c = min(best_w, time.perf_counter() - w0), min(best_c, time.process_time() - c0)
        rows.append(f"| {name} | {best_w:.2f} | {best_c:.2f} | {tr.metadata.get('steps_accepted', '-')} | "
                    f"{tr.metadata['n_renewals']} | {l0:.1f} |")
    L += ["| case | wall s (best of 3) | CPU s (best of 3) | steps | renewals | load (1-min) |", "|---|---|---|---|---|---|",
          *rows, ""]
    ref = ag.simulate(p, 100.0, 1e-3, seed=0, rtol=1e-9)
    zr = ref.x - p.v * ref.t
    edges = np.logspace(np.log10(0.5), np.log10(2000), 8)
    sr = displacement_spectrum(ref.t, ref.x)
    Cr = band_average(sr, edges)
    L += ["Work-precision, 100 s, against rtol 1e-9 (same renewals). Band edges (rad/s): " +
          ", ".join(f"{e:.3g}" for e in edges) + ".", "",
          "| rtol | max abs err zeta / zeta_rms | max band |C_x / C_x,ref - 1| | band errors | wall s | steps |",
          "|---|---|---|---|---|---|"]
    for rtol in (1e-4, 1e-5, 1e-6, 1e-7):
        w0 = time.perf_counter()
        tr = ag.simulate(p, 100.0, 1e-3, seed=0, rtol=rtol)
        el = time.perf_counter() - w0
        z = tr.x - p.v * tr.t
        e = band_average(displacement_spectrum(tr.t, tr.x), edges) / Cr - 1
        L.append(f"| {rtol:.0e} | {np.abs(z - zr).max() / zr.std():.1e} | {np.abs(e).max():.1e} | "
                 + " ".join(f"{x:+.0e}" for x in e) + f" | {el:.2f} | {tr.metadata['steps_accepted']} |")
    write_page(OUT, L)


if __name__ == "__main__":
    main()
