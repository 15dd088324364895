"""``acausal2d simulate``: run a model file and write the CSV, the figures,
the animation page and the run's manifest."""
import os
import sys
import warnings

from .args import MODEL_FILE_HELP
from ..errors import Acausal2dError
from .args import _check_names, _parse_set
from ..analysis.check import grounded_lines, unconnected_line
from ..compiler.connectors import connector_report
from ..compiler.flatten import grounded_ports
from ..analysis.slider_ranges import range_lines, slider_ranges
from ..io.loader import load_model
from ..runtime.event_words import event_line
from ..usercode import user_error_text
from .args import add_run_options, run_options
from ..io.output import OutputFolder


def _plot_specs(args, cm):
    """The figures ``simulate`` writes: --plot groups, else the model's
    declared ``figures``, else one figure per declared output; --x applies
    to all of them.  Every signal name is checked before the run."""
    from ..visual.plotting import declared_figures, parse_groups
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


def _animation_options(args, cm):
    from ..visual.scene import arrow_signals
    arrows = [a.strip() for a in args.arrows.split(",") if a.strip()] if args.arrows else []
    arrow_signals(arrows, cm.names, cm.model)      # names checked before the run
    if args.signal:
        _check_names([args.signal], cm, "--signal")
    poles = None
    if args.poles:
        from ..analysis.poles import check_links
        from ..visual.scene import parse_links
        poles = parse_links(args.poles)
        check_links(poles, cm.names)           # before the run
    return {"arrows": arrows, "signal": args.signal, "autoplay": args.autoplay, "poles": poles}


def _print_summary(model, res, out, pngs, extra=(), table="result.csv", verbose=False):
    """The run's summary: singular positions, early stop, solver counts,
    the files written (``table``: the result file, ``extra``: those the
    model wrote itself), states and the ports fixed to ground because nothing
    is connected to them."""
    from ..visual.scene import NO_GEOMETRY, has_geometry
    for sing in res.singularities:
        print("  %s at t=%.6g in %s" % (sing["kind"], sing["time"], ", ".join(sing["elements"])))
    if res.stopped:
        print("  " + res.stopped)
    st = res.stats
    print("%s: simulated %.4g s in %.3f s (compile %.3f s%s); %d steps, %d output points, "
          "%d events, %d state re-selections, %d residual evaluations -> %s/ (%s, "
          "%d plot%s%s, diagram.svg%s)" % (
              type(model).__name__, res.time[-1] - res.time[0], st["wall_time"],
              st["compile_time"], ", native code %.3f s" % st["native_compile_time"]
              if st.get("native_compile_time") else "", st["steps"], len(res.time),
              st["events"], st["reselections"], st["nfev"], out, table, len(pngs),
              "" if len(pngs) == 1 else "s",
              ", animation.html" if has_geometry(model) else "",
              "".join(", " + os.path.basename(f) for f in extra)))
    if not has_geometry(model):
        print("  " + NO_GEOMETRY % type(model).__name__)
    for note in (getattr(res, "native_notes", None) or []) if verbose else []:
        print("  native: " + note)
    states = getattr(res, "states", None) or []
    print("  states: %s" % (", ".join(states) if states else "none (the motion is prescribed)"))
    for line in grounded_lines(grounded_ports(res.model.system.flat_equations),
                               "  grounded ports: "):
        print(line)
    _print_connectors(connector_report(res.model.model))
    _print_events(res, verbose)
    for line in range_lines(slider_ranges(res)):
        print(line)


def _print_connectors(report):
    """The unconnected connectors in one line; a warning on stderr for each
    element that passes power to a side connected to nothing."""
    line = unconnected_line(report)
    if line:
        print(line)
    for text in report.suspect_texts():
        print("warning: %s; a connect() missing?" % text, file=sys.stderr)


def _print_events(res, verbose=False, first=5):
    """The first events in the elements' words (``Brake 'brake': stuck ->
    sliding forward at t = 0.5000033 s``), with ``verbose`` also the
    relation expressions that switched, and how many more there were."""
    texts = getattr(res, "event_texts", res.events)
    for (t, words), (_, raw) in list(zip(texts, res.events))[:first]:
        print("  " + event_line(t, words))
        if verbose and raw != words:
            print("      relations: %s" % raw)
    if len(res.events) > first:
        print("  ... and %d more events" % (len(res.events) - first))


def cmd_simulate(args):
    """``acausal2d simulate``: run a model file; write the CSV, plots and
    animation into ``--out`` as one transaction (:class:`~acausal2d.io.
    output.OutputFolder`: checked and locked before the run, moved in with
    its manifest at the end, nothing left on a failure)."""
    from ..visual.figure_process import FigureProcess
    with OutputFolder(args.out, "simulate") as tx:
        drawer = FigureProcess.start()     # imports matplotlib on the other core meanwhile
        try:
            res, settings = _run(args)
            pngs, extra = _write_outputs(res, tx, settings, args, drawer)
        finally:
            if drawer is not None:
                drawer.close()
    model = res.model.model
    _print_summary(model, res, args.out, pngs, [tx.final(f) for f in extra], _result_name(args),
                   args.verbose)
    if res.stopped:
        print("stopped early: %s" % res.stopped, file=sys.stderr)
        return 3
    return 0


def _run(args):
    """Load, compile and simulate the model file: (result, settings)."""
    from ..compiled import compile_model
    options = run_options(args, native=args.native)   # checked before the model is compiled
    cm = compile_model(load_model(args.model_file, args.model))
    settings = _simulate_settings(args, cm)
    res = cm.simulate(params=settings["params"], options=options)
    return res, settings


def _simulate_settings(args, cm):
    """Plots, animation, traces and parameters, all checked before the run."""
    from ..visual.scene import trace_signals
    traces = [t.strip() for t in args.trace.split(",")] if args.trace else []
    trace_signals(traces, cm.names)
    transfer = None
    if args.transfer:
        from ..visual.plotting import parse_orders
        transfer = parse_orders(args.transfer)
        if not args.x:
            raise Acausal2dError("--transfer needs --x DRIVE: the drive coordinate the "
                                 "transfer functions are taken over (e.g. --x crank.phi)")
    return {"traces": traces, "specs": _plot_specs(args, cm), "transfer": transfer,
            "animation": _animation_options(args, cm), "params": _parse_set(args.set)}


def _result_name(args):
    """``result.csv`` or ``result.mat`` (``--result-format``)."""
    return "result.mat" if args.result_format == "mat" else "result.csv"


def _write_outputs(res, tx, settings, args, drawer=None):
    """CSV, figures (drawn by ``drawer``, a :class:`~acausal2d.visual.
    figure_process.FigureProcess`, if given), animation and the files the
    model writes itself, into the transaction ``tx``'s folder (the manifest
    lists every file there); returns the figures and the model's files."""
    from ..visual.plotting import draw_jobs, figure_jobs
    from ..visual.scene import has_geometry
    out = tx.path
    if settings["transfer"]:
        from ..visual.plotting import write_transfer_figures
        jobs = None
        pngs = write_transfer_figures(res, out, settings["specs"], settings["transfer"],
                                      args.format)
    else:
        jobs = figure_jobs(res, out, settings["specs"], args.format)
        if drawer is not None:
            drawer.submit(jobs)             # drawn by the child while the files below are written
    table = tx.file(_result_name(args))
    if table.endswith(".mat"):
        res.to_mat(table)
    else:
        res.to_csv(table)
    if has_geometry(res.model.model):
        res.animate(tx.file("animation.html"), traces=settings["traces"],
                    **settings["animation"])
    if res.model is not None:
        _write_diagram(res.model.model, tx.file("diagram.svg"))
    if jobs is not None:
        pngs = drawer.collect() if drawer is not None else draw_jobs(jobs)
    if not settings["specs"]:
        print("  (the model declares no outputs; choose signals to plot with --plot a,b)")
    tx.info.update(model=type(res.model.model).__name__ if res.model else None,
                   stopped=res.stopped, units=_units(res))
    return pngs, _model_files(res, out)


def _write_diagram(model, path):
    """The model's diagram beside the results; a drawing that fails is a
    warning naming why, never the loss of the run."""
    from ..visual.diagram import write_diagram
    try:
        write_diagram(model, path)
    except (KeyboardInterrupt, MemoryError, OSError):
        raise
    except Exception as exc:          # noqa: BLE001 - the run's results matter more
        warnings.warn("diagram.svg is not written: %s: %s" % (type(exc).__name__, exc))


def _units(res):
    """{signal: unit} of the declared units, kept in the manifest so that
    ``compare`` labels its plot axes of a result CSV with them."""
    return {n: u for n in res.names if (u := res.unit(n))}


def _model_files(res, out):
    """Files the model writes itself after a run: its optional method
    ``write_outputs(result, folder)`` returns their paths (e.g. the contour
    plots and cam contour files of the band synthesis models)."""
    model = res.model.model if res.model else None
    write = getattr(model, "write_outputs", None)
    if not callable(write):
        return []
    try:
        return [os.fspath(p) for p in write(res, out) or ()]
    except (Acausal2dError, KeyboardInterrupt, MemoryError):
        raise
    except Exception as exc:            # noqa: BLE001 - the model author's code
        raise Acausal2dError(user_error_text("%s.write_outputs" % type(model).__name__, exc)
                             + "\n  (nothing of this run is kept; fix write_outputs in the "
                             "model file)") from exc


def add_parsers(sub):
    """``acausal2d simulate``."""
    s = sub.add_parser("simulate", help="simulate a model file; write CSV, plots, animation")
    s.add_argument("model_file", help=MODEL_FILE_HELP)
    s.add_argument("--model", help="model class in the file (if it defines several)")
    s.add_argument("--set", action="append", metavar="COMP.PARAM=VALUE",
                   help="parameter value (vectors as 1,0); repeatable")
    add_run_options(s, "stop_time", "rtol", "atol", "intervals", "max_steps", "max_wall_time")
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
    s.add_argument("--transfer", metavar="ORDERS", help="with --x DRIVE: plot the transfer "
                   "functions of these orders (0,1,2: q, dq/dDRIVE, d2q/dDRIVE2, Ebert 2015, eq. "
                   "2.2-2.4) of each plotted signal instead of the signals")
    s.add_argument("--poles", metavar="LINKS", help="draw the instantaneous poles of these "
                   "links on a layer of the animation: label=link pairs, e.g. "
                   "1=ground,2=A0A,3=AB,4=B0B (frames, node constraints or x:y:phi signals)")
    s.add_argument("--native", choices=("auto", "now", "off"), help="native code: auto (default, "
                   "$ACAUSAL2D_NATIVE): a structure not compiled yet runs natively on CasADi's "
                   "C API and is compiled in the background after the run; now: compile "
                   "first; off: the Python path only")
    s.add_argument("--result-format", choices=("csv", "mat"), default="csv",
                   help="result.csv (default) or result.mat in Dymola's result format (MAT v4, "
                   "read by Modelica plotting tools, DyMat, buildingspy)")
    s.add_argument("--out", default="out", help="output directory (default: out)")
    s.add_argument("--verbose", action="store_true", help="also print the relation "
                   "expressions that switched at each event and how the native code was "
                   "chosen")
    s.set_defaults(func=cmd_simulate)
