"""Python's cyclic garbage collector paused while a large structure is
built (compilation, index-1 formulation, state selection)."""
import contextlib
import gc


@contextlib.contextmanager
def cyclic_gc_paused():
    """Python's cyclic garbage collector off for the duration (restored
    after).  A compilation allocates millions of objects that live until it
    ends (symbols, expressions, graphs) and creates almost no garbage
    cycles, so each full collection only re-scans them: with it running, a
    chain of 34k flattened equations compiled in 24 s instead of 7.5 s
    (the collections grow with the square of the model)."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()
