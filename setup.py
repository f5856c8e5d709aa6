"""The build step pyproject.toml cannot say: the rule reference goes into the package.

``docs/rules.md`` (generated from the rules by scripts/gen_rules_doc.py) is copied to
``gclint/_docs/rules.md`` in the built package, so that the links to a rule's documentation (the
language server's diagnostics, SARIF's ``helpUri``: gclint.ruledocs) point into the installed gclint in
any install: a wheel, ``pip install .``, ``pip install ./gclint``.  An editable install links to the
source folder's ``docs/rules.md`` instead (nothing is copied).  MANIFEST.in puts the file in sdists.

(A mypyc-compiled build used to be offered here; it failed mypy's type checks and was never tested, so
it was removed; the pure-Python install is the one the tests and benchmarks measure.)
"""

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

RULES_DOC = Path(__file__).resolve().parent / "docs" / "rules.md"


class BuildWithRuleDocs(build_py):
    def run(self):
        super().run()
        if getattr(self, "editable_mode", False) or not RULES_DOC.is_file():
            return
        target = Path(self.build_lib) / "gclint" / "_docs" / "rules.md"
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(RULES_DOC, target)


setup(cmdclass={"build_py": BuildWithRuleDocs})
