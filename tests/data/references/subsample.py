"""Regenerate the subsampled reference files of this folder from the full
Dymola results (``python tests/data/references/subsample.py
../shared/references``): every 7th data row is kept verbatim, and every row
whose time repeats (event and end rows), so the files keep Dymola's format.
The tests and the README read only the files here, never the full set."""
import os
import sys

FILES = ("Pendulum.csv", "DoublePendulum.csv", "CraneCrab.csv", "PistonEngine.csv",
         "PistonEngine_DynamicStateSelection.csv", "SpringDamperDemo.csv")
EVERY = 7


def subsample(lines, every=EVERY):
    """Header, every ``every``-th data row, and all rows of repeated times."""
    header, rows = lines[0], [ln for ln in lines[1:] if ln.strip()]
    times = [ln.split(",", 1)[0] for ln in rows]
    keep = [k for k in range(len(rows))
            if k % every == 0 or k == len(rows) - 1
            or (k > 0 and times[k] == times[k - 1])
            or (k + 1 < len(rows) and times[k] == times[k + 1])]
    return [header] + [rows[k] for k in keep]


def main(source):
    here = os.path.dirname(os.path.abspath(__file__))
    for name in FILES:
        with open(os.path.join(source, name)) as fh:
            lines = fh.read().splitlines()
        with open(os.path.join(here, name), "w") as fh:
            fh.write("\n".join(subsample(lines)) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join("..", "shared", "references"))
