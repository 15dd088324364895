"""Each compilation owns its symbol table: compiling the piston engine 50
times in one process leaves the table size and the process memory flat (a
process-wide registry grew by ~150 symbols per compile and never freed them)."""
import gc

import acausal2d
from acausal2d.language import symbols
from conftest import load_model_class


def _rss_mb():
    with open("/proc/self/statm") as fh:
        return int(fh.read().split()[1]) * 4096 / 1e6


def test_fifty_compiles_keep_symbol_table_and_memory_flat():
    engine = load_model_class("piston_engine.py", "PistonEngine")
    sizes = []
    for k in range(60):
        cm = acausal2d.compile_model(engine())
        sizes.append(len(cm.system.table))
        if k == 9:
            gc.collect()
            before = _rss_mb()
        del cm
    gc.collect()
    after = _rss_mb()
    assert len(set(sizes)) == 1 and 100 < sizes[0] < 1000
    assert after - before < 10.0, "memory grew by %.1f MB over 50 compiles" % (after - before)
    # nothing is registered process-wide: no table is active outside a flattening
    assert not symbols._active


def test_tables_of_two_compilations_are_independent():
    engine = load_model_class("piston_engine.py", "PistonEngine")
    a = acausal2d.compile_model(engine()).system.table
    b = acausal2d.compile_model(engine()).system.table
    assert a is not b and len(a) == len(b)
