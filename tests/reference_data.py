"""The reference results the tests compare with, read from the subsampled
Dymola/PlanarMechanics files shipped in ``tests/data/references/`` (see the
README there), so the tests need nothing outside the repository.

``REFERENCES[name]`` is ``{"columns": [...], "rows": [(t, ...), ...]}`` with
the file's header as columns (``Time`` first) and its rows as float tuples.
"""
import csv
import os

REFERENCE_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "references")


def read_reference(name):
    """``{"columns", "rows"}`` of ``tests/data/references/<name>.csv``."""
    with open(os.path.join(REFERENCE_DIR, name + ".csv"), newline="") as fh:
        reader = csv.reader(fh)
        columns = [c.strip() for c in next(reader)]
        rows = [tuple(float(c) for c in row) for row in reader if row]
    return {"columns": columns, "rows": rows}


REFERENCES = {os.path.splitext(f)[0]: read_reference(os.path.splitext(f)[0])
              for f in sorted(os.listdir(REFERENCE_DIR)) if f.endswith(".csv")}
