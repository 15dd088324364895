"""Disk caches in the benchmarks: was the native C of a model already
compiled (warm) or did the first run call the C compiler (cold), and what
one run costs in a fresh process with empty caches."""
import os
import resource
import subprocess
import sys
import tempfile
import time


def native_libraries():
    """The compiled libraries in acausal2d's native cache folder."""
    from acausal2d.runtime import cbuild
    try:
        return {f for f in os.listdir(cbuild.cache_dir()) if f.endswith(".so")}
    except OSError:
        return set()


def state(before):
    """"warm" if no library was added since ``before`` (native_libraries())."""
    return "warm" if native_libraries() <= before else "cold (the C compiler ran)"


def cold_run(script, *args):
    """(wall, CPU of the process and its children) of ``python script args``
    in a fresh process with empty caches (native libraries, pulley design)."""
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, ACAUSAL2D_CACHE_DIR=tmp)
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run([sys.executable, os.path.abspath(script)] + list(args), env=env,
                       check=True)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def print_cold(wall, cpu, width=40):
    print("%-*s %10.3f" % (width, "cold: fresh process, empty caches, wall", wall))
    print("%-*s %10.3f" % (width, "cold: the same, CPU incl. the C compiler", cpu))
