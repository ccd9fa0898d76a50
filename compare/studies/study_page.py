"""A study's page: the one way a study writes its markdown (the machine's load while it measured stated at the
end, the folder made, the page written and printed)."""
from __future__ import annotations

import os
from pathlib import Path


def load_line() -> str:
    """The machine's load as a page states it: the 1-minute load average over the machine's cores."""
    return f"Machine load while measured: {os.getloadavg()[0]:.2f} (1-min average, {os.cpu_count()} cores)."


def write_page(path, lines: list, *, load: bool = True) -> Path:
    """Write the page ``lines`` (markdown, one string a line; blank lines at their end dropped) to ``path``, with
    the load line at the end when ``load``, and a final newline; make the folder; print the page. Returns the
    path."""
    lines = list(lines)
    while lines and not lines[-1]:
        lines.pop()
    lines += ["", load_line(), ""] if load else [""]
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    text = "\n".join(lines)
    path.write_text(text)
    print(text)
    return path
