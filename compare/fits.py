"""``compare.fits``, the public path of :mod:`compare.analysis.fits`: the same module under both names, so imports,
attributes and monkeypatches through either reach one object."""
import sys

from .analysis import fits as _module

sys.modules[__name__] = _module
