"""The shipped "measured" CSVs of the calibration examples: synthetic
data, each a model run at known parameter values plus Gaussian noise of a
stated size from a seeded generator (so the fits can be checked against the
truth).  ``python models/measured_data.py`` writes them again.

==================================  =========================================================
file                                content
==================================  =========================================================
pulley_block_measured.csv           rope1.F, rope5.F of models/pulley_block.py with mu = 0.25
                                    on all four pulleys, t = 1 .. 5 s every 0.05 s, noise
                                    sigma = 2 N, numpy default_rng(2024)
belt_span_rig_measured.csv          span.F of models/belt_span_rig.py at c = 1.5e5 N,
                                    d = 150 N s, 201 times over 0.5 s, sigma = 3 N,
                                    default_rng(2026)
four_bar_precision_points.csv       six coupler points of models/four_bar_precision.py with
                                    crank 0.10, coupler 0.35, rocker 0.30 m (no noise)
==================================  =========================================================
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
PULLEY_MU, PULLEY_NOISE, PULLEY_SEED = 0.25, 2.0, 2024
PULLEY_CSV = os.path.join(HERE, "pulley_block_measured.csv")


def write_pulley_block(path=PULLEY_CSV):
    """Rope forces of the pulley block at mu = 0.25 plus noise (module docstring)."""
    import acausal2d
    cm = acausal2d.compile_model(acausal2d.load_model(os.path.join(HERE, "pulley_block.py")))
    t = np.round(np.arange(1.0, 5.0 + 1e-9, 0.05), 10)
    res = cm.simulate(params={p + ".mu": PULLEY_MU for p in ("U1", "L2", "U3", "L4")},
                      output_times=np.union1d([0.0], t), stop_time=5.0)
    rng = np.random.default_rng(PULLEY_SEED)
    cols = [np.interp(t, res.time, res[n]) + rng.normal(0.0, PULLEY_NOISE, t.size)
            for n in ("rope1.F", "rope5.F")]
    np.savetxt(path, np.column_stack([t] + cols), delimiter=",", comments="", fmt="%.10g",
               header="time,rope1.F,rope5.F")
    return path


def write_all():
    """Write the three CSVs; returns their paths."""
    sys.path.insert(0, HERE)
    import belt_span_rig
    import four_bar_precision
    return [write_pulley_block(), belt_span_rig.write_measured(), four_bar_precision.write_points()]


if __name__ == "__main__":
    print("\n".join(write_all()))
