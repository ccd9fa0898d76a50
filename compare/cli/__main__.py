"""``python -m compare.cli``: the ``frictionnoise`` command line."""
import sys

from .main import main

sys.exit(main())
