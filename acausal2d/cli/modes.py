"""``acausal2d modes``: natural frequencies, damping ratios and mode shapes
of a model at a time of its run or at its static equilibrium: the table,
``modes.json``, the mode page ``modes.html`` and, with ``--vary``, the
Campbell-like diagram of the frequencies over a swept parameter."""
import json
import os
import sys

from ..errors import Acausal2dError
from .args import _positive_int, add_run_options
from .linearize import add_point_arguments, point_options
from ..io.files import write_text
from ..io.loader import load_model
from ..io.output import OutputFolder


def _campbell(args, vary, options, out):
    """``--vary``: the frequencies over the swept parameter(s) (serial sweep)."""
    from ..analysis.campbell import campbell
    if options["at"] is not None:
        raise Acausal2dError("--vary linearises each point at the end of its run "
                             "(--stop-time) or at --equilibrium (of the start time), not at --at")
    table = campbell(args.model_file, vary, count=args.count,
                     equilibrium=options["equilibrium"], stop_time=args.stop_time,
                     progress=False if args.quiet else None,
                     params=options["params"], scheduler="serial", model_name=args.model)
    files = [table.to_csv(os.path.join(out, "campbell.csv"))]
    if len(table.failed) < len(table.rows):
        files.append(table.plot(os.path.join(out, "campbell.png")))
    for row in table.failed:
        print("  point %d failed: %s" % (row["point"], row["error"]))
    return files


def cmd_modes(args):
    """``acausal2d modes``: print the table; write modes.json and modes.html."""
    from ..analysis.equilibrium import NoEquilibrium
    from ..compiled import compile_model
    from ..visual.mode_page import write_mode_page
    from ..library.inputs import bind_inputs
    from ..analysis.sweep import grid_size, parse_vary
    vary = parse_vary(args.vary) if args.vary else None
    if vary:
        grid_size(vary)                 # a too large grid is refused before the run
    with OutputFolder(args.out, "modes") as tx:
        model = load_model(args.model_file, args.model)
        model, _ = bind_inputs(model)       # top-level RealInputs held at 0
        cm = compile_model(model)
        options = point_options(args)
        try:
            result = cm.modes(**options)
        except NoEquilibrium as exc:
            print("error: %s" % exc, file=sys.stderr)
            return 3
        files = [write_text(tx.file("modes.json"), json.dumps(result.to_dict(), indent=1)),
                 write_mode_page(result, tx.file("modes.html"))]
        if vary:
            files += _campbell(args, vary, options, tx.path)
    out = args.out
    lin = result.linearization
    where = "the static equilibrium" if lin.point.kind == "equilibrium" else \
        "t = %g s" % lin.point.t
    print("%s at %s (states: %s):" % (type(cm.model).__name__, where, ", ".join(lin.states)))
    print(result.table())
    print("-> %s" % ", ".join(os.path.join(out, os.path.basename(f)) for f in files))
    return 0


def add_parsers(sub):
    """``acausal2d modes``."""
    p = sub.add_parser("modes", help="natural frequencies, damping ratios and mode shapes; "
                       "an animated page of every mode")
    add_point_arguments(p)
    p.add_argument("--vary", action="append", metavar="PARAM=START:STOP:COUNT",
                   help="Campbell diagram: the frequencies over a swept parameter "
                   "(campbell.csv, campbell.png)")
    p.add_argument("--count", type=_positive_int, default=4,
                   help="frequencies in the Campbell diagram (default 4)")
    add_run_options(p, "stop_time")       # with --vary: each point linearised at its end
    p.set_defaults(func=cmd_modes)
