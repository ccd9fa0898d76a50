"""``compare.spectra``, the public path of :mod:`compare.analysis.spectra`: the same module under both names, so imports,
attributes and monkeypatches through either reach one object."""
import sys

from .analysis import spectra as _module

sys.modules[__name__] = _module
