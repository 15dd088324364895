"""``acausal2d diagram``: the model drawn from its code -- a box per
component, a line per ``connect``, every unconnected connector marked with
what happens to it (see :mod:`acausal2d.visual.diagram`)."""
import sys

from ..io.loader import load_model


def cmd_diagram(args):
    """``acausal2d diagram``: write the model's diagram (SVG, or HTML in
    which each sub-model's box opens its own diagram)."""
    from ..visual.diagram import check_diagram_path, structure, write_diagram
    check_diagram_path(args.out)
    model = load_model(args.model_file, args.model)
    write_diagram(model, args.out)
    st = structure(model)
    loose = [p for b in st.components for p in b.ports.values() if p.fate]
    print("%s: %d components, %d connections, %d unconnected connectors (%s) -> %s"
          % (type(model).__name__, len(st.components), len(st.lines), len(loose),
             ", ".join("%d %s" % (n, f) for f, n in _count(p.fate for p in loose)) or "none",
             args.out))
    errors = [p.path for p in loose if p.fate == "error"]
    if errors:
        print("  must be connected: %s" % ", ".join(errors), file=sys.stderr)
    return 0


def _count(items):
    out = {}
    for item in items:
        out[item] = out.get(item, 0) + 1
    return sorted(out.items())


def add_parsers(sub):
    """``acausal2d diagram``."""
    d = sub.add_parser("diagram", help="draw a model: its components, connections and "
                       "unconnected connectors (SVG, or HTML with its sub-models)")
    d.add_argument("model_file")
    d.add_argument("--model", help="model class in the file (if it defines several)")
    d.add_argument("--out", default="diagram.svg", help="the file to write: .svg (default "
                   "diagram.svg) or .html (each sub-model's box opens its own diagram)")
    d.set_defaults(func=cmd_diagram)
