"""``python -m massprops FILE... [options]``: what the ``massprops`` command does."""

import sys

from . import main

if __name__ == "__main__":
    sys.exit(main())
