"""``acausal2d optimize``: choose parameter values that minimise a run
metric (see :mod:`acausal2d.analysis.optimize`); writes optimize.json,
optimize.csv and optimize.png.  Exit 0 at a KKT point, 2 for bad input (a
design parameter without bounds or given twice, an option given twice, an
objective that is not a number at the start or on the whole grid), 3 when
the optimiser stops elsewhere (its budget, a failed line search)."""
import os
import sys
import numpy as np

from .args import MODEL_FILE_HELP
from ..errors import Acausal2dError
from .args import Once, _parse_set, _positive_float, _positive_int, add_dask_options, \
    add_run_options, run_options
from ..io.output import OutputFolder


def cmd_optimize(args):
    """``acausal2d optimize``: optimise, print the report, write the files."""
    from ..analysis.optimize import optimize
    with OutputFolder(args.out, "optimize") as tx:
        opt = optimize(args.model_file, vary=args.vary, objective=args.objective,
                       constraints=args.constraint or (), fixed=_parse_set(args.set),
                       options=run_options(args),
                       max_iterations=args.max_iterations, scheduler=args.scheduler,
                       workers=args.workers, model_name=args.model)
        files = opt.write(tx.path)
        print(opt.report())
        if args.grid:
            files.append(_grid_check(opt, args, tx.path))
        tx.info["optimum"] = bool(opt.success)
    print("%d files written to %s" % (len(files), args.out))
    if not opt.success:
        print("error: no optimum found: %s (optimiser: %s)" % (opt.message, opt.optimizer_message),
              file=sys.stderr)
        return 3
    return 0


GRID_NOISE = 1e-9
"""Relative difference below which a grid value equals the optimum's (the
re-runs of the grid differ from the optimiser's run by round-off)."""


def _grid_check(opt, args, out):
    """Objective on a grid around the optimum (--grid POINTS, --grid-span);
    prints the smallest value found and writes grid.csv."""
    xs, values = opt.grid(rel=args.grid_span, points=args.grid)
    path = os.path.join(out, "grid.csv")
    np.savetxt(path, np.column_stack([xs, values]), delimiter=",", comments="",
               header=",".join(opt.names + ["objective"]), fmt="%.12g")
    if not np.any(np.isfinite(values)):
        raise Acausal2dError("--grid: the objective %s is not a number at any of the %d grid "
                             "points around the optimum (every run failed or the metric is NaN "
                             "there); grid.csv lists them; choose a smaller --grid-span or "
                             "another objective" % (opt.objective_text, len(values)))
    k = int(np.nanargmin(np.where(np.isfinite(values), values, np.nan)))
    # lower only by more than round-off of the re-run (1e-9 relative) counts as below
    below = values[k] < opt.objective - GRID_NOISE * max(abs(opt.objective), 1e-300)
    print("grid of %d points within +-%g around the optimum: smallest objective %.8g%s" % (
        len(values), args.grid_span, values[k],
        " (the optimum's)" if not below else
        " at %s, BELOW the optimum" % ", ".join("%s=%.6g" % kv
                                                for kv in zip(opt.names, xs[k]))))
    return path


def add_parsers(sub):
    """``acausal2d optimize``."""
    o = sub.add_parser("optimize", help="choose parameter values that minimise a run metric "
                       "(e.g. max(abs(drive.tau))) subject to bounds and constraints")
    o.add_argument("model_file", help=MODEL_FILE_HELP)
    o.add_argument("--model", action=Once,
                   help="model class in the file (default: the file's model)")
    o.add_argument("--vary", action="append", required=True, metavar="NAME=START:LO:HI",
                   help="a design parameter with start value and bounds; repeatable (each "
                   "parameter once)")
    o.add_argument("--objective", action=Once, required=True, metavar="EXPR",
                   help="metric to minimise: signals, + - * / **, abs, max, min, mean, rms, "
                   "integral (optionally over T0, T1), final, at(EXPR, T)")
    o.add_argument("--constraint", action="append", metavar="EXPR<=VALUE",
                   help="EXPR<=VALUE or EXPR>=VALUE; repeatable")
    o.add_argument("--set", action="append", metavar="COMP.PARAM=VALUE",
                   help="a parameter value held fixed; repeatable")
    add_run_options(o, "stop_time", "intervals", "rtol")   # metrics at the output points
    o.add_argument("--max-iterations", action=Once, type=_positive_int, default=60,
                   help="optimiser's budget of iterations (default 60); exit 3 when used up")
    o.add_argument("--grid", action=Once, type=_positive_int, metavar="POINTS",
                   help="confirm the optimum on a grid of POINTS values per parameter around "
                   "it (writes grid.csv)")
    o.add_argument("--grid-span", action=Once, type=_positive_float, default=0.01,
                   help="half-width of the grid relative to each parameter's scale "
                   "(default 0.01)")
    add_dask_options(o, "run the Jacobians' simulations on Dask: 'local' or a "
                     "scheduler address (default: serial)")
    o.add_argument("--out", action=Once, default="out",
                   help="output directory (default: out)")
    o.set_defaults(func=cmd_optimize)
