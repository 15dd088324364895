"""The ``acausal2d`` command line: simulate, check, compare.

Exit codes: 0 success, 1 comparison failed, 2 error in the model or the
input (the message names what to change; no traceback).
"""
import argparse
import os
import sys
import time

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
        params[name.strip()] = vals[0] if len(vals) == 1 else tuple(vals)
    return params


PROGRESS_DELAY = 1.0      # s of wall time before the progress bar appears
PROGRESS_INTERVAL = 0.1   # s of wall time between two updates


class _Progress:
    """A progress bar over simulated time, shown after ``PROGRESS_DELAY``
    and updated at most every ``PROGRESS_INTERVAL`` seconds.  It writes to a
    duplicate of the standard error descriptor taken when it is created,
    so it stays visible while the integrator captures descriptor 2 for the
    SUNDIALS messages."""

    def __init__(self, stream=None):
        self.start = time.perf_counter()
        self.last = None
        self.own = stream is None
        if self.own:
            sys.stderr.flush()
            stream = os.fdopen(os.dup(sys.stderr.fileno()), "w")
        self.stream = stream
        self.shown = False

    def __call__(self, t, t_end):
        now = time.perf_counter()
        if now - self.start < PROGRESS_DELAY or \
                (self.last is not None and now - self.last < PROGRESS_INTERVAL and t < t_end):
            return
        self.last = now
        self.shown = True
        frac = min(max(t / t_end if t_end else 1.0, 0.0), 1.0)
        bar = "#" * int(30 * frac)
        self.stream.write("\r  [%-30s] t = %.4g / %.4g s" % (bar, t, t_end))
        self.stream.flush()

    def close(self):
        """End the bar's line (if it was shown); close the duplicated
        descriptor (a stream passed in stays open)."""
        if self.shown:
            self.stream.write("\n")
        if self.own:
            self.stream.close()
        else:
            self.stream.flush()


def cmd_simulate(args):
    from .compare import safe_filename
    from .compiled import compile_model
    from .loader import load_model
    from .scene import trace_signals
    model = load_model(args.model_file, args.model)
    out = args.out
    os.makedirs(out, exist_ok=True)        # before a long run: a bad --out fails now
    cm = compile_model(model)
    traces = [t.strip() for t in args.trace.split(",")] if args.trace else []
    trace_signals(traces, cm.names)        # names checked before the run
    progress = _Progress()
    try:
        res = cm.simulate(stop_time=args.stop_time, params=_parse_set(args.set), rtol=args.rtol,
                          intervals=args.intervals, progress=progress)
    finally:
        progress.close()
    res.to_csv(os.path.join(out, "result.csv"))
    names = [n.strip() for n in args.plot.split(",")] if args.plot else list(res.outputs)
    pngs = []
    for name in names:
        path = os.path.join(out, safe_filename(name) + ".png")
        pngs.append(res.plot([name], path, title=name))
    if not names:
        print("  (the model declares no outputs; choose signals to plot with --plot a,b)")
    res.animate(os.path.join(out, "animation.html"),
                traces=traces)
    files = _model_files(model, res, out)
    for sing in res.singularities:
        print("  %s at t=%.6g in %s" % (sing["kind"], sing["time"], ", ".join(sing["elements"])))
    if res.stopped:
        print("  " + res.stopped)
    st = res.stats
    print("%s: simulated %.4g s in %.3f s (compile %.3f s); %d steps, %d output points, "
          "%d events, %d state re-selections, %d residual evaluations -> %s/ (result.csv, "
          "%d plot%s, animation.html%s)" % (
              type(model).__name__, res.time[-1] - res.time[0], st["wall_time"],
              st["compile_time"], st["steps"], len(res.time), st["events"], st["reselections"],
              st["nfev"], out, len(pngs), "" if len(pngs) == 1 else "s",
              ", " + ", ".join(files) if files else ""))
    return 0


def _model_files(model, res, out):
    """Files the model writes itself after a run: its optional method
    ``write_outputs(result, folder)`` returns their paths (e.g. the contour
    plots and cam contour files of the band synthesis models); listed by
    name."""
    write = getattr(model, "write_outputs", None)
    if not callable(write):
        return []
    return [os.path.basename(p) for p in write(res, out) or ()]


def cmd_check(args):
    from .check import check
    from .loader import load_model
    print(check(load_model(args.model_file, args.model)))
    return 0


def cmd_compare(args):
    from .compare import run_compare_cli
    mapping = {}
    for item in args.map or ():
        if "=" not in item:
            raise Acausal2dError("--map takes ref_name=our_name, got %r" % item)
        a, b = item.split("=", 1)
        mapping[a.strip()] = b.strip()
    signals = [s.strip() for s in args.signals.split(",")] if args.signals else None
    return run_compare_cli(args.result, args.reference, signals=signals, mapping=mapping or None,
                           abs_tol=args.abs_tol, rel_tol=args.rel_tol, out_dir=args.out)


def build_parser():
    """The argparse parser of the ``acausal2d`` command."""
    p = argparse.ArgumentParser(prog="acausal2d", description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    s = sub.add_parser("simulate", help="simulate a model file; write CSV, plots, animation")
    s.add_argument("model_file")
    s.add_argument("--model", help="model class in the file (if it defines several)")
    s.add_argument("--stop-time", type=float)
    s.add_argument("--set", action="append", metavar="COMP.PARAM=VALUE",
                   help="parameter value (vectors as 1,0); repeatable")
    s.add_argument("--rtol", type=float)
    s.add_argument("--intervals", type=int, help="number of output intervals")
    s.add_argument("--plot", help="comma-separated signals to plot (default: model outputs)")
    s.add_argument("--trace", help="comma-separated points whose path the animation draws "
                   "(coupler curves): frames (dyad.ctr2D3) or x:y signal pairs "
                   "(dyad.xP:dyad.yP)")
    s.add_argument("--out", default="out", help="output directory (default: out)")
    s.set_defaults(func=cmd_simulate)
    c = sub.add_parser("check", help="print the structure of a model")
    c.add_argument("model_file")
    c.add_argument("--model")
    c.set_defaults(func=cmd_check)
    m = sub.add_parser("compare", help="compare a result CSV with a reference CSV")
    m.add_argument("result")
    m.add_argument("reference")
    m.add_argument("--signals", help="comma-separated reference columns to check")
    m.add_argument("--map", action="append", metavar="REF=OURS",
                   help="reference column = our column; repeatable")
    m.add_argument("--abs-tol", type=float)
    m.add_argument("--rel-tol", type=float)
    m.add_argument("--out", help="directory for the comparison plots")
    m.set_defaults(func=cmd_compare)
    return p


def main(argv=None):
    """Entry point of the ``acausal2d`` command."""
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except Acausal2dError as exc:
        print("error: %s" % exc, file=sys.stderr)
        return 2
    except OSError as exc:      # files: --out on an existing file, unreadable CSV ...
        print("error: %s" % exc, file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
