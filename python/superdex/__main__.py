"""`python -m superdex ...`: the `superdex` command (superdex/cli.py)."""

import sys

from superdex.cli import main

sys.exit(main())
