"""Measured data from Python: read an instrument's export, analyse a displacement x(t) or a friction force F(t).

:func:`read_measured` reads CSV, semicolon- or tab-separated text with a preamble, a units row and decimal
commas, into SI units; :func:`analyze_displacement` (no mass needed: gamma, C_x, C_mu and the speed; C_F when a
mass is given) and :func:`analyze_force` give the spectra of eq. (2) and their power-law fits. They are the
functions the ``frictionnoise analyze`` command runs.
"""
from __future__ import annotations

from compare.analysis.displacement import DisplacementAnalysis, analyze_displacement
from compare.io.measured import MeasuredData, read_measured
from compare.analysis.force import ForceAnalysis, analyze_force

__all__ = ["read_measured", "MeasuredData", "analyze_displacement", "DisplacementAnalysis", "analyze_force",
           "ForceAnalysis"]
