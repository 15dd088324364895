"""What scoping the thread limits to our runs costs: making the
process's threadpoolctl ``ThreadpoolController`` (at the first run, and again
only after a library with a thread pool was loaded), the check that no such
library was loaded (where a run loads native code), and entering and leaving
a limit (every run), beside a warm run of the pendulum for scale.  Prints a
table.

    python benchmarks/bench_threads.py [--small] [repeats]

Times are wall seconds, the median of ``repeats`` (default 200; ``--small``:
20, a test runs it so that the table cannot rot).
"""
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PENDULUM = os.path.join(HERE, "..", "models", "pendulum.py")

CONTROLLER = ("import time, numpy, scipy.linalg, scipy.sparse.linalg, casadi\n"
              "from threadpoolctl import ThreadpoolController\n"
              "t = time.perf_counter(); ThreadpoolController(); print(time.perf_counter() - t)")


def controller_seconds():
    """Making a ThreadpoolController in a fresh process (the libraries of a
    run loaded), as the first run of a process does."""
    out = subprocess.run([sys.executable, "-c", CONTROLLER], capture_output=True, text=True,
                         check=True, timeout=300)
    return float(out.stdout.split()[-1])


def median_seconds(fn, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main(argv):
    small = "--small" in argv
    numbers = [a for a in argv if not a.startswith("--")]
    repeats = int(numbers[0]) if numbers else (20 if small else 200)
    import acausal2d
    from acausal2d import threads
    cm = acausal2d.compile_model(PENDULUM)
    cm.simulate(stop_time=0.1, intervals=2, progress=False)      # warm; makes the controller

    def enter_leave():
        with threads.our_threads():
            pass

    def run():
        cm.simulate(stop_time=0.1, intervals=2, progress=False)

    rows = [("ThreadpoolController made (once per process) [ms]",
             1e3 * statistics.median(controller_seconds() for _ in range(3 if small else 5))),
            ("check for newly loaded pools (each native library load) [ms]",
             1e3 * median_seconds(threads.libraries_loaded, repeats)),
            ("limit entered and left (every run) [ms]", 1e3 * median_seconds(enter_leave, repeats)),
            ("warm run of the pendulum, 0.1 s (for scale) [ms]",
             1e3 * median_seconds(run, repeats))]
    width = max(len(label) for label, _ in rows)
    for label, value in rows:
        print("%-*s  %10.3f" % (width, label, value))


if __name__ == "__main__":
    main(sys.argv[1:])
