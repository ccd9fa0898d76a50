"""The reduced models of Xu, Zhou & Persson (Soft Matter 2025): parameters, simulators, closed forms.

Model I: :mod:`reduced_models.spring_block`; model Ib (multiscale, the paper's Fig. 1c):
:mod:`reduced_models.multiscale`; model II: :mod:`reduced_models.wear_particle`; model III:
:mod:`reduced_models.asperity_force`. Each module has ``*Params`` (frozen, SI), ``simulate(params, duration,
dt_out=..., seed=...)`` returning a :class:`ModelTrace`, ``theory_spectrum(params, omega)``, ``RESPONSE``
("viscous": C_x ~ C_F / omega^2 below the model's crossover; "inertial": C_x = C_F / (M^2 omega^4), eq. 3) and
``fit_band(params, dt_out=None)`` (the band of its power law in rad/s, or None for the automatic one).
:data:`MODELS` maps the report's keys to these modules, so callers need not branch on model names.
"""
from . import asperity_force, multiscale, spring_block, wear_particle
from .asperity_force import AsperityForceParams
from .multiscale import MultiscaleParams
from .spring_block import SpringBlockParams
from .trace import ModelTrace
from .wear_particle import DurationLaw, WearParticleParams

MODELS = {"model_I": spring_block, "model_Ib": multiscale, "model_II": wear_particle, "model_III": asperity_force}
PARAMS = {"model_I": SpringBlockParams, "model_Ib": MultiscaleParams, "model_II": WearParticleParams,
          "model_III": AsperityForceParams}

__all__ = ["spring_block", "multiscale", "wear_particle", "asperity_force", "SpringBlockParams", "MultiscaleParams",
           "WearParticleParams", "DurationLaw", "AsperityForceParams", "ModelTrace", "MODELS", "PARAMS"]
