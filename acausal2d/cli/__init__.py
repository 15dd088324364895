"""The ``acausal2d`` command line: one module per group of commands
(:mod:`.simulate`; :mod:`.model_info`: check, params; :mod:`.compare`;
:mod:`.studies`: sweep, study), assembled by :func:`build_parser`.

Exit codes: 0 success; 1 comparison failed (outside the tube); 2 error in
the model or the input, or a run that cannot go on (the message names what
to change; no traceback); 3 run stopped early (a limit position, a step or
wall-clock budget): its results up to there are written; 130 interrupted
(Ctrl-C), 143 terminated (SIGTERM).  Every command that writes a folder
writes it as one transaction (:class:`~acausal2d.io.output.OutputFolder`):
checked before the run, one run per folder at a time, written into a
temporary sibling and moved in with its manifest ``acausal2d-run.json`` at
the end; a failed or interrupted run leaves neither partial nor earlier
results there.
"""
import argparse
import logging
import sys
import warnings
import importlib
import signal

from ..errors import Acausal2dError
from ..runtime import notices
from .. import __version__
from ..io.loader import load_model
from ..analysis.study import declared_studies
from .examples import add_examples
from ..usercode import TRACEBACK_ENV, has_user_cause, print_traceback, wants_traceback
from ..io.output import Terminated, terminate_as_interrupt


COMMAND_MODULES = ("simulate", "model_info", "compare", "studies", "fit", "optimize", "linearize", "modes",
                   "export_fmu", "explore", "cache", "diagram")
"""The modules under acausal2d.cli that add subcommands (``add_parsers(sub)``), in help order."""


def build_parser():
    """The argparse parser of the ``acausal2d`` command."""
    p = argparse.ArgumentParser(prog="acausal2d", description="simulate, check and compare "
                                "models of planar linkages and belt drives")
    p.add_argument("--version", action="version", version="acausal2d " + __version__)
    p.add_argument("--traceback", action="store_true",
                   help="on an error, print the whole Python traceback too (also "
                   "$%s=1); may be given after the command as well" % TRACEBACK_ENV)
    sub = p.add_subparsers(dest="command", required=True)
    for name in COMMAND_MODULES:
        importlib.import_module("." + name, __name__).add_parsers(sub)
    add_examples(sub)
    return p


def run_model_file(path, model=None, out="out"):
    """What running a model file does (its ``__main__`` block): simulate it
    (figures, CSV, animation) and run its declared studies, into ``out``.
    Returns the exit code."""
    extra = ["--model", model] if model else []
    code = main(["simulate", path, "--out", out] + extra)
    if code == 0 and declared_studies(type(load_model(path, model))):
        code = main(["study", path, "--out", out] + extra)
    return code


def _print_error(exc, show_traceback):
    """``error: MESSAGE`` on stderr; the whole traceback with ``--traceback``
    (or $ACAUSAL2D_TRACEBACK=1), else, for an error of the user's own code,
    how to see it."""
    if show_traceback:
        print_traceback(exc)
    print("error: %s" % exc, file=sys.stderr)
    if not show_traceback and has_user_cause(exc):
        print("  (the whole traceback: --traceback or %s=1)" % TRACEBACK_ENV, file=sys.stderr)


def _show_warning(message, category, filename, lineno, file=None, line=None):
    """Warnings on the command line: one line ``warning: ...`` on stderr."""
    print("warning: %s" % message, file=sys.stderr)


def main(argv=None):
    """Entry point of the ``acausal2d`` command; returns the exit code (see
    the module docstring).  SIGTERM is handled as Ctrl-C (exit 143 after
    the clean-ups: the output transaction's rollback, the process's
    temporary folder).  Called as the program (``argv`` None), Ctrl-C is
    ignored once the command has ended: the interpreter's shutdown must not
    turn a finished command into a death by SIGINT."""
    notices.logger().setLevel(logging.INFO)      # the first-run notices, on stderr
    with terminate_as_interrupt() as interrupts:     # SIGTERM as Ctrl-C: clean-ups run
        code = _main(argv)
    if code == 0 and interrupts is not None and interrupts.seen:
        code = _swallowed(interrupts)
    if argv is None:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    return code


def _swallowed(interrupts):
    """The exit code of a command whose Ctrl-C or SIGTERM was swallowed on
    its way up (in a finaliser or weakref callback) and that then ended
    normally: it still ends as interrupted (130/143), never 0."""
    term = signal.SIGTERM in interrupts.seen
    print("interrupted%s" % (" (SIGTERM)" if term else ""), file=sys.stderr)
    return 143 if term else 130


def _main(argv):
    argv = list(sys.argv[1:] if argv is None else argv)
    show_traceback = wants_traceback("--traceback" in argv)
    argv = [a for a in argv if a != "--traceback"]      # accepted before or after the command
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:        # argparse: --help, --version, or a usage error (2)
        return exc.code if isinstance(exc.code, int) else 2
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            return args.func(args)
    except Acausal2dError as exc:
        _print_error(exc, show_traceback)
        return 2
    except OSError as exc:      # files: --out on an existing file, unreadable CSV ...
        print("error: %s" % exc, file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:      # Ctrl-C; SIGTERM in an output transaction
        print("interrupted%s" % (" (SIGTERM)" if isinstance(exc, Terminated) else ""),
              file=sys.stderr)
        return 143 if isinstance(exc, Terminated) else 130


if __name__ == "__main__":
    sys.exit(main())
