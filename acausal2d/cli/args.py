"""Argument checks shared by the commands: ``--set`` values, number types
for argparse, and signal names checked against the compiled model before
a run."""
import argparse

from ..errors import Acausal2dError


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
    known = set(cm.names) | {"time"}
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
