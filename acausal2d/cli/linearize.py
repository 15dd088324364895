"""``acausal2d linearize``: the state-space matrices A, B, C, D of a model
at a time of its run or at its static equilibrium, written as
``linear.json`` and one CSV per matrix."""
import csv
import json
import os
import sys

from .args import MODEL_FILE_HELP
from ..errors import Acausal2dError
from .args import _check_names, _parse_set
from ..io.files import atomic_path
from ..io.files import write_text
from ..io.loader import load_model
from ..io.output import OutputFolder


def _names(text):
    return [n.strip() for n in text.split(",") if n.strip()] if text else []


def _parse_start(items):
    """--start NAME=VALUE (node start values of the equilibrium search)."""
    start = {}
    for item in items or ():
        if "=" not in item:
            raise Acausal2dError("--start takes name=value, got %r" % item)
        name, value = item.split("=", 1)
        try:
            start[name.strip()] = float(value)
        except ValueError:
            raise Acausal2dError("--start %s: %r is not a number" % (name, value)) from None
    return start


def point_options(args):
    """Keyword arguments of the operating point: at, equilibrium, params, start."""
    if args.at is not None and not args.at >= 0:
        raise Acausal2dError("--at must be a time >= 0 s, got %g" % args.at)
    if args.start and not args.equilibrium:
        raise Acausal2dError("--start sets start values of the equilibrium search: add "
                             "--equilibrium")
    return {"at": args.at, "equilibrium": args.equilibrium, "params": _parse_set(args.set),
            "start": _parse_start(args.start)}


def _write_matrix(path, M, rows, cols):
    with atomic_path(path) as tmp:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow([""] + list(cols))
            for name, row in zip(rows, M):
                w.writerow([name] + ["%.17g" % v for v in row])
    return path


def write_linearization(lin, out):
    """``OUT/linear.json`` and ``OUT/A.csv`` .. ``D.csv``; returns the paths."""
    os.makedirs(out, exist_ok=True)
    files = [write_text(os.path.join(out, "linear.json"), json.dumps(lin.to_dict(), indent=1))]
    for key, rows, cols in (("A", lin.states, lin.states), ("B", lin.states, lin.inputs),
                            ("C", lin.outputs, lin.states), ("D", lin.outputs, lin.inputs)):
        files.append(_write_matrix(os.path.join(out, key + ".csv"), getattr(lin, key), rows,
                                   cols))
    return files


def cmd_linearize(args):
    """``acausal2d linearize``: write linear.json and A/B/C/D.csv."""
    from ..analysis.equilibrium import NoEquilibrium
    from ..compiled import compile_model
    from ..library.inputs import bind_inputs
    with OutputFolder(args.out, "linearize") as tx:
        model = load_model(args.model_file, args.model)
        model, _ = bind_inputs(model)       # top-level RealInputs become parameters
        cm = compile_model(model)
        outputs = _names(args.outputs) if args.outputs is not None else None
        _check_names(outputs or [], cm, "--outputs")
        try:
            lin = cm.linearize(inputs=_names(args.inputs), outputs=outputs,
                               **point_options(args))
        except NoEquilibrium as exc:
            print("error: %s" % exc, file=sys.stderr)
            return 3
        files = write_linearization(lin, tx.path)
    where = "the static equilibrium" if lin.point.kind == "equilibrium" else \
        "t = %g s" % lin.point.t
    print("%s linearised at %s: %d states, %d inputs, %d outputs -> %s" % (
        type(cm.model).__name__, where, len(lin.states), len(lin.inputs), len(lin.outputs),
        ", ".join(os.path.basename(f) for f in files)))
    print("  states (the selected states, rows and columns of A): %s" % ", ".join(lin.states))
    return 0


def add_point_arguments(p):
    """The model and operating-point options shared by linearize and modes."""
    p.add_argument("model_file", help=MODEL_FILE_HELP)
    p.add_argument("--model", help="model class in the file (if it defines several)")
    p.add_argument("--at", type=float, metavar="T", help="linearise at time T of the run "
                   "(default: the start point); with --equilibrium: the inputs at time T")
    p.add_argument("--equilibrium", action="store_true", help="linearise at the static "
                   "equilibrium (all state derivatives zero), searched from the start values")
    p.add_argument("--start", action="append", metavar="NAME=VALUE",
                   help="start value of the equilibrium search; repeatable")
    p.add_argument("--set", action="append", metavar="COMP.PARAM=VALUE",
                   help="parameter value (vectors as 1,0); repeatable")
    p.add_argument("--out", default="out", help="output directory (default: out)")


def add_parsers(sub):
    """``acausal2d linearize``."""
    p = sub.add_parser("linearize", help="state-space matrices A, B, C, D at a point of the "
                       "run or at the static equilibrium")
    add_point_arguments(p)
    p.add_argument("--inputs", metavar="A,B", help="inputs: the model's top-level RealInputs "
                   "(held at 0) or any parameters (e.g. a Constant source's k)")
    p.add_argument("--outputs", metavar="C,D", help="output signals (default: the model's "
                   "outputs)")
    p.set_defaults(func=cmd_linearize)
