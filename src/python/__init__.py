# The package diffray: the extension _diffray (C++, pybind11) and the material library it reads.
from ._diffray import *  # noqa: F401,F403
from ._diffray import __all__, __doc__, __version__  # noqa: F401
