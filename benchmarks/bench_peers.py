"""acausal2d against rumoca 0.10.2 (a compiled Modelica tool; optional
``bench`` extra: ``pip install -e .[bench]``) on the same slider crank:
``models/piston_engine.py`` and ``benchmarks/peers/MiniPlanar.mo`` (model
``MiniPlanar.SliderCrankAcausal``, plain Modelica without a library; its
result matches the Dymola reference to 7.7e-5).  10 s simulated, rtol 1e-8,
5000 output intervals for both (rumoca: BDF, atol 1e-10).  Prints a table.

    python benchmarks/bench_peers.py [pairs]     (default 5)
    python benchmarks/bench_peers.py --small     (1 pair, 2 warm runs)

whole process = wall time of a fresh ``python -c`` that imports the tool,
                compiles and simulates (the two tools alternate, ``pairs``
                times; the median is shown)
warm          = compile + simulate in this process after a first run
                (median of ``pairs`` runs; imports excluded)
first         = the first compile + simulate in a fresh process, after
                ``import acausal2d`` only (lazy imports of the runtime
                included), against the warm figure
The processes start in a folder of their own, so they import the acausal2d
this Python has installed (not a checkout they happen to start in).  The
last line says which one (its folder; an editable install is the
checkout, and its import hook adds about 0.03 s to every process of the
environment, rumoca's too) and whether its bytecode (``__pycache__``) is
there: without it (``PYTHONDONTWRITEBYTECODE=1`` with a source checkout)
every process compiles acausal2d's modules from source, about 0.05 s of
CPU that an installed package does not pay (rumoca's wheel has its bytecode).
CPU rows: user + system time of the same runs (robust against other load
on the machine).  Ratios are rumoca / acausal2d (> 1: acausal2d is faster).  Without rumoca
the acausal2d side runs and the table says rumoca is missing.
"""
import json
import os
import resource
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
MODEL_PY = os.path.join(ROOT, "models", "piston_engine.py")
MODEL_MO = os.path.join(HERE, "peers", "MiniPlanar.mo")
NEUTRAL = os.path.join(HERE, "peers")   # the processes' folder: no acausal2d package in it
CLASS_MO = "MiniPlanar.SliderCrankAcausal"
STOP, INTERVALS, RTOL = 10.0, 5000, 1e-8

ACAUSAL2D_RUN = """
import time
import acausal2d
t0, c0 = time.perf_counter(), time.process_time()
cm = acausal2d.compile_model(acausal2d.load_model({path!r}))
res = cm.simulate(stop_time={stop}, rtol={rtol}, intervals={n})
print(time.perf_counter() - t0, len(res.time), time.process_time() - c0)
"""

RUMOCA_RUN = """
import time
import rumoca
t0, c0 = time.perf_counter(), time.process_time()
m = rumoca.Session().load({path!r}, model={cls!r})
r = m.simulate((0.0, {stop}), dt={stop} / {n},
               config=rumoca.SimConfig(solver="bdf", rtol={rtol}, atol=1e-10))
print(time.perf_counter() - t0, len(r.time), time.process_time() - c0)
"""


def have_rumoca():
    """True if rumoca can be imported."""
    try:
        import rumoca  # noqa: F401
    except ImportError:
        return False
    return True


def _code(tool):
    if tool == "acausal2d":
        return ACAUSAL2D_RUN.format(path=MODEL_PY, stop=STOP, rtol=RTOL, n=INTERVALS)
    return RUMOCA_RUN.format(path=MODEL_MO, cls=CLASS_MO, stop=STOP, rtol=RTOL, n=INTERVALS)


def _children_cpu():
    use = resource.getrusage(resource.RUSAGE_CHILDREN)
    return use.ru_utime + use.ru_stime


def whole_process(tool):
    """(wall s of the whole process, compile + simulate s inside it, CPU s
    of the whole process: user + system, CPU s of compile + simulate)."""
    c0, t0 = _children_cpu(), time.perf_counter()
    out = subprocess.run([sys.executable, "-c", _code(tool)], capture_output=True, text=True,
                         check=True, cwd=NEUTRAL)
    wall = time.perf_counter() - t0
    fields = out.stdout.split()
    return wall, float(fields[0]), _children_cpu() - c0, float(fields[2])


def warm(tool, runs):
    """Median (wall, CPU) seconds of compile + simulate in this process,
    after one run."""
    scope = {}
    code = compile(_code(tool).replace("print(", "_out = ("), "<warm>", "exec")
    times = []
    for _ in range(runs + 1):
        t0, c0 = time.perf_counter(), time.process_time()
        exec(code, scope)
        times.append((time.perf_counter() - t0, time.process_time() - c0))
    return tuple(statistics.median(t[k] for t in times[1:]) for k in (0, 1))


def main(pairs=5):
    tools = ["acausal2d"] + (["rumoca"] if have_rumoca() else [])
    whole = {t: [] for t in tools}
    for _ in range(pairs):
        for t in tools:                       # alternating: acausal2d, rumoca, acausal2d, ...
            whole[t].append(whole_process(t))
    hot_both = {t: warm(t, max(pairs, 2)) for t in tools}
    hot = {t: hot_both[t][0] for t in tools}
    hot_cpu = {t: hot_both[t][1] for t in tools}
    med = {t: statistics.median(w[0] for w in whole[t]) for t in tools}
    med_cpu = {t: statistics.median(w[2] for w in whole[t]) for t in tools}
    first = {t: statistics.median(w[1] for w in whole[t]) for t in tools}
    first_cpu = {t: statistics.median(w[3] for w in whole[t]) for t in tools}
    print("Slider crank (piston engine), %g s, rtol %g, %d output intervals; %d pairs"
          % (STOP, RTOL, INTERVALS, pairs))
    print("%-44s %10s %10s %10s" % ("", "acausal2d", "rumoca", "ratio"))
    _row("whole process [s] (median)", med)
    _row("whole process CPU [s] (median)", med_cpu)
    _row("warm compile + simulate [s] (median)", hot)
    _row("warm compile + simulate CPU [s] (median)", hot_cpu)
    _row("first compile + simulate in a process [s]", first)
    _row("first compile + simulate CPU [s]", first_cpu)
    print("%-44s %10.2f" % ("acausal2d first / warm", first["acausal2d"] / hot["acausal2d"]))
    print("%-44s %10.2f" % ("acausal2d first / warm (CPU)",
                            first_cpu["acausal2d"] / hot_cpu["acausal2d"]))
    folder, editable = installed()
    print("acausal2d: %s (%s), bytecode %s" % (
        folder, "editable install" if editable else "installed",
        "cached" if bytecode_cached(folder) else
        "not cached (each process compiles acausal2d from source)"))
    if "rumoca" not in tools:
        print("rumoca is missing (pip install rumoca==0.10.2, or the 'bench' extra): "
              "acausal2d side only")


def installed():
    """(folder of the acausal2d the processes import, whether it is an
    editable install)."""
    code = ("import json, os, acausal2d, importlib.metadata as m\n"
            "url = json.loads(m.distribution('acausal2d').read_text('direct_url.json') or '{}')\n"
            "print(json.dumps([os.path.dirname(acausal2d.__file__), "
            "url.get('dir_info', {}).get('editable', False)]))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=NEUTRAL)
    folder, editable = json.loads(out.stdout.strip().splitlines()[-1])
    return folder, bool(editable)


def bytecode_cached(folder):
    """True if the acausal2d package in ``folder`` has up-to-date bytecode
    (pyc) files."""
    import importlib.util
    src = os.path.join(folder, "compiled.py")
    pyc = importlib.util.cache_from_source(src)
    return os.path.exists(pyc) and os.path.getmtime(pyc) >= os.path.getmtime(src)


def _row(label, values):
    a = values["acausal2d"]
    if "rumoca" in values:
        r = values["rumoca"]
        print("%-44s %10.3f %10.3f %10.2f" % (label, a, r, r / a))
    else:
        print("%-44s %10.3f %10s %10s" % (label, a, "missing", "-"))


if __name__ == "__main__":
    if sys.argv[1:] == ["--small"]:
        main(1)
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
