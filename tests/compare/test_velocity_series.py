"""A velocity series of measured displacement records: C_x(omega) against v, its exponent, the q = omega / v collapse
and model I's level (eq. 6), on synthetic records with C_x = K v^beta omega^-4 exactly (the sampled process, folded at
Nyquist)."""
import json

import numpy as np
import pytest

from compare.cli import main

DT, N = 1e-2, 2**14  # 100 Hz for 164 s: the automatic fit bands of omega^-4 records overlap over about a decade
SPEEDS = (2e-4, 5e-4, 1.25e-3)  # m/s, a factor 6.25 in v


def _records(beta, seed0=0):
    """Three records x = v t + zeta, zeta the sampled process of C_x = K (v / v0)^beta omega^-4 exactly (folded at
    Nyquist, circulant embedding: compare.analysis.synthetic.power_law_record), K = 1e-19 m^2 s (rad/s)^4 (0.1 um
    rms) and v0 = 0.5 mm/s for all three."""
    from compare.analysis.synthetic import power_law_record

    t = np.arange(N) * DT
    return [(t, v * t + power_law_record(N, DT, 4.0, prefactor=1e-19 * (v / 5e-4) ** beta, seed=seed0 + i))
            for i, v in enumerate(SPEEDS)]


@pytest.fixture(scope="module")
def analyses():
    """The record-model analyses of ``_records(beta)`` by beta, each made once in the module (the exponent test and
    the refusals read the same three records at beta = 3)."""
    from compare.analysis.displacement import analyze_displacement

    made = {}

    def of(beta):
        if beta not in made:
            made[beta] = [analyze_displacement(t, x) for t, x in _records(beta)]
        return made[beta]
    return of


@pytest.mark.parametrize("beta", [5 / 3, 3.0])
def test_velocity_exponent_is_recovered_within_its_interval(beta, analyses):
    # The exponent of C_x(omega*) against v is beta by construction; three records with independent noise, so the
    # truth must lie in the 95 % interval (a 5 % chance per case if the interval is honest; the band-averaging
    # error counts only half the Welch ordinates as independent, so it is conservative). Measured over 30 other seed
    # sets (seed0 = 100, 103, ..., 187) at beta = 5/3: mean 1.663, sd 0.023, median half-width 0.022 (omega* from
    # 12 to 64 rad/s); 30/30 covered; none took the residual-scatter interval; each record's gamma 3.998, sd 0.033.
    from compare.analysis.velocity_series import velocity_series

    s = velocity_series(analyses(beta))
    assert s.omega_auto and s.common_band[0] < s.omega < s.common_band[1]
    assert abs(s.exponent - beta) <= s.exponent_err, (s.exponent, s.exponent_err, s.exponent_err_source)
    assert s.exponent_err < 0.5  # a useful interval: the speeds span 0.8 of a decade
    np.testing.assert_allclose(s.v, SPEEDS, rtol=1e-3)  # 1e-6 m of noise over >= 3 cm of travel
    # eq. (6): alpha^2/(N a) = 12 pi omega^4 C_x / v^3 scales as v^(beta - 3): constant for model I's beta = 3. The
    # level is a geometric mean over ~ hundreds of ordinates, so its own scatter is a few %; 25 % bounds it.
    ratio = s.level_alpha2_Na / s.level_alpha2_Na[1]
    np.testing.assert_allclose(ratio, (np.array(SPEEDS) / SPEEDS[1]) ** (beta - 3), rtol=0.25)
    # section 2: v C_x(q v) = K v^(beta + 1 - 4) q^-4 collapses exactly at beta = 3; at 5/3 it does not
    assert (s.collapse["collapse_gain"] > 5) == (beta == 3.0), s.collapse


def test_omega_given_and_bad_series_are_refused(analyses):
    from compare.analysis.displacement import analyze_displacement
    from compare.analysis.velocity_series import velocity_series

    ans = analyses(3.0)
    s = velocity_series(ans, omega=10.0)
    assert s.omega == 10.0 and not s.omega_auto and abs(s.exponent - 3) <= s.exponent_err
    with pytest.raises(ValueError, match="two or more"):
        velocity_series(ans[:1])
    with pytest.raises(ValueError, match="do not overlap"):  # bands forced apart: no common omega
        velocity_series([analyze_displacement(*_records(3.0)[0], band=(1.0, 3.0)),
                         analyze_displacement(*_records(3.0)[1], band=(10.0, 30.0))])


def _write(path, t, x):
    with open(path, "w") as fh:
        fh.write("t,x\n" + "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(t, x * 1e6)))


def test_cli_series_of_three_files(tmp_path, capsys, monkeypatch):
    # `frictionnoise analyze A.csv B.csv C.csv`: exit 0, the summary holds the Python result of the same records,
    # the figures are written; one file with --omega, or an omega outside the records: one line, exit 2.
    monkeypatch.chdir(tmp_path)
    names = []
    for i, (t, x) in enumerate(_records(5 / 3)):
        names.append(f"v{i}.csv")
        _write(names[-1], t, x)
    opts = ["--x-unit", "um", "--time-unit", "s"]
    assert main(["analyze", *names, *opts]) == 0
    printed = capsys.readouterr().out
    assert "~ v^(" in printed and "model I alpha^2/(N a)" in printed
    out = tmp_path / "analyze-series-v0"
    assert f"<title>frictionnoise analyze: {len(names)} records against speed</title>" in (out / "index.html").read_text()
    s = json.loads((out / "summary.json").read_text())["velocity_series"]
    assert abs(s["exponent"] - 5 / 3) <= s["exponent_err"] and s["exponent_err_source"] in ("per-record",
                                                                                          "residual scatter")
    assert len(s["model_I_alpha2_over_Na"]) == 3 and "f_kin" in s["model_I_assumption"]
    assert sorted(p.name for p in (out / "figures").iterdir()) == ["series_Cx.png", "series_collapse.png"]
    for argv in (["analyze", names[0], "--omega", "10", *opts],
                 ["analyze", *names[:2], "--omega", "1000", *opts]):  # above the Nyquist frequency, 314 rad/s
        assert main(argv + ["-o", "bad"]) == 2 and not (tmp_path / "bad").exists()
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1, err
