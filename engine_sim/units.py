"""The scene's unit system (mm, g, ms) and the conversions at its boundary. Nothing else converts units.

In mm-g-ms units a force is g mm / ms^2 = 1 N, a velocity mm/ms = 1 m/s and a damping g/ms = 1 N s/m, so
those pass through unchanged; lengths scale by 1e3, masses by 1e3, times by 1e3, stiffness by 1e-3
(N/m -> N/mm), accelerations by 1e-3 and energies by 1e3 (J -> N mm).
"""
LENGTH = 1e3   # scene units per metre
MASS = 1e3     # per kilogram
TIME = 1e3     # per second
STIFFNESS = MASS / TIME**2   # N/m -> g/ms^2 (= N/mm)
ACCEL = LENGTH / TIME**2     # m/s^2 -> mm/ms^2
ENERGY = MASS * LENGTH**2 / TIME**2  # J -> g mm^2/ms^2 (= N mm)
VELOCITY = LENGTH / TIME     # = 1
FORCE = MASS * LENGTH / TIME**2  # = 1
DAMPING = MASS / TIME        # = 1
