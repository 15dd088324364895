"""The body of ``POST /api/run`` (and ``/api/csv``) checked field by field.

A request is a JSON object::

    {"set": {"crank.r": [0.3, 0], "bodyPiston.m": 2.5},   # parameters (optional)
     "stop_time": 2.0,                                   # s, 0 < T <= the server's limit
     "intervals": 500,                                   # output intervals, 1 ... MAX_INTERVALS
     "signals": ["prismatic.s"],                         # columns answered (default: figures)
     "scene": true,                                      # also answer the animation page
     "session": "tab-1",                                 # runs of one session supersede
     "start": {"revoluteDrive.phi": 0.5}}                # start values replaced

``POST /api/start`` takes the same object with ``"drag": {"x": signal,
"y": signal, "to": [X, Y]}``: the point (x, y) moved to (X, Y) at the start.

Every field is optional.  Anything else -- malformed JSON, an unknown field,
an unknown parameter or signal, NaN, a value breaking its parameter's rule,
a stop time beyond the limit -- raises :class:`BadRequest` whose message
names the field (and the parameter) and what to change; the server answers
it with HTTP 400 ``{"error": message, "field": field}``.
"""
import difflib
import json
import math

from ..errors import Acausal2dError

MAX_INTERVALS = 20000
"""Most output intervals a request may ask for."""

MAX_BODY = 1 << 20
"""Largest request body in bytes."""

MAX_DEPTH = 4
"""Deepest nesting of a request's values (``{"drag": {"to": [X, Y]}}`` is 3)."""

MAX_NUMBER_TEXT = 400
"""Longest JSON number text read as a number (longer ones are taken as
infinite and refused by their field)."""

_FIELDS = ("set", "stop_time", "intervals", "signals", "scene", "session", "start", "drag")


class BadRequest(Acausal2dError):
    """A request the server refuses (HTTP 400); ``field`` names the field of
    the JSON body that is wrong."""

    def __init__(self, field, message):
        super().__init__("%s: %s" % (field, message) if field else message)
        self.field = field


class RunSpec:
    """A checked run request: ``params`` ({name: value} for
    :meth:`~acausal2d.compiled.CompiledModel.simulate`), ``stop_time``,
    ``intervals``, ``signals`` (names answered), ``scene`` (bool),
    ``session`` (str or None), ``start`` ({unknown: value}) and ``drag``
    (None, or {"x", "y", "to"} for ``/api/start``)."""

    def __init__(self, params, stop_time, intervals, signals, scene, session):
        self.params, self.stop_time, self.intervals = params, stop_time, intervals
        self.signals, self.scene, self.session = signals, scene, session
        self.start, self.drag, self.run = {}, None, None

    def key(self):
        """What determines the run's numbers (not which columns are answered)."""
        return (tuple(sorted((k, str(v)) for k, v in self.params.items())), self.stop_time,
                self.intervals, tuple(sorted(self.start.items())))


def parse_body(raw):
    """The JSON object of a request body (bytes); BadRequest if it is not one."""
    if len(raw) > MAX_BODY:
        raise BadRequest("body", "the request has %d bytes, at most %d are accepted"
                         % (len(raw), MAX_BODY))
    if not raw.strip():
        return {}
    try:
        body = json.loads(raw.decode("utf-8"), parse_int=_number, parse_float=_number)
    except RecursionError:
        raise BadRequest("body", "nested too deeply (at most %d levels are accepted)"
                         % MAX_DEPTH) from None
    except (UnicodeDecodeError, ValueError) as exc:
        raise BadRequest("body", "malformed JSON (%s); send an object such as "
                         '{"set": {"crank.r": [0.3, 0]}, "stop_time": 2}' % exc) from None
    if not isinstance(body, dict):
        raise BadRequest("body", "must be a JSON object, got %s" % type(body).__name__)
    for key, value in body.items():
        _check_depth(value, key, 1)
    unknown = sorted(set(body) - set(_FIELDS))
    if unknown:
        raise BadRequest(unknown[0], "unknown field; the fields are %s" % ", ".join(_FIELDS))
    return body


def _number(text):
    """A JSON number as a float; one too large for a float (a 401-digit
    integer, 1e400) becomes inf, which the field's check refuses by name."""
    if len(text) > MAX_NUMBER_TEXT:
        return math.inf
    return float(text)


def _check_depth(value, field, depth):
    """BadRequest naming ``field`` where ``value`` nests deeper than
    :data:`MAX_DEPTH` (a request has at most an object of lists)."""
    if depth > MAX_DEPTH:
        raise BadRequest(field, "nested too deeply (at most %d levels are accepted)" % MAX_DEPTH)
    items = value.items() if isinstance(value, dict) else \
        enumerate(value) if isinstance(value, list) else ()
    for key, item in items:
        _check_depth(item, "%s.%s" % (field, key) if isinstance(value, dict) else
                     "%s[%d]" % (field, key), depth + 1)


def _finite_number(field, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise BadRequest(field, "must be a number, got %s" % json.dumps(value)[:60])
    if not math.isfinite(value):
        raise BadRequest(field, "must be a finite number, got %r" % value)
    return value


def stop_time_of(body, default, limit):
    """The checked ``stop_time`` (s): 0 < T <= ``limit``."""
    if body.get("stop_time") is None:
        return default
    t = _finite_number("stop_time", body["stop_time"])
    if not 0 < t <= limit:
        raise BadRequest("stop_time", "must be above 0 s and at most %g s (the server's "
                         "limit, --max-stop-time), got %g" % (limit, t))
    return float(t)


def intervals_of(body, default):
    """The checked ``intervals``: a whole number 1 ... MAX_INTERVALS."""
    if body.get("intervals") is None:
        return default
    n = _finite_number("intervals", body["intervals"])
    if n != int(n) or not 1 <= n <= MAX_INTERVALS:
        raise BadRequest("intervals", "must be a whole number from 1 to %d, got %g"
                         % (MAX_INTERVALS, n))
    return int(n)


def params_of(body, compiled):
    """The checked ``set``: {parameter: float or tuple}; each value is
    checked against its declaration (its rule, its size, finite; field
    ``set.<name>``), then the rules between a component's parameters on
    all of them (``uMax >= uMin``; field ``set``)."""
    given = body.get("set") or {}
    if not isinstance(given, dict):
        raise BadRequest("set", 'must be an object {"comp.param": value}, got %s'
                         % json.dumps(given)[:60])
    params = {}
    for name, value in given.items():
        if isinstance(value, list):
            value = tuple(value)
        try:
            compiled.parameter_values({name: value}, rules=False)
        except Acausal2dError as exc:
            raise BadRequest("set.%s" % name, str(exc)) from None
        params[name] = value
    try:                       # the rules between parameters, on all the values given
        compiled.parameter_values(params)
    except Acausal2dError as exc:
        raise BadRequest("set", str(exc)) from None
    return params


def signals_of(body, names, default):
    """The checked ``signals``: a list of column names of the model."""
    chosen = body.get("signals")
    if chosen is None:
        return list(default)
    if not isinstance(chosen, list) or not all(isinstance(n, str) for n in chosen):
        raise BadRequest("signals", "must be a list of signal names, got %s"
                         % json.dumps(chosen)[:60])
    known = set(names)
    for name in chosen:
        if name not in known:
            close = difflib.get_close_matches(name, names, 6, 0.6)
            raise BadRequest("signals", "no signal %r in the model%s" % (
                name, "; similar: " + ", ".join(close) if close else ""))
    return list(dict.fromkeys(chosen))


def session_of(body):
    """The checked ``session``: a short string, or None."""
    s = body.get("session")
    if s is None:
        return None
    if not isinstance(s, str) or not 0 < len(s) <= 64:
        raise BadRequest("session", "must be a string of 1 to 64 characters, got %s"
                         % json.dumps(s)[:60])
    return s


def start_of(body, compiled):
    """The checked ``start``: {unknown: value}, names among the model's
    start values, values finite numbers."""
    given = body.get("start") or {}
    if not isinstance(given, dict):
        raise BadRequest("start", 'must be an object {"joint.phi": value}, got %s'
                         % json.dumps(given)[:60])
    for name, value in given.items():
        _finite_number("start.%s" % name, value)
        try:
            compiled.start_indices({name: value})
        except Acausal2dError as exc:
            raise BadRequest("start.%s" % name, str(exc)) from None
    return {k: float(v) for k, v in given.items()}


def drag_of(body, names):
    """The checked ``drag``: {"x": signal, "y": signal, "to": [X, Y]}."""
    drag = body.get("drag")
    if not isinstance(drag, dict) or set(drag) != {"x", "y", "to"}:
        raise BadRequest("drag", 'must be an object {"x": signal, "y": signal, "to": [X, Y]}, '
                         "got %s" % json.dumps(drag)[:80])
    for key in ("x", "y"):
        if drag[key] not in names:
            raise BadRequest("drag.%s" % key, "no signal %s in the model" % json.dumps(drag[key]))
    to = drag["to"]
    if not isinstance(to, list) or len(to) != 2:
        raise BadRequest("drag.to", "must be [X, Y], got %s" % json.dumps(to)[:60])
    return {"x": drag["x"], "y": drag["y"],
            "to": [float(_finite_number("drag.to", v)) for v in to]}


def parse_run(raw, compiled, defaults, drag=False):
    """A :class:`RunSpec` from the request body ``raw`` (bytes);
    ``defaults``: {"stop_time", "max_stop_time", "intervals", "signals"};
    ``drag``: the body must have a ``drag`` (``/api/start``), else must not."""
    body = parse_body(raw)
    scene = body.get("scene", False)
    if not isinstance(scene, bool):
        raise BadRequest("scene", "must be true or false, got %s" % json.dumps(scene)[:60])
    if not drag and "drag" in body:
        raise BadRequest("drag", "only POST /api/start takes a drag")
    spec = RunSpec(params_of(body, compiled),
                   stop_time_of(body, defaults["stop_time"], defaults["max_stop_time"]),
                   intervals_of(body, defaults["intervals"]),
                   signals_of(body, compiled.names, defaults["signals"]), scene,
                   session_of(body))
    spec.start = start_of(body, compiled)
    if drag:
        spec.drag = drag_of(body, compiled.names)
    return spec
