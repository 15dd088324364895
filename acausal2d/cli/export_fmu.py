"""``acausal2d export-fmu``: a model as an FMI 2.0 FMU (native code, no
Python needed by the importer); see :func:`acausal2d.fmu.export_fmu`."""
from .args import MODEL_FILE_HELP, MODEL_HELP
from ..io.loader import load_model
from .args import _parse_set, add_run_options, run_options
from ..io.output import terminate_as_interrupt


def cmd_export_fmu(args):
    """``acausal2d export-fmu MODEL.py [--model NAME] [--kind me|cs] [--out F]
    [--fixed-states] [--set COMP.PARAM=VALUE ...]``."""
    from ..fmu import export_fmu
    with terminate_as_interrupt():         # SIGTERM cleans up like Ctrl-C
        model = load_model(args.model_file, args.model)
        out = export_fmu(model, kind=args.kind, out=args.out, fixed_states=args.fixed_states,
                         options=run_options(args), params=_parse_set(args.set) or None)
    print("%s: %s FMU (FMI 2.0) written to %s" % (
        type(model).__name__, "Model Exchange" if args.kind == "me" else "Co-Simulation", out))
    return 0


def add_parsers(sub):
    """``acausal2d export-fmu``."""
    e = sub.add_parser("export-fmu", help="export a model as an FMI 2.0 FMU (Model Exchange "
                       "or Co-Simulation) with native binaries and C sources")
    e.add_argument("model_file", help=MODEL_FILE_HELP)
    e.add_argument("--model", help=MODEL_HELP)
    e.add_argument("--kind", choices=("me", "cs"), default="me",
                   help="me: Model Exchange (the importer integrates), cs: Co-Simulation "
                   "(integrator inside the FMU)")
    e.add_argument("--out", help="the .fmu file (default: <ModelName>.fmu)")
    e.add_argument("--fixed-states", action="store_true",
                   help="export a model with dynamic state selection with the states chosen "
                   "at the start (the FMU stops with an error where they no longer serve)")
    e.add_argument("--set", action="append", metavar="COMP.PARAM=VALUE",
                   help="parameter value exported instead of the model's (vectors as 1,0); "
                   "repeatable.  A parameter read while the model is compiled is a constant "
                   "of the FMU: this is how another value of it is exported")
    add_run_options(e, "stop_time", "rtol", quiet=False)    # the FMU's default experiment
    e.set_defaults(func=cmd_export_fmu)
