"""Which ccdlab package the tests import: the build tree's (build/python/ccdlab), or, with CCDLAB_INSTALLED=1 (the
README's test command, experiments/scripts/test.sh), the one `pip install .` put in the running interpreter's
environment."""
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
if os.environ.get("CCDLAB_INSTALLED") != "1":
    sys.path.insert(0, str(ROOT / "build" / "python"))
