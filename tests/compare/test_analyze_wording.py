"""What analyze prints about a record's floor, its speed and its mechanisms, in words a user can act on."""
from compare.cli.mechanisms import mechanisms_of, ranking_lines, ranking_section
from compare.cli.record_summary import _fit_text

FIT = {"gamma": 4.01, "gamma_err": 0.05, "gamma_interval": [3.96, 4.06], "method": "record", "band": [1.0, 100.0],
       "power_law": True, "flags": []}


def test_a_floor_that_is_absent_or_never_reached_is_said_so():
    assert "no white floor detected" in _fit_text({**FIT, "floor": 0.0, "floor_rms": 0.0, "crossover": None})
    below = _fit_text({**FIT, "floor": 1e-30, "floor_rms": 1e-12, "crossover": None})
    assert "below the power law over the whole band" in below and "no floor resolved" in below and "inf" not in below
    assert "white floor" not in below  # a term fitted, not a floor found
    ends = _fit_text({**FIT, "band": [1.0, 250.0], "floor": 1e-24, "floor_rms": 7.9e-11, "crossover": 250.0,
                      "band_end": "floor"})
    assert "over the power law above 250 rad/s: the floor ends the band" in ends


def test_a_band_cut_below_a_resonance_is_not_said_to_end_at_a_floor():
    # The band search cut the band at 166 rad/s (a resonance's approach above it); the floor term fitted inside the
    # band would cross the power law only at 611 rad/s, beyond the band: the words name the departure and the band
    # above it, not a floor taking over.
    fit = {**FIT, "gamma": 3.96, "band": [1.66, 166.0], "floor": 1e-26, "floor_rms": 1.2e-10, "crossover": 611.0,
           "band_end": "departure", "segments": [
               {"band": [1.66, 166.0], "gamma": 3.96, "gamma_interval": [3.9, 4.0], "differencing_order": 2},
               {"band": [166.0, 3140.0], "gamma": 9.31, "gamma_interval": [9.1, 9.5], "differencing_order": 5}]}
    text = _fit_text(fit)
    assert "over the power law above" not in text and "611" not in text, text
    assert "the band ends at 166 rad/s, where the spectrum departs from this power law" in text, text
    assert "not at a white floor (steeper above: 9.31 over 166-3.14e+03 rad/s)" in text, text
    assert "floor term of 1.2e-10 m rms fitted inside the band, below the power law there" in text, text
    alone = _fit_text({**fit, "floor": 0.0, "floor_rms": 0.0, "segments": fit["segments"][:1]})
    assert "no white floor detected" in alone and "no band of a decade above it holds one power law" in alone


def test_the_exponent_and_the_ranking_label_their_plus_minus_alike():
    assert "+-: 95 % half-width" in _fit_text(FIT)
    assert "+-: 95 % half-width" in ranking_lines({"mechanisms": [
        {"model": "model_I", "verdict": "fits", "p_value": 1.0, "separate": "", "parameters": {}}]})[0]


def test_a_record_whose_displacement_falls_gets_no_mechanism_and_a_reason():
    class Record:
        segmented = False

    note = mechanisms_of(Record(), -16.4)["mechanisms_note"]
    assert "falls over the record" in note and "negate x" in note and "slide forward" not in note


def test_the_ranking_is_the_first_section_of_the_page_text():
    summary = {"mechanisms": [{"model": "model_I", "verdict": "fits", "p_value": 1.0, "separate": "",
                               "parameters": {"L": [1.1e-10, 5e-12, "m^2 s^-3"]}}]}
    sec = ranking_section(summary)
    assert sec.title.startswith("Mechanisms")
    for line in ranking_lines(summary):
        assert line.replace("<", "&lt;").replace(">", "&gt;") in sec.html


def test_a_record_too_short_for_the_ranking_gets_its_length_and_the_minimum():
    # 200 samples (a tribometer's short stroke) used to end in numpy's broadcast error from the families' start
    import numpy as np
    import pytest

    from compare.analysis.identify import MIN_SAMPLES, identify

    class Record:
        segmented = False
        t = np.arange(200) * 1e-3
        x = 1e-4 * t + 1e-9 * np.cumsum(np.cumsum(np.random.default_rng(0).standard_normal(200)))

    note = mechanisms_of(Record(), 1e-4)["mechanisms_note"]
    assert note.startswith("no mechanism named: the record holds 200 samples") and str(MIN_SAMPLES) in note
    with pytest.raises(ValueError, match=f"holds 200 samples.*at least {MIN_SAMPLES}"):
        identify(Record.t, Record.x, v=1e-4)


def test_mu_rms_measures_the_friction_not_the_sensors_floor():
    # omega^4 C_x weighs a white floor as omega^4: integrated to Nyquist, a 3 nm floor on an omega^-4 record of
    # 2^14 samples at 1 kHz reads several times the floor-free mu_rms. Over the fitted band, which ends where the
    # floor takes over, mu_rms is the friction's: C_mu of an omega^-4 record is flat, so the floor-free record's
    # mu_rms over the noisy record's band is its own times sqrt of the bands' widths' ratio; within 15 % (two
    # records' Welch scatter over ~900 rad/s).
    import numpy as np

    from compare.analysis.displacement import analyze_displacement
    from compare.analysis.spectra import rms_from_spectrum
    from compare.analysis.synthetic import power_law_record

    n, dt = 2**14, 1e-3
    t = np.arange(n) * dt
    a = {floor: analyze_displacement(t, 1e-4 * t + power_law_record(n, dt, 4.0, prefactor=1e-9, floor_rms=floor, seed=3))
         for floor in (0.0, 3e-9)}
    clean, noisy = a[0.0], a[3e-9]
    assert noisy.rms_band[1] < clean.rms_band[1] and noisy.summary()["mu_rms_band"] == noisy.rms_band
    width = (noisy.rms_band[1] - noisy.rms_band[0]) / (clean.rms_band[1] - clean.rms_band[0])
    assert abs(noisy.mu_rms / (clean.mu_rms * width**0.5) - 1) < 0.15, (clean.mu_rms, noisy.mu_rms, width)
    to_nyquist = rms_from_spectrum(noisy.C_mu) / rms_from_spectrum(clean.C_mu)
    assert to_nyquist > 2, to_nyquist  # what the floor made of mu_rms over the whole resolved range


def test_a_rejected_model_prints_no_parameters():
    # its best fit estimates nothing the record holds: the terminal points to summary.json, which keeps them
    summary = {"mechanisms": [
        {"model": "model_I", "verdict": "fits", "p_value": 1.0, "separate": "",
         "parameters": {"L": [1.1e-10, 5e-12, "m^2 s^-3"]}},
        {"model": "model_II", "verdict": "rejected", "p_value": 2.5e-5, "separate": "",
         "parameters": {"S": [3.2e-9, 1e-10, "m^2 s^-3"], "s": "not identified"}}]}
    lines = ranking_lines(summary)
    assert "L = 1.1e-10 +- 5e-12" in lines[1]
    assert lines[2].split()[:2] == ["model_II", "rejected"] and "S =" not in lines[2] and "s," not in lines[2]
    assert lines[2].endswith("parameters of its best fit in summary.json"), lines[2]
