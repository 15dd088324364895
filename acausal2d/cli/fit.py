"""``acausal2d fit``: calibrate a model's parameters against measured
curves (see :mod:`acausal2d.analysis.fit`); writes fit.json, fit.csv,
fit.png and the comparison plots.  Exit 0 when the fit converged (KKT
check) to estimates inside their bounds and the fitted run lies in the
tube of the measured noise, 2 for bad input (also an option or a
parameter given twice), 3 when the optimiser's budget ran out, the
optimality check fails or a bound holds an estimate (not a regular
optimum), 1 when the fitted run leaves the tube."""
import sys

from .args import MODEL_FILE_HELP
from ..analysis.fit_report import COMPARE_TUBE
from ..errors import Acausal2dError
from .args import Once, _nonnegative, _parse_set, _positive_float, _positive_int, \
    add_dask_options, add_run_options, run_options
from ..io.output import OutputFolder


def parse_mapping(items, option="--map"):
    """``REF=OURS`` items -> {ref: ours}."""
    mapping = {}
    for item in items or ():
        if "=" not in item:
            raise Acausal2dError("%s takes REF=OURS, got %r" % (option, item))
        a, b = item.split("=", 1)
        if a.strip() in mapping:
            raise Acausal2dError("%s %s is given twice; pair each column once" % (option,
                                                                                  a.strip()))
        mapping[a.strip()] = b.strip()
    return mapping


def parse_weights(text):
    """``a=1,b=0.1`` -> {a: 1.0, b: 0.1}."""
    weights = {}
    for item in (text or "").split(","):
        if not item.strip():
            continue
        name, _, value = item.partition("=")
        if name.strip() in weights:
            raise Acausal2dError("--weights %s is given twice; weight each signal once"
                                 % name.strip())
        try:
            weights[name.strip()] = float(value)
        except ValueError:
            raise Acausal2dError("--weights takes signal=weight,... (e.g. rope1.F=1,rope5.F=0.1),"
                                 " got %r" % item) from None
    return weights


def parse_range(text, option="--t-range"):
    """``T0:T1`` -> (t0, t1)."""
    if text is None:
        return None
    try:
        t0, t1 = (float(v) for v in text.split(":"))
    except ValueError:
        raise Acausal2dError("%s takes T0:T1 (e.g. 2:4), got %r" % (option, text)) from None
    if not t0 < t1:
        raise Acausal2dError("%s %s: T0 must be smaller than T1" % (option, text))
    return t0, t1


def cmd_fit(args):
    """``acausal2d fit``: fit, print the report and the compare table, write the files."""
    with OutputFolder(args.out, "fit") as tx:
        fr = _fit(args)
        files = fr.write(tx.path)
        tx.info["converged"] = bool(fr.success)
    print(fr.report())
    print()
    cmp = fr.compare()
    print(cmp.table())
    print("%d files written to %s (fit.json, fit.csv, fit.png, compare/)" % (len(files), args.out))
    if not fr.success:
        print("error: the fit %s: %s" % ("is not a regular optimum" if fr.at_bound else
                                         "did not converge", fr.message), file=sys.stderr)
        return 3
    if not cmp.passed:
        print("error: the fitted run lies outside the tube of the measured noise (%g noise "
              "std%s): %s" % (COMPARE_TUBE, " + --abs-tol" if args.abs_tol else "",
                              ", ".join(r.name for r in cmp.failed)), file=sys.stderr)
        return 1
    return 0


def _fit(args):
    """The fit the command line asks for."""
    from ..analysis.fit import fit
    signals = [s.strip() for s in args.signals.split(",") if s.strip()] if args.signals else None
    fr = fit(args.model_file, args.data, free=args.free, signals=signals,
             mapping=parse_mapping(args.map) or None, weights=parse_weights(args.weights),
             t_range=parse_range(args.t_range), fixed=_parse_set(args.set), loss=args.loss,
             f_scale=args.f_scale, options=run_options(args),
             max_evaluations=args.max_evaluations,
             scheduler=args.scheduler, workers=args.workers, model_name=args.model,
             abs_tol=args.abs_tol)
    return fr


def add_parsers(sub):
    """``acausal2d fit``."""
    f = sub.add_parser("fit", help="fit model parameters to measured curves (least squares "
                       "with standard errors, 95%% intervals and correlations)")
    f.add_argument("model_file", help=MODEL_FILE_HELP)
    f.add_argument("--model", action=Once,
                   help="model class in the file (default: the file's model)")
    f.add_argument("--data", action=Once, required=True,
                   help="measured CSV (time column + signals)")
    f.add_argument("--free", action="append", required=True, metavar="NAME=START[:LO:HI]",
                   help="a parameter to fit with its start value and bounds; tie parameters "
                   "with a.p,b.p=...; repeatable (each parameter once)")
    f.add_argument("--set", action="append", metavar="COMP.PARAM=VALUE",
                   help="a parameter value held fixed; repeatable")
    f.add_argument("--signals", action=Once, help="comma-separated measured columns to fit "
                   "(default: every column the model also has)")
    f.add_argument("--map", action="append", metavar="REF=OURS",
                   help="measured column = model signal; repeatable")
    f.add_argument("--weights", action=Once, metavar="a=1,b=0.1",
                   help="weights of the signals' residuals")
    f.add_argument("--t-range", action=Once, metavar="T0:T1",
                   help="use the measured times in T0..T1 only")
    f.add_argument("--loss", action=Once, default="linear",
                   choices=["linear", "soft_l1", "huber", "cauchy", "arctan"],
                   help="robust loss for data with outliers (default: least squares)")
    f.add_argument("--f-scale", action=Once, type=_positive_float, default=1.0,
                   help="residual size where the robust loss sets in (default 1)")
    add_run_options(f, "rtol")
    f.add_argument("--abs-tol", action=Once, type=_nonnegative, metavar="TOL",
                   help="tolerance added to the comparison tube (in the signals' units); the "
                   "tube is otherwise %g times the noise estimated from the measured data"
                   % COMPARE_TUBE)
    f.add_argument("--max-evaluations", action=Once, type=_positive_int, default=100,
                   help="optimiser's budget of steps (default 100); exit 3 when used up")
    add_dask_options(f, "run the Jacobian's simulations on Dask: 'local' (a "
                     "local cluster) or a scheduler address tcp://host:8786 (default: serial)")
    f.add_argument("--out", action=Once, default="out",
                   help="output directory (default: out)")
    f.set_defaults(func=cmd_fit)
