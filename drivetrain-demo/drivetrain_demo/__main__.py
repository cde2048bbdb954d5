"""Entry point: python -m drivetrain_demo ..."""

import sys

from .cli import main

sys.exit(main())
