"""``python -m anvilwave``: the command line."""

import sys

from anvilwave.cli import main

sys.exit(main())
