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

__all__ = ["esc", "paragraphs", "table", "page", "summary_of", "write_report", "json_text"]

esc = html.escape

_CSS = """body{font-family:system-ui,sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;color:#222}
h1{font-size:1.5rem}h2{font-size:1.2rem;border-bottom:1px solid #ccc;margin-top:2rem}
nav{background:#f7f7f7;border:1px solid #ddd;padding:0.4rem 1rem;font-size:0.9rem}nav ol{margin:0.3rem 0}
table{border-collapse:collapse;margin:0.6rem 0;font-size:0.9rem}td,th{border:1px solid #ccc;padding:2px 8px}
th{background:#f4f4f4}caption{text-align:left;white-space:nowrap;font-size:0.85rem;color:#555}
figure{margin:1rem 0}figcaption{font-size:0.85rem;color:#444}img{max-width:100%;height:auto}"""


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


def page(results, header: dict, title: str = "frictionnoise report") -> str:
    """The HTML page of a list of StudyResult (numbers-only results, with an empty title, are left out)."""
    sections = [r for r in results if r.title]
    out = ["<!doctype html><html lang='en'><head><meta charset='utf-8'>",
           f"<title>{esc(title)}</title><style>{_CSS}</style></head><body>",
           f"<h1>{esc(title)}</h1>",
           f"<p>Version {esc(str(header.get('version', '-')))}, seed {esc(str(header.get('seed', '-')))}"
           f"{', quick mode (shorter runs)' if header.get('quick') else ''}. Spectra are two-sided in angular "
           "frequency (Xu, Zhou &amp; Persson 2025, eq. 2); exponent uncertainties are 95 % confidence half-widths.</p>"]
    if len(sections) > 1:
        out.append("<nav id='contents'><b>Contents</b><ol>"
                   + "".join(f"<li><a href='#{_anchor(r.key)}'>{esc(r.title)}</a></li>" for r in sections)
                   + "</ol></nav>")
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
