"""Cold start: the first run of a new model structure against the
Python path, the background compile, and later runs at native speed.

    python benchmarks/bench_cold.py            (the full table; medians of 3, the
                                                Python path and the first run of 9 pairs)
    python benchmarks/bench_cold.py --small    (a chain of 3 links, one run, one pair, the piston
                                                engine's whole process once: the suite)
    python benchmarks/bench_cold.py --classic  (also compile first, as the runtime did before)
    python benchmarks/bench_cold.py belt chain (only the models whose names contain these)
    python benchmarks/bench_cold.py --pairs=5  (5 alternating pairs instead of 9)

Every figure is measured in a fresh process with a cache folder of its own:

- "Python path": ``ACAUSAL2D_NATIVE=off``, compile_model + simulate;
- "first run (auto)": an empty cache in mode auto: compile_model +
  simulate on the driver on CasADi's C API, the worker launched after it;
  the drivers' objects and the C API driver are those ``pip install``
  compiled into the package (:mod:`acausal2d.runtime.drivers`; the header
  says how many there are);
- "no drivers": the same with ``ACAUSAL2D_PREBUILT=0``: an install that
  found no compiler, so that the first run also builds the C API driver
  (and the worker the drivers' objects);
- "no compiler": the first run in mode auto with no C compiler on ``PATH``
  (``$CC`` unset): on the C API driver installed with the package, and no
  worker after it;
- "native in": from the worker's start until every library it builds is
  published (at -O0 first where the C is large: runs from then on are
  native; target for the chain of 81 links: <= 5 s);
- "alone": the same as "native in" where no run is beside the worker (a
  run of a millisecond launches it): the background compile itself (the
  worker is launched when the run has ended);
- "background": from the worker's start to its end (the -O1 libraries
  replaced the -O0 ones), and the CPU seconds of the worker and its
  compiler processes ("bg CPU": on a machine shared with other jobs the wall
  time scatters, the CPU time much less);
- "later run": the next process on the filled cache (native speed);
- "compile first": mode now on an empty cache (the behaviour before the
  first run went on without its library; with --classic);
- ``acausal2d simulate models/piston_engine.py``, whole process, with an
  empty cache (auto), the same without the installed drivers
  (``ACAUSAL2D_PREBUILT=0``) and with a full cache (target: <= 1.2x);
  medians of 5 (one each with --small), the three alternating.
"""
import json
import os
import resource
import signal
import statistics
import subprocess
import sys
import tempfile
import time

PAIRS = 9
"""Alternating pairs of the Python path and the first run: on a shared
machine a short run's time scatters by 20-40%, and the belt drive's ratio
was 0.98 and 1.28 as medians of 3 in two full runs of one build."""
KILL = "BENCH_COLD_STOP_WORKER"
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
MODELS = {
    "chain of 81 links": ("chain", 81, 1.0),
    "belt drive": ("belt", 0, None),
    "compressor": ("compressor", 0, None),
    "piston engine": ("piston", 0, None),
}
SMALL = {"chain of 3 links": ("chain", 3, 0.2)}


def _model(kind, n):
    sys.path[:0] = [HERE, os.path.join(ROOT, "models")]
    if kind == "chain":
        from bench_core import PendulumChain
        return PendulumChain(n)
    if kind == "belt":
        import noncircular_belt_drive as nbd
        return nbd.NonCircularBeltDrive(nbd.design())
    if kind == "compressor":
        from compressor import Compressor
        return Compressor()
    from piston_engine import PistonEngine
    return PistonEngine()


def child(kind, n, stop):
    """One run in this process; prints its times as JSON."""
    import acausal2d
    from acausal2d.runtime import background
    model = _model(kind, n)
    t0 = time.perf_counter()
    cm = acausal2d.compile_model(model)
    res = cm.simulate(stop_time=stop)
    t1 = time.perf_counter()
    worker = usable = None
    if os.environ.get(KILL) == "1":       # a first run measured only: its worker is not waited for
        for proc in background._workers:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        background._workers.clear()
    for proc in background._workers:      # launched at the run's end (t1)
        proc.wait()
        worker = max(worker or 0.0, time.perf_counter() - t1)
    use = resource.getrusage(resource.RUSAGE_CHILDREN)
    print(json.dumps({"run": t1 - t0, "worker": worker, "steps": res.stats["steps"],
                      "usable": worker if usable is None else usable,
                      "cpu": use.ru_utime + use.ru_stime,
                      "notes": res.native_notes, "wall": res.stats["wall_time"],
                      "native": res.stats["native_compile_time"]}))


def _child(name, models, cache, mode, prebuilt="1", stop=None, kill=False, compiler=True):
    kind, n, default = models[name]
    stop = default if stop is None else stop
    env = dict(os.environ, ACAUSAL2D_CACHE_DIR=cache, ACAUSAL2D_NATIVE=mode,
               ACAUSAL2D_PREBUILT=prebuilt, **{KILL: "1" if kill else "0"})
    if not compiler:                      # no C compiler on PATH ($CC unset)
        env.pop("CC", None)
        env["PATH"] = cache
    out = subprocess.run([sys.executable, __file__, "--child", kind, str(n), str(stop)],
                         env=env, capture_output=True, text=True, check=True, timeout=1800)
    return json.loads(out.stdout.strip().splitlines()[-1])


def _settled(cache, timeout=600.0):
    """Wait until no background worker works in ``cache`` (its job file is gone)."""
    end = time.perf_counter() + timeout
    while time.perf_counter() < end:
        try:
            if not any(f.startswith(".tmp-job-") and not f.endswith(".log")
                       for f in os.listdir(cache)):
                return
        except OSError:
            return
        time.sleep(0.05)


def measure(name, models, repeat, classic, pairs):
    """Medians of the figures of one model: of ``repeat`` rounds, and for
    the Python path and the first run, of ``pairs`` alternating pairs (the
    rounds' and more, whose workers are stopped after the run)."""
    rows = {"python": [], "auto": [], "usable": [], "worker": [], "cpu": [], "later": [],
            "new": [], "now": [], "alone": [], "nocc": []}
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b, \
                tempfile.TemporaryDirectory() as e:
            rows["python"].append(_child(name, models, b, "off")["run"])
            rows["nocc"].append(_child(name, models, e, "auto", compiler=False)["run"])
            first = _child(name, models, a, "auto")
            rows["auto"].append(first["run"])
            rows["worker"].append(first["worker"] or 0.0)
            rows["usable"].append(first["usable"] or 0.0)
            rows["cpu"].append(first["cpu"])
            _settled(a)
            rows["later"].append(_child(name, models, a, "auto")["run"])
            with tempfile.TemporaryDirectory() as c:
                rows["new"].append(_child(name, models, c, "auto", prebuilt="0")["run"])
                _settled(c)
            with tempfile.TemporaryDirectory() as d:
                rows["alone"].append(_child(name, models, d, "auto", stop=1e-3)["usable"] or 0.0)
                _settled(d)
            if classic:
                rows["now"].append(_child(name, models, b, "now")["run"])
    for _ in range(pairs - repeat):
        with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b, \
                tempfile.TemporaryDirectory() as e:
            rows["python"].append(_child(name, models, b, "off")["run"])
            rows["nocc"].append(_child(name, models, e, "auto", compiler=False)["run"])
            rows["auto"].append(_child(name, models, a, "auto", kill=True)["run"])
    return {k: statistics.median(v) for k, v in rows.items() if v}


def whole_process(repeat):
    """(empty cache, empty cache without the installed drivers, full cache)
    medians of ``acausal2d simulate`` of the piston engine, alternating."""
    model = os.path.join(ROOT, "models", "piston_engine.py")
    cold, bare, warm = [], [], []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out, \
                tempfile.TemporaryDirectory() as fresh:
            for times, where, prebuilt in ((cold, cache, "1"), (warm, cache, "1"),
                                           (bare, fresh, "0")):
                env = dict(os.environ, ACAUSAL2D_CACHE_DIR=where, ACAUSAL2D_NATIVE="auto",
                           ACAUSAL2D_PREBUILT=prebuilt)
                t0 = time.perf_counter()
                subprocess.run([sys.executable, "-m", "acausal2d", "simulate", model, "--out",
                                out], env=env, capture_output=True, check=True, cwd=out)
                times.append(time.perf_counter() - t0)
                _settled(where)
    return statistics.median(cold), statistics.median(bare), statistics.median(warm)


def _installed():
    """How many driver objects were compiled into the package at install,
    and whether the C API driver of this version was (the installed
    acausal2d, which the runs import: from a clone's folder a non-editable
    install's copy would be shadowed by the sources, which have none)."""
    from acausal2d.runtime import drivers
    folder = drivers.PREBUILT
    names = os.listdir(folder) if os.path.isdir(folder) else []
    return len([f for f in names if f.endswith(".o")]), \
        "yes" if drivers.capi_file() in names else "no"


def main(models, repeat, classic, piston, whole_repeat, pairs):
    print("cold start, fresh processes, s: Python and first run medians of %d "
          "alternating pairs, the rest medians of %d; driver objects installed with the "
          "package: %d, the C API driver: %s" % ((pairs, repeat) + _installed()))
    print("%-22s %8s %12s %6s %12s %6s %12s %6s %10s %7s %11s %7s %7s %14s" % (
        "model", "Python", "first(auto)", "ratio", "no drivers", "ratio", "no compiler",
        "ratio", "native in", "alone", "background", "bg CPU", "later", "compile first"))
    for name in models:
        m = measure(name, models, repeat, classic, pairs)
        print("%-22s %8.3f %12.3f %6.2f %12.3f %6.2f %12.3f %6.2f %10.3f %7.3f %11.3f %7.2f "
              "%7.3f %14s" % (
                  name, m["python"], m["auto"], m["auto"] / m["python"], m["new"],
                  m["new"] / m["python"], m["nocc"], m["nocc"] / m["python"], m["usable"],
                  m["alone"], m["worker"], m["cpu"], m["later"],
                  "%.3f" % m["now"] if "now" in m else "-"))
    if piston:
        cold, bare, warm = whole_process(whole_repeat)
        print("acausal2d simulate models/piston_engine.py, whole process, medians of %d: empty "
              "cache %.3f s, empty cache without the installed drivers %.3f s, full cache %.3f "
              "s; ratios %.2f, %.2f" % (whole_repeat, cold, bare, warm, cold / warm,
                                        bare / warm))


if __name__ == "__main__":
    args = sys.argv[1:]
    if args[:1] == ["--child"]:
        child(args[1], int(args[2]), None if args[3] == "None" else float(args[3]))
    elif "--small" in args:
        main(SMALL, 1, "--classic" in args, True, 1, 1)
    else:
        chosen = [a for a in args if not a.startswith("--")]
        picked = {k: v for k, v in MODELS.items() if not chosen or any(c in k for c in chosen)}
        pairs = int(next((a[8:] for a in args if a.startswith("--pairs=")), PAIRS))
        repeat = min(3, pairs)
        main(picked, repeat, "--classic" in args, not chosen or "piston" in chosen, 5, pairs)
