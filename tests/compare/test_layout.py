"""compare/ by role: the import contracts of pyproject.toml hold (lint-imports, as CI runs it), and the public
import paths users already have (compare.spectra, compare.fits, compare.testing, the console script) still work."""
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_the_import_contracts_hold():
    exe = shutil.which("lint-imports", path=str(Path(sys.executable).parent)) or shutil.which("lint-imports")
    assert exe, "lint-imports (import-linter, in the test extra) is not installed"
    r = subprocess.run([exe], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and "BROKEN" not in r.stdout, r.stdout[-3000:]
    assert r.stdout.count("KEPT") >= 4, r.stdout[-3000:]


def test_the_public_paths_are_the_analysis_modules():
    import compare
    import compare.analysis.assertions
    import compare.analysis.fits
    import compare.analysis.spectra
    import compare.fits
    import compare.spectra
    import compare.testing

    assert compare.spectra is compare.analysis.spectra and compare.fits is compare.analysis.fits
    assert compare.testing is compare.analysis.assertions
    from compare.fits import fit_power_law
    from compare.spectra import displacement_spectrum

    assert compare.fit_power_law is fit_power_law and compare.displacement_spectrum is displacement_spectrum


def test_the_console_script_points_at_the_cli():
    import tomllib

    from compare.cli import main

    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
    module, _, name = scripts["frictionnoise"].partition(":")
    assert (module, name) == ("compare.cli", "main") and callable(main)
