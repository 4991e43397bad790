"""Not the Python module: this is the checkout's C++ source folder `roving/`, which `import roving`
finds first when Python runs from the checkout's root. It hands over to the real module: the one
on sys.path beyond this checkout (PYTHONPATH, an installed package), else this checkout's build.
"""
import importlib.machinery
import importlib.util
import os
import sys

_checkout = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_places = [p for p in sys.path if os.path.abspath(p or os.curdir) != _checkout]
_places.append(os.path.join(_checkout, "build", "python"))
_spec = importlib.machinery.PathFinder.find_spec(__name__, _places)
if _spec is None or _spec.loader is None:
    raise ImportError("roving: the Python module is neither installed nor built: run "
                      "'bash scripts/build.sh' in " + _checkout + " (it makes build/python), or install "
                      "the Debian package (docs/library.md)")
_module = importlib.util.module_from_spec(_spec)
sys.modules[__name__] = _module
_spec.loader.exec_module(_module)
