"""The library is importable from the clone root (issue 34): after a plain
``pip install .`` the source folder ``acausal2d/`` shadows the installed
package when Python runs from the clone root, so ``acausal2d/library`` is a
link to the top-level ``library/`` of the design card."""
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# drop the editable install's finder: what remains is what a plain install sees from the clone root
SCRIPT = """
import sys
sys.meta_path = [f for f in sys.meta_path if 'editable' not in repr(f).lower()]
import acausal2d.library.planar, acausal2d.library.rotational
print(acausal2d.library.planar.__name__)
"""


def test_library_imports_from_the_clone_root_without_the_installed_package():
    proc = subprocess.run([sys.executable, "-c", SCRIPT], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "acausal2d.library.planar"


def test_the_link_points_at_the_top_level_library():
    link = os.path.join(ROOT, "acausal2d", "library")
    assert os.path.islink(link)
    assert os.path.samefile(link, os.path.join(ROOT, "library"))
