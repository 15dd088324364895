"""``acausal2d explore``: the model in a local web page -- change a
parameter, see the mechanism and its curves change at once (see
:mod:`acausal2d.explore`)."""
import socket
import sys

from .args import MODEL_FILE_HELP
from ..errors import Acausal2dError
from .args import _positive_float


def _check_address(host, port):
    """The server can listen on host:port (else an error naming --host or
    --port), checked before the model is compiled."""
    try:
        family = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0][0]
    except socket.gaierror as exc:
        raise Acausal2dError("--host %s: not an address of this machine (%s); the default is "
                             "127.0.0.1" % (host, exc)) from None
    with socket.socket(family, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind((host, port))
        except OSError as exc:
            raise Acausal2dError("--port %d on %s: %s; choose another port (--port 0 takes a "
                                 "free one)" % (port, host, exc.strerror or exc)) from None


def cmd_explore(args):
    """``acausal2d explore``: compile the model, make one run to warm it,
    then serve the page until Ctrl-C."""
    try:
        import starlette  # noqa: F401
        import uvicorn  # noqa: F401
    except ImportError as exc:
        raise Acausal2dError("acausal2d explore needs the web server packages (%s); install "
                             "them with: pip install 'acausal2d[explore]'" % exc.name) from None
    from ..explore.runner import Explorer
    from ..explore.server import serve
    if not 0 <= args.port <= 65535:
        raise Acausal2dError("--port must be 0 ... 65535, got %d" % args.port)
    _check_address(args.host, args.port)
    explorer = Explorer(args.model_file, args.model, args.max_stop_time, args.max_wall_time)
    explorer.warm()
    print("acausal2d explore: %s from %s; Ctrl-C stops the server"
          % (type(explorer.compiled.model).__name__, args.model_file), file=sys.stderr)
    return serve(explorer, args.host, args.port, args.open,
                 announce=lambda url: print(url, flush=True))


def add_parsers(sub):
    """``acausal2d explore``."""
    s = sub.add_parser("explore", help="a local web page: change parameters and start "
                       "positions, see the mechanism and its curves change at once")
    s.add_argument("model_file", help=MODEL_FILE_HELP)
    s.add_argument("--model", help="model class in the file (if it defines several)")
    s.add_argument("--port", type=int, default=8765, help="TCP port (default 8765; 0: a free "
                   "one, printed)")
    s.add_argument("--host", default="127.0.0.1", help="address to listen on (default "
                   "127.0.0.1: this machine only)")
    s.add_argument("--open", action="store_true", help="open the page in the web browser")
    s.add_argument("--max-stop-time", type=_positive_float, metavar="SECONDS",
                   help="longest run a request may ask for (default: ten times the model's "
                   "experiment stop time)")
    s.add_argument("--max-wall-time", type=_positive_float, default=10.0, metavar="SECONDS",
                   help="wall-clock budget of one run (default 10); a longer run answers "
                   "what it has, marked stopped")
    s.set_defaults(func=cmd_explore)
