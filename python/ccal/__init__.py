"""Precision-centrifuge calibration of accelerometers: exact kinematics, identification of the coefficients,
and the error budget of the centrifuge's tolerances. Values are SI unless a name says otherwise (specific
force in g); display units are given alongside.

The compiled part is the private module ccal._ccal; the package re-exports its public names, with
signatures, the display view, pickling and repr added by the modules beside this file (docs/python.md)."""

from . import _ccal
from ._ccal import __commit__, __version__  # noqa: F401 (the git commit built from, or "unknown")
from ._install import install as _install_api
from ._pickling import restore_config as _restore_config, restore_result as _restore_result  # noqa: F401

_install_api(globals())
del _install_api
