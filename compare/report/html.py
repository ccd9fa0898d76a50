"""Writers: study results to one self-contained HTML page, summary.json and figures/*.png.

Studies build their fragments with :func:`paragraphs` and :func:`table`; :func:`page` lays out the page (a
table of contents linking every section, numbered figure captions); :func:`write_report` writes the folder
atomically (a temporary folder renamed into place), so an interrupted run leaves no half-written report.
"""
from __future__ import annotations

import base64
import html
import json
import math
import re
from pathlib import Path

import numpy as np

__all__ = ["esc", "num", "fixed", "pct", "span", "rst_inline", "paragraphs", "table", "page", "verdict_table", "summary_of", "write_report", "json_text"]

esc = html.escape

_CSS = """body{font-family:system-ui,sans-serif;max-width:66rem;margin:2rem auto;padding:0 1rem;color:#222}
h1{font-size:1.5rem}h2{font-size:1.2rem;border-bottom:1px solid #ccc;margin-top:2rem}
nav{background:#f7f7f7;border:1px solid #ddd;padding:0.3rem 0.8rem;font-size:0.8rem}
nav ol{margin:0.2rem 0;columns:3;column-gap:1.5rem;padding-left:1.4rem}
table.summary{font-size:0.78rem;width:100%}table.summary td{padding:1px 5px;white-space:nowrap}
table.summary td:last-child{white-space:normal}
td.agree{background:#e3f4e3}td.disagree{background:#fbe3e3}td.none{background:#eee;color:#555}p.meta{font-size:0.85rem}
table{border-collapse:collapse;margin:0.6rem 0;font-size:0.9rem}td,th{border:1px solid #ccc;padding:2px 8px}
th{background:#f4f4f4}caption{text-align:left;white-space:nowrap;font-size:0.85rem;color:#555}
figure{margin:1rem 0}figcaption{font-size:0.85rem;color:#444}img{max-width:100%;height:auto}"""


def num(x, digits: int = 3) -> str:
    """The report's one number format: ``digits`` significant figures, plain decimals from 1e-3 to 1e5 (1570, not
    1.57e+03) and scientific outside (2.5e-07); NaN or None as "n/a"; never "-0"."""
    if x is None or not math.isfinite(x):
        return "n/a"
    if x == 0:
        return "0"
    if 1e-3 <= abs(x) < 1e5:
        text = f"{x:.{max(0, digits - 1 - math.floor(math.log10(abs(x))))}f}"
        return "0" if float(text) == 0 else text
    return f"{x:.{max(0, digits - 1)}e}"


def fixed(x: float, digits: int = 2, sign: bool = False) -> str:
    """``x`` with ``digits`` decimals ("+0.16" with ``sign``); a value that rounds to zero reads "0.00", never
    "-0.00" or "+0.00"."""
    text = f"{x:{'+' if sign else ''}.{digits}f}"
    return text.lstrip("+-") if float(text) == 0 else text


def pct(fraction, decimals: int = 3) -> str:
    """A fraction as a signed percentage, "+0.106 %"; one that rounds to zero at ``decimals`` reads "0 % (below
    0.001 %)" rather than "-0.000 %"."""
    if fraction is None or not math.isfinite(fraction):
        return "n/a"
    text = f"{100 * fraction:+.{decimals}f}"
    if float(text) == 0:
        return f"0 % (below {10 ** -decimals:g} %)"
    return text + " %"


def span(lo, hi, digits: int = 3) -> str:
    """A range "lo-hi" in the report's number format, both ends alike: "3.07-1570", and "1.79e-04-4.24e-03" when
    either end needs the scientific form."""
    ends = [x for x in (lo, hi) if x is not None and math.isfinite(x) and x != 0]
    if any(not 1e-3 <= abs(x) < 1e5 for x in ends):
        return "-".join(f"{x:.{max(0, digits - 1)}e}" if x in ends else num(x, digits) for x in (lo, hi))
    return f"{num(lo, digits)}-{num(hi, digits)}"


def rst_inline(text: str) -> str:
    """Docstring prose as HTML: escaped, with reST inline markup rendered (``code`` and :role:`target` as <code>,
    the ~ prefix dropping the module path) and line breaks joined."""
    out = esc(" ".join(text.split()))
    out = re.sub(r":[a-z]+:`~?([^`]+)`", lambda m: f"<code>{m.group(1).split('.')[-1] if m.group(0).count('~') else m.group(1)}</code>", out)
    return re.sub(r"``([^`]+)``", r"<code>\1</code>", out)


def paragraphs(items) -> str:
    """Paragraphs of prose (each already HTML: escape user text with :func:`esc`)."""
    return "\n".join(f"<p>{p}</p>" for p in items)


def table(caption: str, header: list, rows: list) -> str:
    """A captioned table; header and caption are escaped, cells are HTML."""
    out = [f"<table><caption>{esc(caption)}</caption><tr>" + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>"]
    out += ["<tr>" + "".join(f"<td>{c}</td>" for c in row) + "</tr>" for row in rows]
    out.append("</table>")
    return "\n".join(out)


def _anchor(key: str) -> str:
    return "s-" + re.sub(r"[^A-Za-z0-9_-]+", "-", key)


def _verdict_cell(v) -> str:
    cls = {True: "agree", False: "disagree", None: "none"}[v.agree]
    note = getattr(v, "note", "")
    return f"<td class='{cls}'>{esc(v.word)}{'<br>' + esc(note) if note else ''}</td>"


def verdict_table(results) -> str:
    """The summary table: one row per verdict of every study, linked to its section ("" when there are none)."""
    rows = []
    for r in results:
        for v in getattr(r, "verdicts", ()):
            name = esc(v.study.split("/")[-1])
            link = f"<a href='#{_anchor(r.key)}' title='{esc(r.title)}'>{name}</a>" if r.title else name
            rows.append(f"<tr><td>{link}</td><td>{v.what}</td><td>{v.measured}</td><td>{v.reference}</td>"
                        f"{_verdict_cell(v)}<td>{v.by}</td></tr>")
    if not rows:
        return ""
    head = "".join(f"<th>{h}</th>" for h in ("study", "compared", "measured (95 %)", "reference", "verdict", "by how much"))
    return ("<table id='summary' class='summary'><caption>Summary: each study's key number against its reference "
            "(no verdict where a fit is not a power law)</caption><tr>" + head + "</tr>" + "\n".join(rows) + "</table>")


def _header(header: dict) -> str:
    """The line under the title: version, seed (when the report has one), mode and conventions."""
    seed = header.get("seed")
    bits = [f"Version {esc(str(header.get('version', 'unknown')))}"]
    if seed is not None:
        bits.append(f"seed {esc(str(seed))}")
    if header.get("quick") and not header.get("all_scenes", True):
        bits.append("quick mode: the models and the scenes of the paper's three mechanisms, in shorter runs "
                    "(<code>--quick --all-scenes</code> adds every other shipped scene; the full report, without "
                    "<code>--quick</code>, runs them all at full length)")
    elif header.get("quick"):
        bits.append("quick mode (shorter runs)")
    return (f"<p class='meta'>{', '.join(bits)}. Spectra are two-sided in angular frequency (Xu, Zhou &amp; Persson "
            "2025, eq. 2); &plusmn; is a 95 % confidence half-width.</p>")


def page(results, header: dict, title: str = "frictionnoise report") -> str:
    """The HTML page of a list of StudyResult (numbers-only results, with an empty title, are left out): the
    title, the contents, the summary table of every study's verdicts, then the sections."""
    sections = [r for r in results if r.title]
    out = ["<!doctype html><html lang='en'><head><meta charset='utf-8'>",
           f"<title>{esc(title)}</title><style>{_CSS}</style></head><body>",
           f"<h1>{esc(title)}</h1>", _header(header)]
    if len(sections) > 1:
        out.append("<nav id='contents'><b>Contents</b><ol>"
                   + "".join(f"<li><a href='#{_anchor(r.key)}'>{esc(r.title)}</a></li>" for r in sections)
                   + "</ol></nav>")
    out.append(verdict_table(results))
    n = 0
    for r in sections:
        out.append(f"<section id='{_anchor(r.key)}'><h2>{esc(r.title)}</h2>")
        if r.html:
            out.append(r.html)
        for f in r.figures:
            n += 1
            b64 = base64.b64encode(f.png).decode()
            out.append(f"<figure id='fig-{n}'><img alt='Figure {n}: {esc(f.name)}' src='data:image/png;base64,{b64}'>"
                       f"<figcaption><b>Figure {n}.</b> {esc(f.caption)} (figures/{esc(f.name)}.png)</figcaption></figure>")
        out.append("</section>")
    out.append("</body></html>")
    return "\n".join(out)


def summary_of(results, header: dict) -> dict:
    """summary.json: the header, then each result's numbers under its key ("a/b" nests)."""
    summary = dict(header)
    verdicts = [v.to_dict() for r in results for v in getattr(r, "verdicts", ())]
    if verdicts:
        summary["verdicts"] = verdicts
    for r in results:
        *parents, leaf = r.key.split("/")
        d = summary
        for p in parents:
            d = d.setdefault(p, {})
        d[leaf] = r.numbers
    return summary


def _json_default(o):
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if hasattr(o, "__dataclass_fields__"):
        from dataclasses import asdict
        return asdict(o)
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def _finite(o):
    """``o`` with NaN and infinities as None: strict JSON has no NaN (a browser's JSON.parse refused the file)."""
    if isinstance(o, float):
        return o if math.isfinite(o) else None
    if isinstance(o, dict):
        return {k: _finite(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_finite(v) for v in o]
    return o


def json_text(obj, indent=2) -> str:
    """Strict JSON (NaN and infinities as null) with numpy scalars, arrays and dataclasses converted."""
    return json.dumps(_finite(json.loads(json.dumps(obj, default=_json_default))), indent=indent, allow_nan=False)


def write_report(out_dir, results, summary: dict, title: str = "frictionnoise report") -> Path:
    """Write index.html, summary.json and figures/*.png into ``out_dir`` atomically."""
    from ..io.outputs import atomic_folder

    with atomic_folder(out_dir) as tmp:
        (tmp / "figures").mkdir()
        for r in results:
            for f in r.figures:
                (tmp / "figures" / f"{f.name}.png").write_bytes(f.png)
        (tmp / "summary.json").write_text(json_text(summary))
        (tmp / "index.html").write_text(page(results, summary, title))
    return Path(out_dir).resolve()
