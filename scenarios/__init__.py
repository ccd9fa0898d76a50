"""The scenarios shipped with frictionnoise, as package data: scene files (``*.toml``), sweep files
(``sweeps/``), example data (``data/``) and measured profiles (``profiles/``).

Find them by name with :func:`engine_sim.shipped_scenarios` or ``frictionnoise scenarios``; run one with
``frictionnoise run <name>`` from any folder (a file of the same spelling in the current folder wins).
"""
__all__: list[str] = []
