"""The ``frictionnoise`` command line: :mod:`.parser` declares it, :mod:`.main` runs it, :mod:`.commands` does
what each subcommand does, :mod:`.progress` and :mod:`.compile_notice` report on the terminal."""
from .main import main

__all__ = ["main"]
