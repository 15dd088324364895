"""The ``acausal2d`` command line: simulate, check, compare, params, study,
sweep.

Exit codes: 0 success; 1 comparison failed (outside the tube); 2 error in
the model or the input, or a run that cannot go on (the message names what
to change; no traceback); 3 run stopped early (a limit position, a step or
wall-clock budget): its results up to there are written; 130 interrupted
(Ctrl-C).  ``simulate`` lists the files it writes in the output folder's
``acausal2d-run.json`` and removes those of the previous run there first,
so a failed run never leaves earlier results that look like its own.
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
    """A progress bar over simulated time on ``stream`` (default: the
    current ``sys.stderr``), shown after ``PROGRESS_DELAY`` and updated at
    most every ``PROGRESS_INTERVAL`` seconds."""

    def __init__(self, stream=None):
        self.start = time.perf_counter()
        self.last = None
        self.stream = stream if stream is not None else sys.stderr
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
        """End the bar's line (if it was shown)."""
        if self.shown:
            self.stream.write("\n")
        self.stream.flush()


def _plot_specs(args, cm):
    """The figures ``simulate`` writes: --plot groups, else the model's
    declared ``figures``, else one figure per declared output; --x applies
    to all of them.  Every signal name is checked before the run."""
    from .plotting import declared_figures, parse_groups
    if args.plot:
        specs = [{"groups": [g], "x": None, "title": None, "name": None}
                 for g in parse_groups(args.plot)]
    else:
        specs = declared_figures(cm.model) or \
            [{"groups": [[n]], "x": None, "title": None, "name": None} for n in cm.outputs]
    for spec in specs:
        spec["x"] = args.x or spec["x"]
        option = "--plot" if args.plot else "%s.figures" % type(cm.model).__name__
        _check_names([n for g in spec["groups"] for n in g], cm, option)
        _check_names([spec["x"]] if spec["x"] else [], cm, "--x" if args.x else option)
    return specs


def _check_names(names, cm, option):
    """Signal names given on the command line exist (checked before the run)."""
    known = set(cm.names) | {"time"}
    for name in names:
        if name not in known:
            close = [n for n in cm.names if name.split(".")[-1] in n][:8]
            raise Acausal2dError("%s: no signal %r in the model%s" % (
                option, name, "; similar: " + ", ".join(close) if close else ""))


def _animation_options(args, cm):
    from .scene import arrow_signals
    arrows = [a.strip() for a in args.arrows.split(",") if a.strip()] if args.arrows else []
    arrow_signals(arrows, cm.names, cm.model)      # names checked before the run
    if args.signal:
        _check_names([args.signal], cm, "--signal")
    return {"arrows": arrows, "signal": args.signal, "autoplay": args.autoplay}


def _print_summary(model, res, out, pngs, extra=()):
    """The run's summary: singular positions, early stop, solver counts,
    the files written (``extra``: those the model wrote itself) and states."""
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
              "".join(", " + os.path.basename(f) for f in extra)))
    states = getattr(res, "states", None) or []
    print("  states: %s" % (", ".join(states) if states else "none (the motion is prescribed)"))


def cmd_simulate(args):
    """``acausal2d simulate``: run a model file; write the CSV, plots and animation."""
    from .compiled import compile_model
    from .files import clear_previous_run
    from .loader import load_model
    model = load_model(args.model_file, args.model)
    out = args.out
    os.makedirs(out, exist_ok=True)        # before a long run: a bad --out fails now
    clear_previous_run(out)
    cm = compile_model(model)
    settings = _simulate_settings(args, cm)
    progress = _Progress()
    try:
        res = cm.simulate(stop_time=args.stop_time, params=settings["params"], rtol=args.rtol,
                          intervals=args.intervals, progress=progress,
                          max_steps=args.max_steps, max_wall_time=args.max_wall_time)
    finally:
        progress.close()
    pngs, extra = _write_outputs(res, out, settings, args)
    _print_summary(model, res, out, pngs, extra)
    if res.stopped:
        print("stopped early: %s" % res.stopped, file=sys.stderr)
        return 3
    return 0


def _simulate_settings(args, cm):
    """Plots, animation, traces and parameters, all checked before the run."""
    from .scene import trace_signals
    traces = [t.strip() for t in args.trace.split(",")] if args.trace else []
    trace_signals(traces, cm.names)
    return {"traces": traces, "specs": _plot_specs(args, cm),
            "animation": _animation_options(args, cm), "params": _parse_set(args.set)}


def _write_outputs(res, out, settings, args):
    """CSV, figures, animation, the files the model writes itself and the
    run's manifest; returns the figures and the model's files."""
    from .files import write_manifest
    from .plotting import write_figures
    files = [res.to_csv(os.path.join(out, "result.csv"))]
    pngs = write_figures(res, out, settings["specs"], args.format)
    if not settings["specs"]:
        print("  (the model declares no outputs; choose signals to plot with --plot a,b)")
    files += pngs
    files.append(res.animate(os.path.join(out, "animation.html"), traces=settings["traces"],
                             **settings["animation"]))
    extra = _model_files(res, out)
    write_manifest(out, files + extra,
                   model=type(res.model.model).__name__ if res.model else None,
                   stopped=res.stopped)
    return pngs, extra


def _model_files(res, out):
    """Files the model writes itself after a run: its optional method
    ``write_outputs(result, folder)`` returns their paths (e.g. the contour
    plots and cam contour files of the band synthesis models)."""
    write = getattr(res.model.model if res.model else None, "write_outputs", None)
    if not callable(write):
        return []
    return [os.fspath(p) for p in write(res, out) or ()]


def cmd_params(args):
    """``acausal2d params``: print the model's parameter table."""
    from .compiled import compile_model
    from .loader import load_model
    model = load_model(args.model_file, args.model)
    print("%s parameters (set with --set NAME=VALUE or params={NAME: value}):"
          % type(model).__name__)
    print(compile_model(model).parameters_table())
    return 0


def _sweep_settings(args, cm):
    """Points, fixed values and outputs of ``acausal2d sweep``, checked
    against the compiled model before anything runs."""
    from .sweep import expand_params, grid_points, parse_vary
    vary = parse_vary(args.vary)
    fixed = _parse_set(args.set)
    known = set(cm.parameter_names)
    for name in list(expand_params({c: 0 for c in vary})) + list(fixed):
        if name not in known:
            close = [n for n in cm.parameter_names if name.split(".")[-1] in n][:8]
            raise Acausal2dError("--vary/--set: unknown parameter %r%s" % (
                name, "; similar: " + ", ".join(close) if close else ""))
    cm.parameter_values(fixed)                  # fixed values checked against their rules
    outputs = [n.strip() for n in args.outputs.split(",") if n.strip()] if args.outputs \
        else list(cm.outputs)
    _check_names(outputs, cm, "--outputs")
    _check_run_settings(args, cm)
    if args.x is not None and args.x not in vary:
        raise Acausal2dError("--x %r is not a varied parameter; varied: %s"
                             % (args.x, ", ".join(vary)))
    return grid_points(vary), fixed, outputs


def _check_run_settings(args, cm):
    """--stop-time, --rtol and --at of a sweep, checked once before the
    points run (each point would fail alike)."""
    stop = args.stop_time if args.stop_time is not None else \
        float((getattr(cm.model, "experiment", None) or {}).get("stop_time", 1.0))
    if not stop > 0:
        raise Acausal2dError("--stop-time must be larger than 0, got %g" % stop)
    if args.rtol is not None and not 0 < args.rtol < 0.1:
        raise Acausal2dError("--rtol must be between 0 and 0.1 (e.g. 1e-6), got %g" % args.rtol)
    if args.at is not None and args.at > stop:
        raise Acausal2dError("--at %g lies after the end of the run (%g s)" % (args.at, stop))


def cmd_sweep(args):
    """``acausal2d sweep``: a parameter study on Dask; write sweep.csv and sweep.png."""
    from .sweep import ModelSpec, compiled_model, sweep
    cm = compiled_model(ModelSpec(args.model_file, args.model))   # errors here exit with 2
    points, fixed, outputs = _sweep_settings(args, cm)
    name = type(cm.model).__name__
    os.makedirs(args.out, exist_ok=True)
    result = sweep(args.model_file, points=points, params=fixed, outputs=outputs, at=args.at,
                   stop_time=args.stop_time, rtol=args.rtol, intervals=args.intervals,
                   scheduler=args.scheduler, workers=args.workers, model_name=args.model)
    csv_path = result.to_csv(os.path.join(args.out, "sweep.csv"))
    files = [csv_path]
    if outputs and len(result.failed) < len(result.rows):
        files.append(result.plot(os.path.join(args.out, "sweep.png"), x=args.x))
    for row in result.failed:
        print("  point %d failed: %s" % (row["point"], row["error"]))
    print("%s: %s -> %s" % (name, result.summary(), ", ".join(files)))
    return 0


def cmd_study(args):
    """``acausal2d study``: run (or list) the model's declared studies."""
    from .loader import load_model
    from .study import declared_studies, run_studies
    model = load_model(args.model_file, args.model)
    if args.list:
        studies = declared_studies(type(model))
        for name, st in studies.items():
            print("%-16s %s" % (name, st.doc))
        if not studies:
            print("%s declares no studies" % type(model).__name__)
        return 0
    files = run_studies(args.model_file, model, args.names, args.out,
                        {"scheduler": args.scheduler, "workers": args.workers})
    print("%s: %d file%s -> %s" % (type(model).__name__, len(files),
                                   "" if len(files) == 1 else "s", ", ".join(files)))
    return 0


def cmd_check(args):
    """``acausal2d check``: print the structure report of a model."""
    from .check import check
    from .loader import load_model
    print(check(load_model(args.model_file, args.model)))
    return 0


def cmd_compare(args):
    """``acausal2d compare``: compare a result CSV with a reference CSV."""
    from .compare import run_compare_cli
    mapping = {}
    for item in args.map or ():
        if "=" not in item:
            raise Acausal2dError("--map takes ref_name=our_name, got %r" % item)
        a, b = item.split("=", 1)
        mapping[a.strip()] = b.strip()
    signals = [s.strip() for s in args.signals.split(",")] if args.signals else None
    return run_compare_cli(args.result, args.reference, signals=signals, mapping=mapping or None,
                           abs_tol=args.abs_tol, rel_tol=args.rel_tol, out_dir=args.out,
                           time_tol=args.time_tol, until=args.until)


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


def _add_simulate_parser(sub):
    s = sub.add_parser("simulate", help="simulate a model file; write CSV, plots, animation")
    s.add_argument("model_file")
    s.add_argument("--model", help="model class in the file (if it defines several)")
    s.add_argument("--stop-time", type=float)
    s.add_argument("--set", action="append", metavar="COMP.PARAM=VALUE",
                   help="parameter value (vectors as 1,0); repeatable")
    s.add_argument("--rtol", type=float)
    s.add_argument("--intervals", type=int, help="number of output intervals")
    s.add_argument("--plot", help="signals to plot: a,b overlays a and b in one figure (one axes "
                   "per unit), a,b;c writes two figures (default: the model's figures or "
                   "outputs)")
    s.add_argument("--x", metavar="SIGNAL", help="x axis of the plots (default time); angles "
                   "in rad are unwrapped and shown in degrees")
    s.add_argument("--format", choices=("png", "svg", "pdf"), default="png",
                   help="file format of the plots (default: png)")
    s.add_argument("--autoplay", action="store_true", help="the animation starts playing")
    s.add_argument("--arrows", metavar="NAMES", help="comma-separated frames (force and torque "
                   "arrows) or rotational flanges (torque arrows) drawn in the animation")
    s.add_argument("--signal", metavar="SIGNAL", help="a signal plotted under the animation "
                   "with a cursor that follows the time slider")
    s.add_argument("--trace", help="comma-separated points whose path the animation draws "
                   "(coupler curves): frames (dyad.ctr2D3) or x:y signal pairs "
                   "(dyad.xP:dyad.yP)")
    s.add_argument("--max-steps", type=_positive_int, default=1000000,
                   help="step budget of the run (default 1000000); exit 3 when used up")
    s.add_argument("--max-wall-time", type=_positive_float, metavar="SECONDS",
                   help="wall-clock budget of the run; exit 3 when used up")
    s.add_argument("--out", default="out", help="output directory (default: out)")
    s.set_defaults(func=cmd_simulate)


def _add_compare_parser(sub):
    m = sub.add_parser("compare", help="compare a result CSV with a reference CSV")
    m.add_argument("result")
    m.add_argument("reference")
    m.add_argument("--signals", help="comma-separated reference columns to check")
    m.add_argument("--map", action="append", metavar="REF=OURS",
                   help="reference column = our column; repeatable")
    m.add_argument("--abs-tol", type=float)
    m.add_argument("--rel-tol", type=float)
    m.add_argument("--time-tol", type=_nonnegative, metavar="SECONDS",
                   help="time tolerance: compare in the csv-compare tube of the reference "
                   "widened by this in time (steps may be shifted by up to this much)")
    m.add_argument("--until", type=float, metavar="T",
                   help="compare reference points up to time T only")
    m.add_argument("--out", help="directory for the comparison plots")
    m.set_defaults(func=cmd_compare)


def _add_sweep_parser(sub):
    w = sub.add_parser("sweep", help="parameter study on Dask: simulate every combination of "
                       "the --vary values; write sweep.csv and sweep.png")
    w.add_argument("model_file")
    w.add_argument("--model")
    w.add_argument("--vary", action="append", required=True, metavar="PARAM=START:STOP:COUNT",
                   help="values of a parameter: START:STOP:COUNT or v1,v2,...; tie parameters "
                   "to one value with a.p,b.p=...; repeatable (all combinations)")
    w.add_argument("--set", action="append", metavar="COMP.PARAM=VALUE",
                   help="a parameter value held for every point; repeatable")
    w.add_argument("--outputs", help="comma-separated signals recorded per point (default: "
                   "the model's outputs)")
    w.add_argument("--at", type=_nonnegative, metavar="T",
                   help="record the outputs at time T (default: at the end of the run)")
    w.add_argument("--stop-time", type=float)
    w.add_argument("--rtol", type=float)
    w.add_argument("--intervals", type=_positive_int)
    w.add_argument("--scheduler", help="address of a running Dask scheduler (tcp://host:8786);"
                   " default: a local cluster; 'serial': run in this process")
    w.add_argument("--workers", type=_positive_int, help="worker processes of the local "
                   "cluster (default: one per core)")
    w.add_argument("--x", metavar="PARAM", help="varied parameter on the plot's x axis "
                   "(default: the first --vary)")
    w.add_argument("--out", default="out", help="output directory (default: out)")
    w.set_defaults(func=cmd_sweep)


def build_parser():
    """The argparse parser of the ``acausal2d`` command."""
    from .. import __version__
    p = argparse.ArgumentParser(prog="acausal2d", description=__doc__.split("\n")[0])
    p.add_argument("--version", action="version", version="acausal2d " + __version__)
    sub = p.add_subparsers(dest="command", required=True)
    _add_simulate_parser(sub)
    c = sub.add_parser("check", help="print the structure of a model")
    c.add_argument("model_file")
    c.add_argument("--model")
    c.set_defaults(func=cmd_check)
    _add_compare_parser(sub)
    r = sub.add_parser("params", help="list a model's parameters with value, unit, rule and "
                       "description")
    r.add_argument("model_file")
    r.add_argument("--model")
    r.set_defaults(func=cmd_params)
    _add_sweep_parser(sub)
    t = sub.add_parser("study", help="run the studies the model declares (sweeps, plots over "
                       "an angle, ...) and write their figures and tables")
    t.add_argument("model_file")
    t.add_argument("names", nargs="*", help="studies to run (default: all)")
    t.add_argument("--model")
    t.add_argument("--list", action="store_true", help="list the model's studies")
    t.add_argument("--scheduler", help="Dask scheduler address for the studies' sweeps "
                   "(default: a local cluster; 'serial': this process)")
    t.add_argument("--workers", type=_positive_int, help="worker processes of the local "
                   "cluster (default: one per core)")
    t.add_argument("--out", default="out", help="output directory (default: out)")
    t.set_defaults(func=cmd_study)
    return p


def run_model_file(path, model=None, out="out"):
    """What running a model file does (its ``__main__`` block): simulate it
    (figures, CSV, animation) and run its declared studies, into ``out``.
    Returns the exit code."""
    from .loader import load_model
    from .study import declared_studies
    extra = ["--model", model] if model else []
    code = main(["simulate", path, "--out", out] + extra)
    if code == 0 and declared_studies(type(load_model(path, model))):
        code = main(["study", path, "--out", out] + extra)
    return code


def main(argv=None):
    """Entry point of the ``acausal2d`` command; returns the exit code (see
    the module docstring)."""
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as exc:        # argparse: --help, --version, or a usage error (2)
        return exc.code if isinstance(exc.code, int) else 2
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
