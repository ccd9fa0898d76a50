"""The command line under fuzzed input, every subcommand: missing, empty, binary, folder, wrong-format and
comment-only files, NaN, inf, negative, out-of-range and non-numeric values, scenario fields beyond their
validated range, unicode paths. Every case exits 0, 2 or 130 with no traceback; exit 2 prints one line and
leaves no output. Simulated durations are capped so each case is short. The number of cases is printed."""
import contextlib
import io
import math
import shutil
import tempfile
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from compare.cli import main
from engine_sim import shipped_scenarios

PATCHES = shipped_scenarios()["pads_friction_patches"]
NAMES = ["plain", "ünïcödé", "日本語", "emoji🙂", "spa ce", "-dash"]
NUMBERS = ["nan", "inf", "-inf", "-1", "0", "1e-9", "0.02", "3", "1e12", "abc", "", "1e400"]
# scenario fields set beyond (or at the edge of) their validated range
BAD_FIELDS = ["[run]\ndt = 1.0", "[run]\nduration = nan", "[run]\nwarmup = -1.0", "[block]\nM = -0.1",
              "[block]\nM = inf", "[pads]\nN = 0", "[pads]\nk0 = \"stiff\"", "[substrate]\nalpha = 5.0",
              "[run]\ndt_out = 0.0", "[drive]\nv = -1e-3", "[pads]\nbogus = 1", "[run]\nseed = -3",
              "[run]\niterations = 0", "[run]\ndt = 1e-30"]
FILE_KINDS = ["missing", "empty", "comments", "binary", "folder", "npz_junk", "csv", "scenario", "bad_field",
              "trace", "sweep", "bad_sweep"]


def _small_scenario_text():
    text = PATCHES.read_text()
    return text.replace("warmup = 1.0", "warmup = 0.01").replace("duration = 60.0", "duration = 0.03")


def _make(kind: str, d: Path, name: str, field: str) -> Path:
    p = d / f"{name}.in"
    if kind == "missing":
        return d / f"{name}-absent.toml"
    if kind == "empty":
        p.write_bytes(b"")
    elif kind == "comments":
        p.write_text("# only a comment\n\n   # and another\n")
    elif kind == "binary":
        p.write_bytes(bytes(range(256)) * 8)
    elif kind == "folder":
        p.mkdir()
    elif kind == "npz_junk":
        with open(p, "wb") as fh:
            np.savez(fh, t=np.arange(4.0), x=np.full(4, np.nan))
    elif kind == "csv":
        t = np.arange(20000) * 1e-3  # a random walk (gamma = 2), long enough for a fit
        x = np.cumsum(np.random.default_rng(0).normal(size=t.size)) * 1e-3
        p.write_text("t_s,x_m\n" + "".join(f"{a:.3f},{b:.6g}\n" for a, b in zip(t, x)))
    elif kind == "scenario":
        p.write_text(_small_scenario_text())
    elif kind == "bad_field":
        sec, line = field.split("\n")
        text = _small_scenario_text()
        p.write_text(text.replace(sec + "\n", sec + "\n" + line + "\n", 1) if sec in text else text + f"\n{field}\n")
    elif kind == "trace":
        shutil.copy(_trace(), p)
        shutil.copy(_trace().with_suffix(".json"), p.with_suffix(".json"))
    elif kind == "sweep":
        p.write_text('name = "fz"\ntarget = "model_III"\n[fixed]\nduration = 2.0\n[grid]\nv = [5e-4]\n')
    elif kind == "bad_sweep":
        p.write_text('target = "model_I"\n[fixed]\nduration = "long"\n[grid]\nvel = [1e-3]\n')
    return p


_TRACE = {}


def _trace() -> Path:
    """A small trace written by `frictionnoise run` (made once)."""
    if "p" not in _TRACE:
        d = Path(tempfile.mkdtemp(prefix="fuzz-trace-"))
        (d / "s.toml").write_text(_small_scenario_text())
        with contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
            assert main(["run", str(d / "s.toml"), "-o", str(d / "r")]) == 0
        _TRACE["p"] = d / "r" / "trace.npz"
    return _TRACE["p"]


def _capped(v: str, cap: float) -> str:
    """A fuzzed duration, capped so a valid case stays short (the invalid ones pass through)."""
    try:
        f = float(v)
    except ValueError:
        return v
    return str(min(f, cap)) if math.isfinite(f) and f > 0 else v


cases = st.fixed_dictionaries({
    "cmd": st.sampled_from(["run", "compare", "render", "sweep", "analyze", "report"]),
    # valid inputs drawn more often, so that the fuzzed numbers also reach the running paths
    "kind": st.sampled_from(FILE_KINDS + ["scenario"] * 4 + ["trace", "sweep", "csv"] * 2),
    "name": st.sampled_from(NAMES),
    "field": st.sampled_from(BAD_FIELDS),
    "num": st.sampled_from(NUMBERS),
    "flag": st.sampled_from([0, 0, 0, 1, 2, 3, 4, 5]),  # 0: the plain (valid) call, more often
    "out": st.sampled_from(["new"] * 4 + ["existing_folder", "file", "under_file"]),
})


def _argv(c, src: Path, out: Path):
    n = c["num"]
    cmd = c["cmd"]
    if cmd == "run":
        flags = [[], ["--duration", _capped(n, 0.03)], ["--seed", n], ["--epoch", n],
                 ["--checkpoint-every", n, "--duration", "0.03"], ["--duration", "0.03", "--epoch", n]][c["flag"]]
        return ["run", str(src), *flags, "-o", str(out)]
    if cmd == "compare":
        flags = [[], ["--duration", _capped(n, 0.03)], ["--seed", n], [], [], []][c["flag"]]
        return ["compare", str(src), *flags, "-o", str(out)]
    if cmd == "render":
        flags = [["--frames", "2", "--duration", "0.005"], ["--frames", n, "--duration", "0.005"],
                 ["--duration", _capped(n, 0.005), "--frames", "2"], ["--seed", n, "--frames", "1"],
                 ["--frames", "2", "--gif", "--duration", "0.005"], ["--frames", "0"]][c["flag"]]
        return ["render", str(src), *flags, "-o", str(out)]
    if cmd == "sweep":
        flags = [["--serial"], ["--serial", "--workers", n], ["--workers", "0"], ["--serial", "--connect-timeout", n],
                 ["--serial"], ["--serial"]][c["flag"]]
        return ["sweep", str(src), *flags, "-o", str(out)]
    if cmd == "analyze":
        flags = [["--mass", "1"], ["--mass", n], ["--mass", "1", "--band", n, "10"], ["--mass", "1"],
                 ["--mass", "1", "--x-unit", "um"], ["--mass", "1"]][c["flag"]]
        return ["analyze", str(src), *flags, "-o", str(out)]
    # report: only cases that must stop before running (the report itself takes minutes)
    flags = [["--workers", "0"], ["--workers", "-2"], ["--seed", "-1"], ["--workers", "abc"], ["--seed", "nan"],
             ["--workers", "0"]][c["flag"]]
    if c["out"] in ("new", "existing_folder") and flags[0] == "--workers" and flags[1] not in ("0", "-2", "abc"):
        flags = ["--workers", "0"]
    return ["report", *flags, "-o", str(out)]


@pytest.mark.slow
def test_cli_fuzz_every_subcommand():
    counts = Counter()

    @settings(max_examples=400, deadline=None, derandomize=True, database=None,
              suppress_health_check=[HealthCheck.too_slow])
    @given(cases)
    def one(c):
        with tempfile.TemporaryDirectory() as tmp:
            d = Path(tmp)
            src = _make(c["kind"], d, c["name"], c["field"])
            out = d / f"out-{c['name']}"
            if c["out"] == "existing_folder":
                out.mkdir()
                (out / "keep.txt").write_text("old")
            elif c["out"] in ("file", "under_file"):
                out.write_text("a file")
                if c["out"] == "under_file":
                    out = out / "sub"
            before = sorted(p.name for p in d.iterdir())
            err, so = io.StringIO(), io.StringIO()
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(so):
                try:
                    status = main(_argv(c, src, out))
                except SystemExit as e:  # argparse's usage errors
                    status = e.code
            e = err.getvalue()
            counts[(c["cmd"], status)] += 1
            assert status in (0, 2, 130), (c, status, e[-2000:])
            assert "Traceback" not in e, (c, e[-2000:])
            if status == 2:
                # progress lines a log gets while a run goes (one per tenth) are not the message
                e = "".join(ln for ln in e.splitlines(keepends=True) if " s simulated (" not in ln)
                assert e.count("\n") == 1 and e.startswith("frictionnoise: "), (c, e)
                assert sorted(p.name for p in d.iterdir()) == before, (c, e)  # nothing new beside the inputs
                if c["out"] == "existing_folder":
                    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"], (c, e)

    one()
    total = sum(counts.values())
    print(f"\nCLI fuzz: {total} cases; by subcommand and exit status: "
          + ", ".join(f"{k[0]} {k[1]}: {v}" for k, v in sorted(counts.items(), key=str)))
    assert total >= 400
    assert {k[0] for k in counts} == {"run", "compare", "render", "sweep", "analyze", "report"}
    assert sum(v for k, v in counts.items() if k[1] == 0) >= 15 and any(k[1] == 2 for k in counts)
