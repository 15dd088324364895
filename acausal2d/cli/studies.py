"""``acausal2d sweep`` (parameter studies on Dask) and ``acausal2d study``
(the studies a model declares)."""

from .args import MODEL_FILE_HELP, MODEL_HELP
from ..errors import Acausal2dError
from .args import _check_names, _nonnegative, _parse_set, add_dask_options
from ..io.loader import load_model
from ..analysis.study import declared_studies, run_studies
from .args import add_run_options, \
    run_options
from ..io.output import OutputFolder


def _sweep_settings(args, cm, vary):
    """Points, fixed values and outputs of ``acausal2d sweep`` (``vary``:
    the parsed --vary), checked against the compiled model before anything
    runs."""
    from ..analysis.sweep import expand_params, grid_points
    fixed = _parse_set(args.set)
    known = set(cm.parameter_names)
    for name in list(expand_params({c: 0 for c in vary})) + list(fixed):
        if name not in known:
            close = [n for n in cm.parameter_names if name.split(".")[-1] in n][:8]
            raise Acausal2dError("--vary/--set: unknown parameter %r%s" % (
                name, "; similar: " + ", ".join(close) if close else ""))
    cm.parameter_values(fixed, structural=True, rules=False)   # each against its rule (the
    # rules between parameters and a structural one are the runs', with the varied values)
    outputs = [n.strip() for n in args.outputs.split(",") if n.strip()] if args.outputs \
        else list(cm.outputs)
    _check_names(outputs, cm, "--outputs")
    options = _check_run_settings(args, cm)
    if args.x is not None and args.x not in vary:
        raise Acausal2dError("--x %r is not a varied parameter; varied: %s"
                             % (args.x, ", ".join(vary)))
    return grid_points(vary), fixed, outputs, options


def _check_run_settings(args, cm):
    """The run options of a sweep and --at, checked once before the points
    run (each point would fail alike); returns the RunOptions."""
    options = run_options(args)
    stop = cm.run_options(options).stop_time
    if args.at is not None and args.at > stop:
        raise Acausal2dError("--at %g lies after the end of the run (%g s)" % (args.at, stop))
    return options


def cmd_sweep(args):
    """``acausal2d sweep``: a parameter study on Dask; write sweep.csv and sweep.png."""
    from ..analysis.sweep import ModelSpec, compiled_model, grid_size, parse_vary, sweep
    vary = parse_vary(args.vary)
    grid_size(vary)                         # a too large grid is refused before anything
    with OutputFolder(args.out, "sweep") as tx:
        cm = compiled_model(ModelSpec(args.model_file, args.model))  # errors here exit with 2
        points, fixed, outputs, options = _sweep_settings(args, cm, vary)
        result = sweep(args.model_file, points=points, params=fixed, outputs=outputs,
                       at=args.at, options=options, scheduler=args.scheduler,
                       workers=args.workers, model_name=args.model)
        files = [result.to_csv(tx.file("sweep.csv"))]
        if outputs and len(result.failed) < len(result.rows):
            files.append(result.plot(tx.file("sweep.png"), x=args.x))
        tx.info.update(model=type(cm.model).__name__, points=len(result.rows),
                       failed=len(result.failed))
    for row in result.failed:
        print("  point %d failed: %s" % (row["point"], row["error"]))
    print("%s: %s -> %s" % (type(cm.model).__name__, result.summary(),
                            ", ".join(tx.final(f) for f in files)))
    return 0


def cmd_study(args):
    """``acausal2d study``: run (or list) the model's declared studies."""
    model = load_model(args.model_file, args.model)
    if args.list:
        studies = declared_studies(type(model))
        for name, st in studies.items():
            print("%-16s %s" % (name, st.doc))
        if not studies:
            print("%s declares no studies" % type(model).__name__)
        return 0
    with OutputFolder(args.out, "study", merge=True) as tx:    # beside simulate's files
        files = run_studies(args.model_file, model, args.names, tx.path,
                            {"scheduler": args.scheduler, "workers": args.workers,
                             "progress": not args.quiet})
        tx.info["model"] = type(model).__name__
    files = [tx.final(f) for f in files]
    print("%s: %d file%s -> %s" % (type(model).__name__, len(files),
                                   "" if len(files) == 1 else "s", ", ".join(files)))
    return 0


def add_parsers(sub):
    """``acausal2d sweep`` and ``acausal2d study``."""
    w = sub.add_parser("sweep", help="parameter study on Dask: simulate every combination of "
                       "the --vary values; write sweep.csv and sweep.png")
    w.add_argument("model_file", help=MODEL_FILE_HELP)
    w.add_argument("--model", help=MODEL_HELP)
    w.add_argument("--vary", action="append", required=True, metavar="PARAM=START:STOP:COUNT",
                   help="values of a parameter: START:STOP:COUNT or v1,v2,...; tie parameters "
                   "to one value with a.p,b.p=...; repeatable (all combinations)")
    w.add_argument("--set", action="append", metavar="COMP.PARAM=VALUE",
                   help="a parameter value held for every point; repeatable")
    w.add_argument("--outputs", help="comma-separated signals recorded per point (default: "
                   "the model's outputs)")
    w.add_argument("--at", type=_nonnegative, metavar="T",
                   help="record the outputs at time T (default: at the end of the run)")
    add_run_options(w, "stop_time", "rtol", "intervals")
    add_dask_options(w, "address of a running Dask scheduler (tcp://host:8786);"
                     " default: a local cluster; 'serial': run in this process")
    w.add_argument("--x", metavar="PARAM", help="varied parameter on the plot's x axis "
                   "(default: the first --vary)")
    w.add_argument("--out", default="out", help="output directory (default: out)")
    w.set_defaults(func=cmd_sweep)
    t = sub.add_parser("study", help="run the studies the model declares (sweeps, plots over "
                       "an angle, ...) and write their figures and tables")
    t.add_argument("model_file", help=MODEL_FILE_HELP)
    t.add_argument("names", nargs="*", help="studies to run (default: all)")
    t.add_argument("--model", help=MODEL_HELP)
    t.add_argument("--list", action="store_true", help="list the model's studies")
    add_run_options(t)
    add_dask_options(t, "Dask scheduler address for the studies' sweeps "
                     "(default: a local cluster; 'serial': this process)")
    t.add_argument("--out", default="out", help="output directory (default: out)")
    t.set_defaults(func=cmd_study)
