"""Wall time of runs whose events could storm: each must end in seconds.

    python benchmarks/bench_events.py [repeats]     (default 5)
    python benchmarks/bench_events.py --small       (1 repeat, for the test suite)

- drive train, shared ramp: a constant torque on J1 -- Clutch -- J2 --
  Brake; one Ramp closes the clutch and, through Feedback (1 - ramp), opens
  the brake; 1 s at rtol 1e-8 (the brake's normal force 1 - ramp is solved
  as +-1e-32 where it is 0; Modelica Standard Library 4.0 semantics of
  PartialFriction).  Target: a few seconds (a run that once took minutes);
- Zeno ball: a ball bouncing with restitution 0.5, whose bounces
  accumulate at 1.3546 s; the run must stop there with an error.  Target:
  10 s;
- relay storm: a two-point switch with a hysteresis of 1e-7 (an event
  every 2e-7 s); the run must stop with an event-storm error.  Target: 10 s.
Each figure is compile + simulate, the median of ``repeats`` runs in this
process (the first run of a model pays for the compiler's imports).  The
models are those of tests/test_friction_modes.py (benchmarks/event_models.py).
"""
import statistics
import sys
import time

import acausal2d
from acausal2d.runtime.events import EventError
from event_models import Bouncing, RampedDrive, Switching


CASES = (("drive train, shared ramp (1 s)", RampedDrive, 1.0, None, 5.0),
         ("Zeno ball (stops at 1.35 s)", Bouncing, 3.0, "Zeno", 10.0),
         ("relay storm (stops at 1e-4 s)", Switching, 1.0, "event storm", 10.0))


def one(make, stop, error):
    """(seconds, events or the error's time) of compile + simulate."""
    t = time.perf_counter()
    try:
        res = acausal2d.compile_model(make()).simulate(stop_time=stop, rtol=1e-8)
        outcome = "%d events" % len(res.events)
        assert error is None, "the run should have stopped with an error"
    except EventError as err:
        assert error is not None and error in str(err), str(err)
        outcome = "stopped at t=%.4g" % err.time
    return time.perf_counter() - t, outcome


def main(repeats=5):
    print("Runs whose events could storm: compile + simulate, median of %d" % repeats)
    print("%-32s %10s %10s  %s" % ("model", "median [s]", "target [s]", "outcome"))
    for label, make, stop, error, target in CASES:
        runs = [one(make, stop, error) for _ in range(repeats)]
        med = statistics.median(r[0] for r in runs)
        print("%-32s %10.2f %10.2f  %s%s" % (label, med, target, runs[-1][1],
                                            "" if med <= target else "  OVER TARGET"))


if __name__ == "__main__":
    if sys.argv[1:] == ["--small"]:
        main(1)
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
