"""Every shipped scenario slides steadily, balances forces and energy; the drives compared (section 2)."""
import numpy as np
import pytest

import engine_sim
from compare.analysis.fits import fit_power_law
from compare.analysis.spectra import band_average, displacement_spectrum, force_series_spectrum
from engine_sim import load_scenario, shipped_scenarios


@pytest.mark.slow  # every shipped scene, 6-30 s each
@pytest.mark.parametrize("name", sorted(shipped_scenarios()))
def test_shipped_scenario_slides_steadily(name):
    sc = load_scenario(shipped_scenarios()[name]).with_run(duration=6.0, warmup=1.0)
    if sc.law_part.reduced_model == "spring_slider":
        pytest.skip("sticks and slips by design (k < k_c): tests/engine_sim/test_rate_state_law.py")
    tr = engine_sim.run(sc)
    assert np.all(np.isfinite(tr.x)) and np.all(np.isfinite(tr.F_t))
    v_all = (tr.x[-1] - tr.x[0]) / tr.t[-1]
    assert 0.5e-3 <= v_all <= 10e-3
    idx = np.array_split(np.arange(len(tr.t) // 2, len(tr.t)), 4)
    for q in idx:
        assert (tr.x[q[-1]] - tr.x[q[0]]) / (tr.t[q[-1]] - tr.t[q[0]]) == pytest.approx(v_all, rel=0.05)
    # friction (Coulomb + viscous) balances the drive within 2 % (measured within 1e-5)
    assert np.mean(tr.F_t + tr.F_drag) == pytest.approx(np.mean(tr.F_drive), rel=0.02)
    # energy balance within 2 % (measured within 5e-5 without particles, 1.5-1.8 % with them; recycled grains
    # carry their energy change in work_recycle)
    resid = tr.work_drive[-1] + tr.work_recycle[-1] - tr.dissipated[-1] - tr.mech_energy[-1]
    assert resid / tr.work_drive[-1] == pytest.approx(0, abs=0.02)
    # overlap with the track: the collision slop (1e-7 m) on flat tracks; on the rough profile impacts on
    # flanks reach 1.2 um, pads riding over grains 5.2 um (measured); bound 8 um. Grains: 4.1 um, bound 8 um.
    assert tr.penetration.max() < (8e-6 if sc.wear.count else 3e-6) and tr.particle_penetration.max() < 8e-6
    if sc.wear.count:
        # grains add friction: the block slides slower than the bare law (measured 3.8-3.9 vs 5.0 mm/s)
        assert v_all < sc.steady_velocity and tr.metadata["wear"]["left_interface"] == 0
    else:
        # the speed follows the friction law within 10 %; the patch noise lowers it (tilted_plane: 9 %):
        # pads dwell longer on high-friction patches, so the time-averaged mu exceeds mu0 (0.618 vs 0.6)
        assert v_all == pytest.approx(sc.steady_velocity, rel=0.10)


@pytest.mark.slow  # every shipped scene, 6-30 s each
def test_constant_force_and_constant_velocity_drives():
    # Same seed and substrate, 30 s each. Measured: C_x agrees within 1.5 % per band over 2-1000 rad/s
    # (the soft drive spring's corner, k_drive / (N c) = 0.33 rad/s, lies below the band), while the
    # friction-force spectrum under constant velocity exceeds the constant-force one by 230-4600x below
    # 10 rad/s: at constant force the friction is pinned to the drive, C_F = M^2 omega^4 C_x (eq. 3).
    out = {}
    for name in ("pads_friction_patches", "constant_velocity"):
        sc = load_scenario(shipped_scenarios()[name]).with_run(duration=30.0)
        tr = engine_sim.run(sc, seed=5)
        out[name] = (displacement_spectrum(tr.t, tr.x, nperseg=2**13),
                     force_series_spectrum(tr.t, tr.F_t + tr.F_drag, nperseg=2**13))
    edges = np.logspace(np.log10(2.0), 3.0, 9)
    (xf, Ff), (xv, Fv) = out["pads_friction_patches"], out["constant_velocity"]
    rx = band_average(xv, edges) / band_average(xf, edges)
    assert np.all(np.abs(rx - 1) < 0.10), rx
    rF = band_average(Fv, [2.0, 10.0]) / band_average(Ff, [2.0, 10.0])
    assert rF[0] > 10.0
    assert fit_power_law(xv, band=(15.0, 150.0)).gamma == pytest.approx(4.0, abs=0.3)
