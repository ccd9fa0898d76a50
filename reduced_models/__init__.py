"""The reduced models of Xu, Zhou & Persson (Soft Matter 2025): parameters, simulators, closed forms."""
from . import spring_block
from .spring_block import SpringBlockParams
from .trace import ModelTrace

__all__ = ["spring_block", "SpringBlockParams", "ModelTrace"]
