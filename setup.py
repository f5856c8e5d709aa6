"""Optional compiled build (like black's): ``GCLINT_USE_MYPYC=1`` compiles the hot modules with mypyc.

    pip install "mypy>=1.8" && GCLINT_USE_MYPYC=1 pip install --no-build-isolation .

The compiled modules are the same source files (typed Python); without the variable gclint installs as
pure Python, which is the default and what the tests use.  bench/bench_check.py reports both builds.
"""

import os

from setuptools import setup

# The per-line hot path: parsing, the tree, the machine state, the engine loop.  Rules stay
# interpreted (third-party rules subclass them).
HOT_MODULES = [
    "gclint/syntax/nodes.py",
    "gclint/syntax/fastpath.py",
    "gclint/syntax/build.py",
    "gclint/syntax/parse.py",
    "gclint/machine/state.py",
    "gclint/machine/interpreter.py",
    "gclint/engine.py",
]

ext_modules = []
if os.environ.get("GCLINT_USE_MYPYC") == "1":
    from mypyc.build import mypycify

    ext_modules = mypycify(["--ignore-missing-imports", "--follow-imports=silent", *HOT_MODULES], opt_level="3")

setup(ext_modules=ext_modules)
