"""``python -m archrock.cli``: same as the ``archrock`` command."""

import sys

from . import main

sys.exit(main())
