"""Write SpringDamperDemo.csv with two more columns, ``body.a[1]`` and
``body.a[2]``: the body's acceleration by Newton's law from Dymola's own
positions and velocities (``python tests/data/references/add_accelerations.py
out/SpringDamperDemo_a.csv``).

The model (see ``models/planar_examples.py``): a free body m = 0.5 kg on a
world-axis spring-damper (c = 5 N/m, d = 1 N s/m per axis) from
A = (-1, 0) under gravity g = 9.81 m/s^2, so

    a = (-c (r - A) - d v) / m + (0, -g).

Nothing of acausal2d is used: the columns are an independent reference for
the accelerations a run reports as ``body.ax``, ``body.ay``."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "SpringDamperDemo.csv")
M, C, D, G, AX, AY = 0.5, 5.0, 1.0, 9.81, -1.0, 0.0


def with_accelerations(lines):
    """The CSV lines (Dymola format) with body.a[1], body.a[2] appended."""
    head = [h.strip('"') for h in lines[0].split(",")]
    k = {name: j for j, name in enumerate(head)}
    out = [lines[0] + ',"body.a[1]","body.a[2]"']
    for line in lines[1:]:
        v = [float(x) for x in line.split(",")]
        ax = (-C * (v[k["body.r[1]"]] - AX) - D * v[k["body.v[1]"]]) / M
        ay = (-C * (v[k["body.r[2]"]] - AY) - D * v[k["body.v[2]"]]) / M - G
        out.append("%s,%.17g,%.17g" % (line, ax, ay))
    return out


def main(target):
    with open(SOURCE, encoding="utf-8") as fh:
        lines = [ln for ln in fh.read().splitlines() if ln.strip()]
    folder = os.path.dirname(os.path.abspath(target))
    os.makedirs(folder, exist_ok=True)
    with open(target, "w", encoding="utf-8") as fh:
        fh.write("\n".join(with_accelerations(lines)) + "\n")
    return target


if __name__ == "__main__":
    print(main(sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "SpringDamperDemo_a.csv")))
