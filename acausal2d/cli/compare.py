"""``acausal2d compare``: a result CSV against a reference CSV in a tolerance
tube."""
import sys

from ..errors import Acausal2dError
from .args import _nonnegative
from .. import compare


def cmd_compare(args):
    """``acausal2d compare``: compare a result CSV with a reference CSV."""
    mapping = {}
    for item in args.map or ():
        if "=" not in item:
            raise Acausal2dError("--map takes ref_name=our_name, got %r" % item)
        a, b = item.split("=", 1)
        mapping[a.strip()] = b.strip()
    signals = [s.strip() for s in args.signals.split(",")] if args.signals else None
    return run_compare_cli(args.result, args.reference, signals=signals, mapping=mapping or None,
                           abs_tol=args.abs_tol, rel_tol=args.rel_tol, out_dir=args.out,
                           time_tol=args.time_tol, until=args.until,
                           only_common=args.only_common)


def add_parsers(sub):
    """``acausal2d compare``."""
    m = sub.add_parser("compare", help="compare a result CSV with a reference CSV")
    m.add_argument("result", help="the result CSV to check (e.g. result.csv of a simulate "
                   "output folder)")
    m.add_argument("reference", help="the reference CSV (a time column and one column per "
                   "signal, e.g. exported from a Modelica tool)")
    m.add_argument("--signals", help="comma-separated reference columns to check")
    m.add_argument("--map", action="append", metavar="REF=OURS",
                   help="reference column = our column; repeatable")
    m.add_argument("--abs-tol", type=float, metavar="TOL",
                   help="absolute half-width of the tube around the reference, in the signal's "
                   "unit (default 2e-3 when --rel-tol is not given either)")
    m.add_argument("--rel-tol", type=float, metavar="TOL",
                   help="half-width of the tube relative to the largest |reference value| of "
                   "each signal (with --abs-tol: the larger of the two)")
    m.add_argument("--time-tol", type=_nonnegative, metavar="SECONDS",
                   help="time tolerance: compare in the csv-compare tube of the reference "
                   "widened by this in time (steps may be shifted by up to this much)")
    m.add_argument("--until", type=float, metavar="T",
                   help="compare reference points up to time T only")
    m.add_argument("--only-common", action="store_true",
                   help="pass on the signals both files have; reference signals without a "
                   "counterpart in the result are still listed (without this they fail)")
    m.add_argument("--out", help="directory for the comparison plots")
    m.set_defaults(func=cmd_compare)


def run_compare_cli(result_csv, reference_csv, signals=None, mapping=None, abs_tol=None,
                    rel_tol=None, out_dir=None, stream=None, time_tol=None, until=None,
                    only_common=False):
    """Compare two CSV files, print the table to ``stream`` (default: the
    current ``sys.stdout``, looked up at call time) (and write plots
    into ``out_dir`` if given); return 0 if every signal passed, else 1.
    :class:`~acausal2d.errors.Acausal2dError` is left to the caller."""
    if stream is None:
        stream = sys.stdout
    cmp = compare(result_csv, reference_csv, signals=signals, mapping=mapping,
                  abs_tol=abs_tol, rel_tol=rel_tol, plot_dir=out_dir, time_tol=time_tol,
                  until=until, only_common=only_common)
    print(cmp.table(), file=stream)
    if cmp.plots:
        print("%d plot%s written to %s" % (len(cmp.plots), "" if len(cmp.plots) == 1 else "s",
                                           out_dir), file=stream)
    return 0 if cmp.passed else 1
