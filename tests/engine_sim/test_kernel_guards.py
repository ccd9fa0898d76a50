"""numba kernels write into their callers' buffers without bounds checks (unless NUMBA_BOUNDSCHECK=1): each call
site checks the sizes first and refuses, instead of writing past a buffer (a resume once corrupted the heap)."""
import types

import numpy as np
import pytest


def _short_np(real, fn):
    """A stand-in for a module's `np` whose `fn` allocates one element less."""
    shim = types.SimpleNamespace(**{k: getattr(real, k) for k in dir(real) if not k.startswith("__")})
    setattr(shim, fn, lambda n, *a, **k: getattr(real, fn)(n - 1 if isinstance(n, int) else n, *a, **k))
    return shim


def test_asperity_force_refuses_short_buffers(monkeypatch):
    from reduced_models import asperity_force as m

    monkeypatch.setattr(m, "np", _short_np(np, "empty"))
    with pytest.raises(RuntimeError, match="asperity_force._run: buffers of"):
        m.simulate(m.AsperityForceParams(), 0.1, seed=0)


def test_wear_particle_refuses_short_buffers(monkeypatch):
    from reduced_models import wear_particle as m

    monkeypatch.setattr(m, "np", _short_np(np, "zeros"))
    with pytest.raises(RuntimeError, match="wear_particle_kernel.run: buffer sizes"):
        m.simulate(m.WearParticleParams(n_particles=10), 0.1, 1e-3, seed=0)


def test_resume_refuses_recorder_arrays_of_another_shape():
    import pickle

    from engine_sim import load_scenario, shipped_scenarios
    from engine_sim.checkpoint import CheckpointError, restore
    from engine_sim.scene import Scene

    scene = Scene(load_scenario(shipped_scenarios()["pads_friction_patches"]), 0)
    arrays = {"t": np.zeros(5), "out": np.zeros((5, 3)), "pad_force": np.zeros((5, 30)),
              "n_contact": np.zeros(5, np.int32), "p_state": np.zeros((5, 0), np.int8), "p_force": np.zeros((5, 0)),
              "recycle": np.zeros(5)}
    with pytest.raises(CheckpointError, match="recorder array 'out' of shape"):
        restore(pickle.dumps(scene), {"k": 5, "x0": 0.0, "part": np.zeros((0, 6)), "arrays": arrays}, 10)
