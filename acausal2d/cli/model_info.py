"""``acausal2d check`` (the structure report) and ``acausal2d params`` (the
parameter table) of a model file."""
import sys

from .args import MODEL_FILE_HELP, MODEL_HELP
from ..analysis.check import check
from ..errors import Acausal2dError
from ..io.loader import load_model


def cmd_check(args):
    """``acausal2d check``: print the structure report of a model; with
    ``--diagram FILE`` also write its diagram, even when the model does not
    compile (then it marks the components the error names)."""
    from ..visual.diagram import check_diagram_path
    if args.diagram:
        check_diagram_path(args.diagram)          # before the model is compiled
    model = load_model(args.model_file, args.model)
    try:
        report = check(model)
    except Acausal2dError as exc:
        if args.diagram:
            _diagram(model, args.diagram, exc)
        raise
    print(report)
    if args.diagram:
        _diagram(model, args.diagram)
    return 0


def _diagram(model, path, error=None):
    from ..visual.diagram import write_diagram
    write_diagram(model, path, error)
    print("  diagram:           %s" % path, file=sys.stderr if error else sys.stdout)


def cmd_params(args):
    """``acausal2d params``: print the model's parameter table."""
    from ..compiled import compile_model
    model = load_model(args.model_file, args.model)
    print("%s parameters (set with --set NAME=VALUE or params={NAME: value}):"
          % type(model).__name__)
    print(compile_model(model).parameters_table())
    return 0


def add_parsers(sub):
    """``acausal2d check`` and ``acausal2d params``."""
    c = sub.add_parser("check", help="print the structure of a model")
    c.add_argument("model_file", help=MODEL_FILE_HELP)
    c.add_argument("--model", help=MODEL_HELP)
    c.add_argument("--diagram", metavar="FILE", nargs="?", const="diagram.svg",
                   help="also write the model's diagram (default diagram.svg; .html: with its "
                   "sub-models), also when the model does not compile")
    c.set_defaults(func=cmd_check)
    r = sub.add_parser("params", help="list a model's parameters with value, unit, rule and "
                       "description")
    r.add_argument("model_file", help=MODEL_FILE_HELP)
    r.add_argument("--model", help=MODEL_HELP)
    r.set_defaults(func=cmd_params)
