"""Friction laws, one class each: its spec (the ``[friction]`` section, SI), validation, build (the velocity part
of the law as pymunk objects on each sliding body), stepping (a law that needs a force written each step),
recorded terms (its drag force and power) and its share of ``describe()`` (parameters and slope dF/dv).

Every law is velocity strengthening at its operating point, f(v) = mu N_pad + g(v), with the Coulomb part mu N_pad
solved by pymunk's contact solver (mu carried by the substrate's shapes) and the velocity part g(v) added per sliding
body. The recorder reads g through the law's own channels: its dampers' coefficient and the form the shipped laws
share, g(v) = c v + b N_pad ln(1 + |v|/v_c) sign(v) (``drag_terms``), the impulses it applied per step
(``impulse_totals``) and, for a law of another form, the rest of g at each sample by the law's own compiled kernel
(``recorded_drag``). A new law is one module with a :class:`Law` subclass decorated with ``@LAWS.register``:
shipped, a module here (importing its base from :mod:`engine_sim.laws.law`) and one import line below; a user's,
named in a scenario's ``plugins`` (:mod:`engine_sim.plugins`).
"""
from .law import LAWS, FrictionSpec, Law, law_kind  # noqa: F401

# the laws shipped: each module registers its class
from . import linear, log, rate_state  # noqa: F401

__all__ = ["FrictionSpec", "Law", "LAWS", "law_kind"]
