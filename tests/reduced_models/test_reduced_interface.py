"""The uniform reduced-model interface that every registered model provides: simulate(params, duration,
dt_out=..., seed=...), RESPONSE, fit_band, so that callers need not branch on the model."""
import numpy as np
import pytest

from reduced_models import MODELS, PARAMS, asperity_force

DEFAULTS = {"model_I": {}, "model_Ib": {}, "model_II": {"n_particles": 20}, "model_III": {}, "model_ageing": {}, "model_Iv": {}}


@pytest.mark.parametrize("key", sorted(MODELS))
def test_every_model_takes_the_same_call(key):
    mod, p = MODELS[key], PARAMS[key](**DEFAULTS[key])
    dt = 0.002 if key != "model_III" else 4 * p.dt
    tr = mod.simulate(p, 100 * dt, dt_out=dt, seed=3)
    assert len(tr.t) == 100 and tr.t[1] - tr.t[0] == pytest.approx(dt, rel=1e-12)
    again = mod.simulate(p, 100 * dt, dt_out=dt, seed=3)
    assert np.array_equal(tr.x, again.x)  # seeded, bit for bit
    assert mod.RESPONSE in ("viscous", "inertial")
    band = mod.fit_band(p, dt)
    assert band is None or 0 < band[0] < band[1]


def test_model_III_dt_out_samples_its_grid():
    # dt_out = 4 grid steps: every 4th position of the grid run, and the force averaged over the 4 steps
    # (same seed, same grid draws).
    p = asperity_force.AsperityForceParams.reference()
    fine = asperity_force.simulate(p, 400 * p.dt, seed=1)
    coarse = asperity_force.simulate(p, 400 * p.dt, dt_out=4 * p.dt, seed=1)
    assert np.array_equal(coarse.x, fine.x[::4])
    np.testing.assert_allclose(coarse.force, fine.force.reshape(-1, 4).mean(axis=1), rtol=1e-14)
    with pytest.raises(ValueError, match="whole number of grid steps"):
        asperity_force.simulate(p, 400 * p.dt, dt_out=2.5 * p.dt, seed=1)
