"""ccdlab: continuous collision detection and proximity queries for deforming triangle meshes.

Every function takes NumPy array-likes (positions N×3, faces F×3) and the pipeline's settings by keyword
(ccdlab.settings() lists them: k, threads, tester, …); a bad argument raises ccdlab.Error (a ValueError) that names
the call and the argument.
Guide: docs/python.md; the proximity query: docs/proximity.md.
"""
from ._ccdlab import (Detector, Error, __version__, active_set_and_step, earliest_toi, proximity, schedulers, sequence,
                      settings, step, testers, validate)

Error.__module__ = __name__  # shown as ccdlab.Error, not as the extension's inner name

__all__ = ["Detector", "Error", "__version__", "active_set_and_step", "earliest_toi", "proximity", "schedulers",
           "sequence", "settings", "step", "testers", "validate"]
