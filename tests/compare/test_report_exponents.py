"""The report's exponents come from the record model (compare.analysis.record_model.fit_record) fitted to the time
record, not from a straight line through a Welch spectrum (compare.analysis.fits.fit_power_law)."""
import ast
import pathlib

import numpy as np
import pytest

from compare.analysis.record_model import fit_record
from compare.report.studies._common import record_fit

ROOT = pathlib.Path(__file__).resolve().parents[2]
REPORT_FILES = sorted((ROOT / "compare" / "report" / "studies").glob("*.py")) + [
    ROOT / "compare" / "sweep" / "tasks.py", ROOT / "compare" / "analysis" / "wear_study.py"]
DT = 1e-3


@pytest.mark.parametrize("path", REPORT_FILES, ids=lambda p: p.name)
def test_no_report_study_fits_a_welch_spectrum(path):
    # fit_power_law is named nowhere in the report's studies, the sweep's task or the wear study's statistics (imported, called or reached as an
    # attribute): every exponent they quote is fitted to a record by the record model.
    names = {n.id for n in ast.walk(ast.parse(path.read_text())) if isinstance(n, ast.Name)}
    names |= {n.attr for n in ast.walk(ast.parse(path.read_text())) if isinstance(n, ast.Attribute)}
    names |= {a.name for n in ast.walk(ast.parse(path.read_text())) if isinstance(n, ast.ImportFrom) for a in n.names}
    assert "fit_power_law" not in names


def test_model_check_quotes_fit_record_on_its_record():
    # The registered model's study against fit_record on the same seeded simulator record: the summary's gamma,
    # interval and method are the record model's, equal to the last bit (the same computation on the same record).
    from reduced_models import model as registered

    from compare.report.studies.model_check import model_result

    res = model_result("model_I", seed=3, duration=40.0)
    model = registered("model_I")
    p = model.PARAMS.reference()
    dt = model.default_dt_out(p)
    tr = model.simulate(p, 40.0, dt, seed=3)
    band = model.fit_band(p, dt)
    ref = fit_record(tr.x, float(tr.t[1] - tr.t[0]), band=band, stationarity=False)
    assert res.numbers["method"] == "record" and "differencing_order" in res.numbers
    assert res.numbers["gamma"] == ref.gamma and res.numbers["gamma_interval"] == [ref.gamma_low, ref.gamma_high]


def test_integrated_force_fit_reads_the_force_exponent():
    # A 1/f-like force (omega^-1.0, flatter than the record model's omega^-1.05) fitted through its running sum:
    # C of the sum is C_F dt^2 / (4 sin^2(omega dt / 2)) = C_F / omega^2 to (omega dt)^2 / 12, so the sum reads
    # gamma_F + 2 and record_fit returns gamma_F. 2^15 samples give a half-width near 0.03 over 1-300 rad/s; the
    # 0.1 tolerance is three of them.
    from compare.analysis.synthetic import power_law_record

    n = 2**15
    x = power_law_record(n, DT, 3.0, seed=2)  # a record whose differences are an omega^-1 force
    f = np.diff(x) / DT
    t = np.arange(len(f)) * DT
    fit = record_fit(t, f, band=(1.0, 300.0), quantity="F", stationarity=False, integrate=True)
    assert fit.quantity == "F" and abs(fit.gamma - 1.0) < 0.1


def test_a_flat_force_is_refused_as_flat_not_as_its_running_sum():
    # The running sum of a constant channel is a straight line (a record with a spectrum); the record itself is
    # refused, in one line naming the channel.
    t = np.arange(4096) * DT
    with pytest.raises(ValueError, match="F") as e:
        record_fit(t, np.full(t.size, 2.5), band=(1.0, 300.0), quantity="F", integrate=True)
    assert "\n" not in str(e.value)


def test_a_force_held_between_events_is_fitted_not_refused_as_rounded():
    # An exact simulator's force that holds between contact events (model III's, still in most steps) is not a file
    # written at its resolution: the running-sum fit takes it. The same 1/f force as above, each value held for 8
    # steps (still in 7/8 of the steps); holding is a zero-order hold, which leaves the spectrum below omega = 2 pi /
    # (8 dt) / 4 = 196 rad/s within 10 % of the unheld one, so the exponent over 1-100 rad/s stays near 1.
    from compare.analysis.record_model import check_record
    from compare.analysis.synthetic import power_law_record

    x = power_law_record(2**15, 8 * DT, 3.0, seed=2)
    f = np.repeat(np.diff(x) / (8 * DT), 8)
    t = np.arange(len(f)) * DT
    with pytest.raises(ValueError, match="resolution"):
        check_record(f, "F")  # a file like this one is refused as rounded
    fit = record_fit(t, f, band=(1.0, 100.0), quantity="F", stationarity=False, integrate=True)
    assert fit.quantity == "F" and abs(fit.gamma - 1.0) < 0.15
