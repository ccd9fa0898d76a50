"""The reduced models of Xu, Zhou & Persson (Soft Matter 2025): parameters, simulators, closed forms.

Model I: :mod:`reduced_models.spring_block`; model Ib (multiscale, the paper's Fig. 1c):
:mod:`reduced_models.multiscale`; model II: :mod:`reduced_models.wear_particle`; model III:
:mod:`reduced_models.asperity_force`.

Registration
------------
:data:`MODELS` maps a model's key (the sweep file's ``target``, the report's summary key, the argument of
``frictionnoise compare``) to its module. The sweep, the report and ``frictionnoise compare`` read models only
through it: a new model is one module and one :func:`register` line below, with no edit elsewhere. A registered
module provides:

``PARAMS``
    Its parameter class: a frozen dataclass in SI units, validated on construction (ValueError naming the field),
    built from keyword arguments; its fields with ``init`` and ``repr`` are the names a sweep may set, each of the
    type of its default; it has a field ``v``, the sliding speed (m/s), and ``to_dict()``.
``simulate(params, duration, dt_out, seed=...)``
    A :class:`ModelTrace` of ``duration`` seconds sampled every ``dt_out`` seconds, seeded by ``seed`` alone.
``theory_spectrum(params, omega)``
    The closed-form displacement spectrum C_x(omega) (m^2 s, two-sided, eq. 2) at angular frequencies omega
    (rad/s).
``RESPONSE``
    "viscous" (C_x ~ C_F / omega^2 below the model's crossover) or "inertial" (C_x = C_F / (M^2 omega^4), eq. 3).
``fit_band(params, dt_out=None)``
    The band (lo, hi) in rad/s of its power law, or None for the fit's automatic band.
``default_duration(params)``, ``default_dt_out(params)``
    A run's simulated seconds and output step when the caller sets none (s).
``SWEEP_SERIES``
    The :class:`ModelTrace` field whose spectrum a sweep task returns: "x" (C_x, the block's displacement) or
    "force" (C_F).

:func:`register` checks these names are there. :data:`PARAMS` is the parameter class of each registered model.
"""
from . import asperity_force, multiscale, spring_block, wear_particle
from .asperity_force import AsperityForceParams
from .multiscale import MultiscaleParams
from .spring_block import SpringBlockParams
from .trace import ModelTrace
from .wear_particle import DurationLaw, WearParticleParams

__all__ = ["spring_block", "multiscale", "wear_particle", "asperity_force", "SpringBlockParams", "MultiscaleParams",
           "WearParticleParams", "DurationLaw", "AsperityForceParams", "ModelTrace", "MODELS", "PARAMS", "PROTOCOL",
           "register", "model"]

PROTOCOL = ("PARAMS", "simulate", "theory_spectrum", "RESPONSE", "fit_band", "default_duration", "default_dt_out",
            "SWEEP_SERIES")
MODELS: dict = {}
PARAMS: dict = {}


def register(name: str, module, registry: dict | None = None):
    """Make ``module`` the model ``name`` in ``registry`` (default :data:`MODELS`, and its class in :data:`PARAMS`).

    Parameters
    ----------
    name : str
        The model's key (a sweep's ``target``, the argument of ``frictionnoise compare``), e.g. ``"model_I"``.
    module : module
        The model's module, providing every name of :data:`PROTOCOL`.
    registry : dict, optional
        The registry to fill; default :data:`MODELS`.

    Returns
    -------
    module
        ``module``; TypeError naming the first attribute of :data:`PROTOCOL` it lacks otherwise.
    """
    missing = [a for a in PROTOCOL if not hasattr(module, a)]
    if missing:
        raise TypeError(f"model {name!r} ({getattr(module, '__name__', module)!r}) lacks {missing[0]}: a registered "
                        f"model provides {', '.join(PROTOCOL)} (see reduced_models/__init__.py)")
    if module.RESPONSE not in ("viscous", "inertial"):
        raise TypeError(f"model {name!r}: RESPONSE must be 'viscous' or 'inertial' (got {module.RESPONSE!r})")
    if module.SWEEP_SERIES not in ("x", "force"):
        raise TypeError(f"model {name!r}: SWEEP_SERIES must be 'x' or 'force' (got {module.SWEEP_SERIES!r})")
    if registry is None:
        registry = MODELS
        PARAMS[name] = module.PARAMS
    registry[name] = module
    return module


def model(name: str):
    """The registered model module ``name``.

    Parameters
    ----------
    name : str
        A key of :data:`MODELS`.

    Returns
    -------
    module
        The model's module; KeyError naming the registered ones otherwise.
    """
    try:
        return MODELS[name]
    except KeyError:
        raise KeyError(f"no model {name!r}; registered: {', '.join(MODELS)}") from None


register("model_I", spring_block)
register("model_Ib", multiscale)
register("model_II", wear_particle)
register("model_III", asperity_force)
from . import ageing, rate_state  # noqa: E402  model I with ageing contacts; the rate-and-state law and spring-slider
register("model_ageing", ageing)
from . import vibrating_block  # noqa: E402  model I on a substrate vibrating along the sliding direction
register("model_Iv", vibrating_block)
