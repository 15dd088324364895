"""``python -m acausal2d`` runs the command line (same as ``acausal2d``)."""
import atexit
import os
import sys

from .cli import main

code = main()
if code in (130, 143):
    # Interrupted.  CPython (3.11-3.13) remembers a KeyboardInterrupt that
    # ended code run by exec() of a string (a dataclass or namedtuple being
    # made while Ctrl-C arrives) even when it was caught later, and under
    # ``python -m`` turns the exit code into a death by SIGINT after
    # finalisation: the clean-ups run here, then the code is the one main()
    # returned.
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(code)
sys.exit(code)
