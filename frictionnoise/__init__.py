"""frictionnoise: the displacement and force noise of sliding friction, from Python.

``import frictionnoise as fn`` gives what a notebook user calls, in SI units (m, kg, s, N; frequencies in
rad/s; spectra in the two-sided angular convention of eq. (2) of Xu, Zhou & Persson, Soft Matter 21, 7594
(2025), DOI 10.1039/d5sm00617a):

- **spectra and fits**: :func:`displacement_spectrum`, :func:`force_series_spectrum`, :func:`force_spectrum`,
  :func:`friction_coefficient_spectrum`, :func:`rms_from_spectrum`, :func:`band_average`, :func:`log_bin`,
  :class:`Spectrum`; :func:`fit_power_law` and :class:`PowerLawFit`; the test helpers
  :func:`assert_spectral_slope` and :func:`assert_spectrum_matches`;
- **the reduced models** I, Ib, II and III and their extensions: their parameters (:class:`SpringBlockParams`,
  :class:`MultiscaleParams`, :class:`WearParticleParams`, :class:`AsperityForceParams`, :class:`AgeingParams`
  for ageing contacts, :class:`VibratingBlockParams` for a shaken substrate; ``.reference()`` is the paper's case), :func:`simulate` and :func:`theory_spectrum` for any of them, :func:`model` and
  :data:`MODELS` for the modules;
- **scenes** (the pymunk engine): :func:`shipped_scenarios`, :func:`load_scenario`, :func:`run_scene`,
  :func:`render_scene`, :func:`compare_scene`, :func:`save_trace` and :func:`load_trace`;
- **measured data**: :func:`read_measured`, :func:`analyze_displacement` for x(t) and :func:`analyze_force` for a
  friction-force record; :func:`identify` ranks the paper's mechanisms for x(t) (:class:`Mechanism`).

The names above are imported on first use (PEP 562 ``__getattr__``): ``import frictionnoise`` loads no numerics,
and the packages below it (``engine_sim``, ``reduced_models``, ``compare``) may import this package's own shared
helpers, :data:`G`, :func:`package_version` and :func:`atomic_write`, defined here without importing any of them.
"""
from __future__ import annotations

import itertools
import os
from importlib import import_module
from importlib import metadata as _metadata
from pathlib import Path

# name -> module that defines it (imported on first access)
_LAZY = {
    # spectra and fits
    "Spectrum": "compare.spectra", "displacement_spectrum": "compare.spectra",
    "force_series_spectrum": "compare.spectra", "series_spectrum": "compare.spectra",
    "force_spectrum": "compare.spectra", "friction_coefficient_spectrum": "compare.spectra",
    "rms_from_spectrum": "compare.spectra", "band_average": "compare.spectra", "log_bin": "compare.spectra",
    "PowerLawFit": "compare.fits", "fit_power_law": "compare.fits",
    "assert_spectral_slope": "compare.testing", "assert_spectrum_matches": "compare.testing",
    # the reduced models
    "SpringBlockParams": "reduced_models", "MultiscaleParams": "reduced_models",
    "WearParticleParams": "reduced_models", "AsperityForceParams": "reduced_models",
    "AgeingParams": "reduced_models.ageing", "VibratingBlockParams": "reduced_models.vibrating_block",
    "ModelTrace": "reduced_models", "MODELS": "reduced_models",
    "simulate": "frictionnoise.models", "theory_spectrum": "frictionnoise.models", "model": "frictionnoise.models",
    # scenes
    "Scenario": "engine_sim", "EngineTrace": "engine_sim", "load_scenario": "engine_sim",
    "shipped_scenarios": "engine_sim", "run_scene": "frictionnoise.scenes", "render_scene": "frictionnoise.scenes",
    "compare_scene": "frictionnoise.scenes", "save_trace": "frictionnoise.scenes",
    "load_trace": "frictionnoise.scenes",
    # measured data
    "MeasuredData": "frictionnoise.measurements", "read_measured": "frictionnoise.measurements",
    "DisplacementAnalysis": "frictionnoise.measurements", "analyze_displacement": "frictionnoise.measurements",
    "ForceAnalysis": "frictionnoise.measurements", "analyze_force": "frictionnoise.measurements",
    "identify": "compare.analysis.identify", "Mechanism": "compare.analysis.identify",
}

__all__ = ["G", "package_version", "atomic_write", *_LAZY]

_counter = itertools.count()

G = 9.81  # m/s^2: the paper's g (standard gravity rounded as in Xu, Zhou & Persson 2025)


def __getattr__(name):
    if name in _LAZY:
        value = getattr(import_module(_LAZY[name]), name)
        globals()[name] = value  # looked up once
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))


def package_version() -> str:
    """The installed distribution's version.

    Returns
    -------
    str
        The version of the installed ``frictionnoise`` distribution, or ``"0+unknown"`` when running from a
        source tree that was never installed.
    """
    try:
        return _metadata.version("frictionnoise")
    except _metadata.PackageNotFoundError:
        return "0+unknown"


def atomic_write(path, data: bytes | str | None = None, *, write=None) -> Path:
    """Write a file atomically: a reader sees the old file or the whole new one, never a part.

    The content goes into a hidden temporary sibling, renamed over ``path`` when complete; on any error the
    temporary file is removed. The file is created 0666 less the umask, as :func:`open` does.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write.
    data : bytes or str, optional
        The content (text is written as UTF-8).
    write : callable, optional
        ``write(tmp_path)`` writes the temporary file itself (for writers that want a path, such as
        ``numpy.savez``); called after ``data`` is written, if both are given.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{next(_counter)}.tmp")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
    try:
        with os.fdopen(fd, "wb") as fh:
            if data is not None:
                fh.write(data.encode() if isinstance(data, str) else data)
        if write is not None:
            write(tmp)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path
