"""Instrument files written the way rigs write them, made here from seeded numbers (no third party's data): each
generator returns the bytes and the numbers it wrote, so a reader's values are checked against the generator.

- :func:`umt_export`: a CETR/Bruker UMT export: a 20-line preamble of run and step blocks, the header
  ``Fx,Fz,Z,Y,X,V1,V2,V3,T,Ff,COF``, the units row ``g,g,mm,mm,mm,mm/sec,mm/sec,mm/sec,sec,g,`` with its trailing
  comma (COF has no unit), a blank line, the data, then "Step No. 2" with its own block; CRLF ends.
- :func:`look_ascii`: the look program's ASCII export (xlook): ``number of records = N``, name, units and recs
  rows, whitespace-separated data.
- :func:`stroke_files`: one file per stroke, as the UMT also writes.
- :func:`xlsx_book`, :func:`tdms_file`: a workbook and a LabVIEW TDMS file of the same table (openpyxl, npTDMS).
"""
from __future__ import annotations

import numpy as np

UMT_HEADER = "Fx,Fz,Z,Y,X,V1,V2,V3,T,Ff,COF"
UMT_UNITS = "g,g,mm,mm,mm,mm/sec,mm/sec,mm/sec,sec,g,"


def _umt_rows(n, t0, seed, load_g=1000.0, mu=0.3):
    """Rows of one step: a reciprocating stroke at 100 Hz, friction with seeded noise, as the export rounds them."""
    rng = np.random.default_rng(seed)
    T = t0 + 0.01 * np.arange(n)
    X = 2.0 * np.sin(2 * np.pi * 0.1 * (T - t0))
    V = 2.0 * np.pi * 0.1 * 2.0 * np.cos(2 * np.pi * 0.1 * (T - t0))
    Fz = -load_g * (1 + 0.01 * rng.standard_normal(n))
    Ff = np.sign(V) * mu * load_g * (1 + 0.05 * rng.standard_normal(n))
    Fx = Ff + 0.5 * rng.standard_normal(n)
    cof = Ff / Fz
    rows, vals = [], {"T": [], "Ff": [], "Fz": [], "COF": []}
    for i in range(n):
        cells = [f"{Fx[i]:.3f}", f"{Fz[i]:.3f}", "0.000", "0.000", f"{X[i]:.4f}", "0.0000", "0.0000",
                 f"{V[i]:.4f}", f"{T[i]:.3f}", f"{Ff[i]:.3f}", f"{cof[i]:.5f}"]
        rows.append(",".join(cells))
        for k, c in (("T", cells[8]), ("Ff", cells[9]), ("Fz", cells[1]), ("COF", cells[10])):
            vals[k].append(float(c))
    return rows, {k: np.array(v) for k, v in vals.items()}


def umt_export(n1=6000, n2=5000, pause_s=3.0, seed=11):
    """(bytes, {column: values as written}, {"step2_line": line of step 2's first data row, "header_line": ...})."""
    pre = ["Data File,frictionnoise synthetic UMT export", "Instrument,UMT (synthetic test file)", "Date,11/25/2026",
           "Time,10:30:00 AM", "Operator,test generator", "Sample,steel ball on PTFE", "Run No. 1",
           "Run Name,reciprocating", "Load Sensor,FVL 10 kg", "Sampling Rate,100 Hz", "Number of Steps,2", "",
           "Step No. 1", "Step Name,Reciprocating 1 kg", "Step Duration,60 sec", "Stroke,4 mm", "Frequency,0.1 Hz",
           "Load,1000 g", "Step Start,0 sec", "Step Data"]
    assert len(pre) == 20
    r1, v1 = _umt_rows(n1, 0.0, seed)
    t2 = v1["T"][-1] + pause_s
    r2, v2 = _umt_rows(n2, t2, seed + 1, load_g=2000.0)
    step2 = ["Step No. 2", "Step Name,Reciprocating 2 kg", "Step Duration,50 sec", "Load,2000 g", "Step Data"]
    lines = pre + [UMT_HEADER, UMT_UNITS, ""] + r1 + step2 + [UMT_HEADER, UMT_UNITS, ""] + r2 + [""]
    vals = {k: np.concatenate([v1[k], v2[k]]) for k in v1}
    where = {"header_line": 21, "first_data_line": 24, "step2_line": 24 + n1 + len(step2) + 3}
    return "\r\n".join(lines).encode("latin-1"), vals, where


def look_ascii(n=400, seed=5):
    """(bytes, {name: values as written}): a look ASCII export of a rock-friction run (time, load-point
    displacement, shear and normal stress)."""
    rng = np.random.default_rng(seed)
    t = 0.1 * np.arange(n)
    lp = 10.0 * t
    tau = 5.0 + 0.05 * np.cumsum(rng.standard_normal(n)) * 0.1
    sn = 10.0 + 0.01 * rng.standard_normal(n)
    cols = {"Time": t, "LP_Disp": lp, "Shr_stress": tau, "Nor_stress": sn}
    written = {k: np.array([float(f"{v:.6g}") for v in c]) for k, c in cols.items()}
    lines = ["begin", f"number of records = {n}", "name: " + "\t".join(cols), "units: s\tum\tMPa\tMPa",
             "recs: " + "\t".join(str(n) for _ in cols)]
    lines += ["\t".join(f"{written[k][i]:.6g}" for k in cols) for i in range(n)]
    return ("\n".join(lines) + "\n").encode(), written


def stroke_files(folder, strokes=4, n=200, seed=9):
    """One CSV per stroke (stroke_001.csv, ...), time running on; returns {column: values as written}."""
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    out = {"t": [], "F": []}
    for k in range(strokes):
        t = (k * n + np.arange(n)) * 0.01
        F = (1 if k % 2 == 0 else -1) * (2.0 + 0.1 * rng.standard_normal(n))
        rows = [f"{a:.2f},{b:.5f}" for a, b in zip(t, F)]
        (folder / f"stroke_{k + 1:03d}.csv").write_text("Stroke " + str(k + 1) + "\ntime (s),Ff (N)\n"
                                                        + "\n".join(rows) + "\n")
        out["t"] += [float(r.split(",")[0]) for r in rows]
        out["F"] += [float(r.split(",")[1]) for r in rows]
    return {k: np.array(v) for k, v in out.items()}


def _table(n=300, seed=4):
    rng = np.random.default_rng(seed)
    t = 0.002 * np.arange(n)
    return t, 0.5 + 0.02 * rng.standard_normal(n), 1.0 + 0.01 * rng.standard_normal(n)


def xlsx_book(path, n=300, seed=4, bad_cell=None):
    """A workbook: a title row, a header row with units, the data (numbers as cells); returns the columns."""
    import openpyxl

    t, F, N = _table(n, seed)
    wb = openpyxl.Workbook()
    ws = wb.active
    ws.title = "Run 1"
    ws.append(["Friction test (synthetic)"])
    ws.append(["time (s)", "Ff (N)", "Fn (N)"])
    for a, b, c in zip(t, F, N):
        ws.append([float(a), float(b), float(c)])
    if bad_cell is not None:
        ws[bad_cell] = "n/a"
    wb.save(path)
    return {"t": t, "F": F, "N": N}


def tdms_file(path, n=300, seed=4):
    """A TDMS file: one group, waveform channels (wf_increment 2 ms) with unit_string properties."""
    from nptdms import ChannelObject, GroupObject, RootObject, TdmsWriter

    t, F, N = _table(n, seed)
    props = {"wf_increment": 0.002, "wf_start_offset": 0.0}
    with TdmsWriter(str(path)) as w:
        w.write_segment([RootObject({}), GroupObject("Friction", {}),
                         ChannelObject("Friction", "Ff", F, dict(props, unit_string="N")),
                         ChannelObject("Friction", "Fn", N, dict(props, unit_string="N"))])
    return {"t": t, "F": F, "N": N}


def dektak_export(n=12821, with_resolution=True, rows=None, seed=2026):
    """A Dektak-like stylus export: a preamble of scan parameters (the spacing as ``Resolution,0.156,um/pt``
    unless ``with_resolution`` is False), the header ``Lateral um,Raw Micrometer``, positions rounded to 0.1 um
    (so the median step of the positions as written is 0.2 um, the scan's 0.156 um), CR CR LF line ends. Returns
    (bytes, heights in um as written). ``rows`` replaces the data rows as written."""
    from tests.stylus_export import stylus_heights

    h = 1e6 * stylus_heights(n, seed=seed)
    x = 0.156 * np.arange(n)
    pre = ["Dektak-like export (frictionnoise synthetic test file)", "Scan Length,2000.0,um", "Scan Duration,60,s",
           f"Data Points,{n}", "Stylus Type,Radius: 2.0 um"] + (["Resolution,0.156,um/pt"] if with_resolution else [])
    data = rows if rows is not None else [f"{a:.1f},{b:.4f}" for a, b in zip(x, h)]
    written = np.array([float(r.split(",")[1]) for r in data]) if rows is None else None
    return "\r\r\n".join(pre + ["", "Lateral um,Raw Micrometer"] + data + [""]).encode("latin-1"), written
