"""The ``frictionnoise`` argument parser: a declarative table of the subcommands, their options and help."""
from __future__ import annotations

import argparse
import difflib
import re

from .commands import cmd_analyze, cmd_compare, cmd_render, cmd_report, cmd_run, cmd_sweep
from .shipped import cmd_scenarios

__all__ = ["Parser", "build_parser"]


class Parser(argparse.ArgumentParser):
    """argparse's usage errors as one line too (exit 2), like every other user error; a mistyped command or choice
    gets the closest valid one suggested."""

    def error(self, message):
        m = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)", message)
        if m:
            close = difflib.get_close_matches(m.group(1), re.findall(r"'([^']*)'", m.group(2)), n=1)
            if close:
                message += f"; did you mean {close[0]!r}?"
        m = re.match(r"unrecognized arguments: (--?[\w-]+)", message)
        if m:
            options = [o for a in self._actions for o in a.option_strings if o.startswith("--")]
            close = difflib.get_close_matches(m.group(1), options, n=1)
            if close:
                message += f"; did you mean {close[0]!r}?"
        where = "" if self.prog == "frictionnoise" else f"{self.prog}: "
        self.exit(2, f"frictionnoise: error: {where}{message} (see {self.prog} --help)\n")

    def parse_args(self, args=None, namespace=None):
        """As argparse's, with an unknown option reported by the subcommand it was given to (its help named, the
        closest of its options suggested) rather than by the top-level parser."""
        ns, extra = self.parse_known_args(args, namespace)
        if extra:
            command = getattr(ns, "command", None)
            subs = [a for a in self._actions if isinstance(a, argparse._SubParsersAction)]
            owner = subs[0].choices.get(command, self) if subs and command else self
            owner.error("unrecognized arguments: " + " ".join(extra))
        return ns



def _micro(unit: str) -> str:
    """A unit as typed, with the micro sign (µ, U+00B5, or the Greek mu, U+03BC) read as "u", as files write it."""
    return unit.replace("\u00b5", "u").replace("\u03bc", "u")

def build_parser() -> argparse.ArgumentParser:
    from frictionnoise.base import package_version  # the leaf package: no numerics imported to build the parser

    ap = Parser(
        prog="frictionnoise",
        description="Displacement noise of sliding friction: reduced models, scenes and spectra.",
        epilog="Seeds: report, run, compare and render take --seed K (the same seed gives the same numbers, bit for "
               "bit); a sweep's seeds are the grid axis `seed` of its file; analyze draws no random numbers. "
               "Every -o names a folder the command writes its files into (a name ending in a file suffix such as "
               ".npz or .png is refused). `frictionnoise COMMAND --help` describes a command.",
    )
    ap.add_argument("--version", action="version", version=f"frictionnoise {package_version()}")
    sub = ap.add_subparsers(dest="command", metavar="COMMAND")

    def add(name, summary):
        """A subcommand whose help line and description are the same one-line summary."""
        return sub.add_parser(name, help=summary, description=summary[0].upper() + summary[1:] + ".")

    rep = add("report", "the main job: the paper's model figures, every shipped scene against its reduced model, "
                        "fits and timings, as an HTML report with summary.json")
    rep.add_argument("-o", "--output", default="frictionnoise-report",
                     help="output folder for index.html, summary.json and figures/ (default: %(default)s)")
    rep.add_argument("--quick", action="store_true",
                     help="the models and three scenes (pads_friction_patches, pads_with_wear, asperity_field) in "
                          "shorter runs: about 2 min on 2 cores; the full report runs every scene (about 3 min)")
    rep.add_argument("--all-scenes", action="store_true",
                     help="with --quick: every shipped scene at its quick length (about 70 s on 2 cores)")
    rep.add_argument("--seed", type=int, default=0,
                     help="random seed of every model and scene run (default: %(default)s); same seed, same numbers")
    rep.add_argument("--workers", type=int, default=None, metavar="N",
                     help="run the report's stages in N processes (default: the usable cores, at most 4; 1: in this "
                          "process); the numbers do not depend on it")
    rep.set_defaults(func=cmd_report)

    run = add("run", "run a scenario and write its trace (.npz arrays in SI units + .json metadata)")
    run.add_argument("scenario", help="scenario TOML file or shipped name (see `frictionnoise scenarios`)")
    run.add_argument("-o", "--output", default=None, metavar="DIR",
                     help="output folder, created if needed: the run writes DIR/trace.npz and DIR/trace.json (a name "
                          "ending in a file suffix such as .npz is refused; default: run-<scenario name>)")
    run.add_argument("--duration", type=float, default=None, help="simulated seconds (default: the scenario's)")
    run.add_argument("--seed", type=int, default=None,
                     help="random seed of the substrate and the scene (default: the scenario's [run] seed)")
    run.add_argument("--checkpoint-every", type=float, default=None, metavar="S",
                     help="checkpoint to DIR/checkpoint.pkl about every S simulated seconds (rounded to whole epochs, "
                          "at least one); rerunning the same command resumes from it, bit for bit")
    run.add_argument("--epoch", type=float, default=None, metavar="S",
                     help="simulated seconds between the run's state round trips (default: the scene's, chosen so "
                          "they cost at most 5 %% of the stepping); part of the run's definition, like --seed")
    run.set_defaults(func=cmd_run)

    cmp_ = add("compare", "report one scene (scenario TOML or trace .npz) against the reduced model that fits it, or "
                          "one registered reduced model (model_I, model_Ib, ...) against its closed form")
    cmp_.add_argument("source", help="scenario TOML file, shipped name, trace .npz written by `frictionnoise run`, or "
                                     "the name of a registered reduced model")
    cmp_.add_argument("-o", "--output", default=None, metavar="DIR",
                      help="output folder for index.html, summary.json and figures/ (default: compare-<name>)")
    cmp_.add_argument("--duration", type=float, default=None, help="simulated seconds when running a scenario or a model (default: its own)")
    cmp_.add_argument("--seed", type=int, default=None,
                      help="random seed of the scene run and of the reduced model's run (default: the scenario's)")
    cmp_.add_argument("--band", type=float, nargs=2, default=None, metavar=("LO", "HI"),
                      help="fit band (rad/s) of a scene compared with model I, instead of 3-30 v/a (a scan shorter "
                           "than the renewal length, a short trace)")
    cmp_.set_defaults(func=cmd_compare)

    ren = add("render", "render a scenario headless to PNG frames (and an animated GIF)")
    ren.add_argument("scenario", help="scenario TOML file or shipped name")
    ren.add_argument("-o", "--output", default=None, metavar="DIR",
                     help="output folder for frame_000.png, ... and animation.gif (default: render-<scenario name>)")
    ren.add_argument("--frames", type=int, default=12, help="number of frames (default: %(default)s)")
    ren.add_argument("--duration", type=float, default=0.6, help="simulated seconds spanned (default: %(default)s)")
    ren.add_argument("--gif", action="store_true", help="also write animation.gif")
    ren.add_argument("--view", choices=("side", "tracks"), default="side",
                     help="side: the block on its spring-mounted pads over the substrate, its vertical exaggeration "
                          "printed (default); tracks: every pad's track as a map, coloured by friction")
    ren.add_argument("--seed", type=int, default=None,
                     help="random seed of the substrate and the scene (default: the scenario's [run] seed)")
    ren.set_defaults(func=cmd_render)

    sw = add("sweep", "run a parameter grid (dask LocalCluster by default; seeds are a grid axis of the sweep "
                      "file) and its report")
    sw.add_argument("sweep", help="sweep TOML file")
    sw.add_argument("-o", "--output", default=None, help="output folder, also the task cache (default: sweep-<name>)")
    sw.add_argument("--scheduler", default=None, help="address of a running dask scheduler, e.g. tcp://host:8786")
    sw.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default: %(default)s)")
    sw.add_argument("--serial", action="store_true", help="run in this process, without dask")
    sw.add_argument("--connect-timeout", type=float, default=10.0, metavar="S",
                    help="give up on --scheduler after S seconds (default: %(default)s)")
    sw.set_defaults(func=cmd_sweep)

    lst = add("scenarios", "list the shipped scenarios (run one by name: frictionnoise run NAME); with a NAME, print "
                           "that shipped file, or copy it with --copy DEST (a starting point of your own)")
    lst.add_argument("name", nargs="?", default=None,
                     help="a shipped scene (tilted_plane), sweep (sweeps/velocity_model1) or data file "
                          "(data/model1_synthetic_um.csv); a leading scenarios/ is allowed, as the docs write them")
    lst.add_argument("--copy", metavar="DEST", default=None,
                     help="write the shipped file NAME to DEST (a folder, or a new file's path) instead of printing it; "
                          "never overwrites")
    lst.add_argument("--all", action="store_true",
                     help="list every shipped file: the scenes, then the sweeps, example data and profiles")
    lst.set_defaults(func=cmd_scenarios)

    an = add("analyze", "analyse measured x(t) or friction force F(t) from a text export: spectra, exponent, rms and a "
                        "report (deterministic: no random numbers, so no --seed)")
    an.add_argument("data", nargs="+",
                    help="text table (CSV, ;- or tab-separated; preamble, units row and decimal commas are read): "
                         "time and displacement or force columns. Several displacement files (e.g. one per sliding "
                         "speed) are each analysed and compared as a velocity series: C_x at one omega against v, its "
                         "exponent, the collapse in q = omega / v and model I's level alpha^2/(N a)")
    an.add_argument("--mass", type=float, default=None,
                    help="block mass M (kg), optional: with displacement data it adds C_F = M^2 omega^4 C_x (eq. 3) "
                         "and the force exponent (gamma, C_x, C_mu and the velocity need no mass); with force data "
                         "it adds the equivalent C_x of a free block")
    an.add_argument("--time-col", default=None, help="time column name (default: the first)")
    an.add_argument("--x-col", default=None, help="displacement column name (default: the second, unless --force-col)")
    an.add_argument("--force-col", default=None, help="friction-force column: analyse force data (C_F, force exponent)")
    an.add_argument("--normal-col", default=None, help="normal-force column (force data): adds C_mu of F/N")
    an.add_argument("--direction-col", default=None, help="direction column of a reciprocating test (strokes)")
    an.add_argument("--mu-col", default=None,
                    help="friction-coefficient column (force data): analysed as mu (C_mu) instead of F/N")
    an.add_argument("--time-unit", default=None, type=_micro,
                    help="time unit (s, ms, min, ...), when neither the header nor a units row names it; a unit the "
                         "file states and a different one given here is an error")
    an.add_argument("--x-unit", default=None, type=_micro,
                    help="displacement unit (nm, um, mm, m, in, ...), when neither the header (x_um, x [mm]) nor a "
                         "units row names it")
    an.add_argument("--force-unit", default=None,
                    help="force unit (N, mN, kN, gf, kip, ...; a mass unit such as g is read as its weight), when "
                         "neither the header (F(N)) nor a units row names it")
    an.add_argument("--contact-area", type=float, default=None, metavar="M2",
                    help="contact area (m^2) that turns a stress column (MPa, ...) into a force; without it a stress "
                         "is refused")
    an.add_argument("--speed", type=float, default=None, metavar="V",
                    help="imposed sliding speed (m/s): for force data the distance-domain spectrum and stroke "
                         "length; for displacement the speed the mechanisms' families use (default: the record's mean "
                         "speed, from its ends)")
    an.add_argument("--cut", type=float, default=None, metavar="S",
                    help="seconds cut at each end of a stroke (default: 10 %% of the median stroke)")
    an.add_argument("--method", default=None, choices=["record", "whittle", "lsq"],
                    help="exponent fit: record (the power law plus a white floor fitted to the whole record by the "
                         "debiased Whittle likelihood; the default for displacement; force data of one stroke with "
                         "unbroken time stamps, a constant-velocity rig: fitted through the force's running sum; "
                         "displacement in uniform pieces: fitted to the longest piece, by default when it holds 3/4 "
                         "of the samples), whittle (the Whittle likelihood over a band of the stroke-averaged Welch "
                         "spectrum; the default for force data) or lsq (least squares on the log-binned spectrum; "
                         "the default for displacement in pieces none of which holds 3/4 of the samples)")
    an.add_argument("--band", type=float, nargs=2, default=None, metavar=("LO", "HI"),
                    help="fit band (rad/s); default (record): searched over every Fourier frequency, the band with the "
                         "most frequencies where one power law holds, ended where a white floor takes over; default "
                         "(whittle, lsq): "
                         "the straightest stretch of a decade between four Welch frequency steps and a sixteenth of "
                         "the Nyquist frequency, or all of that range, flagged, when it spans less (a record under "
                         "about 32768 samples); printed with the fit")
    an.add_argument("--resample", type=float, default=None, metavar="DT",
                    help="time stamps that change rate, skip, repeat or step back: put the record on one grid of DT "
                         "seconds (faster segments low-passed first; the filter is stated) instead of analysing its "
                         "uniform segments separately and together")
    an.add_argument("--omega", type=float, default=None, metavar="W",
                    help="several files: the angular frequency (rad/s) at which C_x is compared across speeds "
                         "(default: inside the band common to every record's fit band, where the least precise "
                         "record's level is most precise)")
    an.add_argument("--discrete", action="store_true",
                    help="displacement data of a discrete-time process (a simulation's cumulative sum of random steps): "
                         "fit the power law's discrete form (2 sin(omega dt/2)/dt)^-gamma, not the continuous law "
                         "folded at Nyquist that a sampled measurement follows (default)")
    an.add_argument("--no-mechanisms", action="store_true",
                    help="displacement data: skip the mechanism ranking (every registered model's family fitted; "
                         "most of analyze's time on a long record) and report the exponent, floor and spectra only")
    an.add_argument("-o", "--output", default=None, help="output folder (default: analyze-<file stem>; several files: analyze-series-<first stem>)")
    an.set_defaults(func=cmd_analyze)
    return ap
