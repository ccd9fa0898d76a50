"""The reduced models of Xu, Zhou & Persson (Soft Matter 2025): parameters, simulators, closed forms.

Model I: :mod:`reduced_models.spring_block`; model II: :mod:`reduced_models.wear_particle`;
model III: :mod:`reduced_models.asperity_force`. Each module has ``*Params`` (frozen, SI), ``simulate``
and ``theory_spectrum``; all simulators return a :class:`ModelTrace`.
"""
from . import asperity_force, spring_block, wear_particle
from .asperity_force import AsperityForceParams
from .spring_block import SpringBlockParams
from .trace import ModelTrace
from .wear_particle import DurationLaw, WearParticleParams

__all__ = ["spring_block", "wear_particle", "asperity_force", "SpringBlockParams", "WearParticleParams",
           "DurationLaw", "AsperityForceParams", "ModelTrace"]
