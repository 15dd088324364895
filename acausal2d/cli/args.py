"""Argument checks shared by the commands: ``--set`` values, number types
for argparse, signal names checked against the compiled model before a
run, and the run options (:func:`add_run_options`, :func:`run_options`)
declared once for every command that runs simulations."""
import argparse

from ..errors import Acausal2dError
from ..options import DEFAULTS, RunOptionError, RunOptions


MODEL_FILE_HELP = ("the model file: Python source defining the model classes (any file name), "
                   "or a mec2 model (.json)")
"""Help of every command's ``model_file`` argument."""
MODEL_HELP = "the model class in the file (needed when the file defines several)"
"""Help of every command's ``--model`` option."""


def _parse_set(items):
    params = {}
    for item in items or ():
        if "=" not in item:
            raise Acausal2dError("--set takes comp.param=value, got %r" % item)
        name, value = item.split("=", 1)
        try:
            vals = [float(v) for v in value.split(",")]
        except ValueError:
            raise Acausal2dError("--set %s: %r is not a number (vectors: 1,0)" % (name, value)) \
                from None
        if name.strip() in params:
            raise Acausal2dError("--set %s is given twice; give each parameter once"
                                 % name.strip())
        params[name.strip()] = vals[0] if len(vals) == 1 else tuple(vals)
    return params


class Once(argparse.Action):
    """argparse action of an option that takes one value: given twice it is
    a usage error (exit 2) naming it, never "the last one wins"."""

    def __call__(self, parser, namespace, values, option_string=None):
        seen = namespace.__dict__.setdefault("_given_once", set())
        if self.dest in seen:
            parser.error("%s is given twice; give it once" % "/".join(self.option_strings))
        seen.add(self.dest)
        setattr(namespace, self.dest, values)


def _check_names(names, cm, option):
    """Signal names given on the command line exist (checked before the run)."""
    known = set(cm.names) | set(cm.signal_names) | {"time"}
    for name in names:
        if name not in known:
            close = [n for n in cm.names if name.split(".")[-1] in n][:8]
            raise Acausal2dError("%s: no signal %r in the model%s" % (
                option, name, "; similar: " + ", ".join(close) if close else ""))


def _nonnegative(text):
    """argparse type: a finite number >= 0 (else exit code 2 with a message)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError("%r is not a number" % text) from None
    if not (value >= 0 and value < float("inf")):
        raise argparse.ArgumentTypeError("must be a finite number >= 0, got %r" % text)
    return value


def _positive_float(text):
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError("%r is not a number" % text) from None
    if not (value > 0 and value < float("inf")):
        raise argparse.ArgumentTypeError("must be a positive number, got %r" % text)
    return value


def _positive_int(text):
    """argparse type: an integer >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError("%r is not a whole number" % text) from None
    if value < 1:
        raise argparse.ArgumentTypeError("must be at least 1, got %d" % value)
    return value


def add_dask_options(parser, scheduler_help):
    """``--scheduler`` (its help, with the command's default, is
    ``scheduler_help``) and ``--workers`` of a command that can run its
    simulations on Dask."""
    parser.add_argument("--scheduler", help=scheduler_help)
    parser.add_argument("--workers", type=_positive_int, help="worker processes of the local "
                        "cluster (default: one per core)")


RUN_FLAGS = {
    "stop_time": ("--stop-time", "SECONDS", "end time of the run (default: the model's "
                  "experiment, else %g s)" % DEFAULTS["stop_time"]),
    "rtol": ("--rtol", "TOL", "relative tolerance of the integrator (default: the model's "
             "experiment, else %g)" % DEFAULTS["rtol"]),
    "atol": ("--atol", "TOL", "absolute tolerance of the integrator (default: rtol times each "
             "unknown's nominal)"),
    "intervals": ("--intervals", "N", "number of output intervals (default: the model's "
                  "experiment, else %d)" % DEFAULTS["intervals"]),
    "max_steps": ("--max-steps", "N", "step budget of the run (default %d); exit 3 when used "
                  "up" % DEFAULTS["max_steps"]),
    "max_wall_time": ("--max-wall-time", "SECONDS", "wall-clock budget of the run; exit 3 when "
                      "used up"),
}
"""The command-line flag, metavar and help of each run option."""


def option_type(name):
    """argparse type of the run option ``name``: the text as a number (or
    as it is, when it is none); the check is :class:`RunOptions`' own, made
    by :func:`run_options` inside the command's output transaction, so a
    bad value reads as in the API and leaves no earlier results behind."""
    def parse(text):
        for kind in (int, float):
            try:
                return kind(text)
            except ValueError:
                pass
        return text                       # the check names it: "... must be a number"
    parse.__name__ = name
    return parse


def add_run_options(parser, *names, quiet=True):
    """Declare the run options ``names`` (keys of :data:`RUN_FLAGS`, each
    with one type) and, on a command that runs simulations (``quiet``),
    ``--quiet``."""
    for name in names:
        flag, metavar, text = RUN_FLAGS[name]
        parser.add_argument(flag, dest=name, action=Once, type=option_type(name),
                            metavar=metavar, help=text)
    if quiet:
        parser.add_argument("--quiet", action="store_true",
                            help="no progress bar (it is shown only when stderr is a terminal)")


def run_options(args, **extra):
    """The :class:`~acausal2d.options.RunOptions` of the parsed command
    line (the options :func:`add_run_options` declared, ``--quiet``) and
    ``extra``."""
    given = {n: getattr(args, n) for n in RUN_FLAGS if getattr(args, n, None) is not None}
    if getattr(args, "quiet", False):
        given["progress"] = False
    try:
        return RunOptions(**dict(given, **extra))
    except RunOptionError as exc:
        flag = RUN_FLAGS[exc.option][0] if exc.option in RUN_FLAGS else exc.option
        raise RunOptionError(exc.option, exc.message, flag) from None
