"""``compare.testing``, the public path of :mod:`compare.analysis.assertions`: the same module under both names, so imports,
attributes and monkeypatches through either reach one object."""
import sys

from .analysis import assertions as _module

sys.modules[__name__] = _module
