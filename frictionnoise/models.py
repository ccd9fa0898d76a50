"""The reduced models, called alike: :func:`simulate` and :func:`theory_spectrum` for any model's parameters.

A model's parameter object says which model it is (:data:`reduced_models.PARAMS`), so a caller writes
``fn.simulate(fn.SpringBlockParams.reference(), 60.0, seed=0)`` and never branches on the model's name.
"""
from __future__ import annotations

from types import ModuleType

import numpy as np

from reduced_models import MODELS, PARAMS

__all__ = ["model", "simulate", "theory_spectrum"]


def model(which) -> ModuleType:
    """The module of a reduced model.

    Parameters
    ----------
    which : str or parameter object
        A key of :data:`reduced_models.MODELS` (``"model_I"``, ``"model_Ib"``, ``"model_II"``,
        ``"model_III"``) or an instance of a model's parameter class (e.g.
        :class:`~reduced_models.SpringBlockParams`).

    Returns
    -------
    module
        The model's module, with ``simulate``, ``theory_spectrum``, ``RESPONSE`` and ``fit_band``.

    Raises
    ------
    KeyError
        An unknown name or a parameter object of no registered model (the message lists the known ones).
    """
    if isinstance(which, str):
        if which not in MODELS:
            raise KeyError(f"no model {which!r}; known: {', '.join(MODELS)}")
        return MODELS[which]
    for key, cls in PARAMS.items():
        if type(which) is cls:
            return MODELS[key]
    raise KeyError(f"{type(which).__name__} is not the parameter class of a model; known: "
                   f"{', '.join(c.__name__ for c in PARAMS.values())}")


def simulate(params, duration: float, dt_out: float | None = None, seed=None, **options):
    """Simulate a reduced model: the block's displacement and the friction force against time.

    Parameters
    ----------
    params : SpringBlockParams, MultiscaleParams, WearParticleParams or AsperityForceParams
        The model's parameters in SI units; the class selects the model (``.reference()`` is the paper's case).
    duration : float
        Simulated time (s).
    dt_out : float, optional
        Output step (s); default: the model's own (1 ms for models I, Ib and II, the grid step for model III).
    seed : int or numpy.random.Generator, optional
        Seed of the model's random numbers; the same seed gives the same trace bit for bit.
    **options
        Passed to the model's own ``simulate`` (e.g. ``contacts=True`` for model I's miniblock displacements).

    Returns
    -------
    reduced_models.ModelTrace
        ``t`` (s), ``x`` (m, the block's position), ``force`` (N) and ``metadata``.
    """
    kw = dict(options)
    if dt_out is not None:
        kw["dt_out"] = dt_out
    return model(params).simulate(params, duration, seed=seed, **kw)


def theory_spectrum(params, omega, **options) -> np.ndarray:
    """The model's closed-form displacement spectrum C_x(omega).

    Model I: eq. (A10); model Ib: (A10) one level down; model II: eq. (B2) through eq. (3); model III: the
    window sum's exact spectrum through eq. (3). Two-sided in angular frequency (eq. 2).

    Parameters
    ----------
    params : SpringBlockParams, MultiscaleParams, WearParticleParams or AsperityForceParams
        The model's parameters (SI); the class selects the model.
    omega : array_like
        Angular frequencies (rad/s), positive.
    **options
        Passed to the model's own ``theory_spectrum`` (e.g. ``closure=`` for models Ib and II).

    Returns
    -------
    numpy.ndarray
        C_x at ``omega`` (m^2 s).
    """
    return model(params).theory_spectrum(params, np.asarray(omega, dtype=float), **options)
