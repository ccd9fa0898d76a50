"""The `frictionnoise` command line. User errors print one line and exit 2; no tracebacks."""
from __future__ import annotations

import argparse
import sys

__all__ = ["main"]


class UserError(Exception):
    """An error in the user's input: printed as one line, exit status 2."""


def _build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="frictionnoise",
        description="Displacement noise of sliding friction: reduced models, scenes and spectra.",
    )
    ap.add_subparsers(dest="command", metavar="COMMAND")
    return ap


def main(argv=None) -> int:
    ap = _build_parser()
    args = ap.parse_args(argv)
    if args.command is None:
        ap.print_help()
        return 0
    try:
        return args.func(args)
    except UserError as e:
        print(f"frictionnoise: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
