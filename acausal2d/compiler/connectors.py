"""The connector report: every connector nothing is connected to, grouped
by what the flattening makes of it, and the elements that pass power from
one side to a side left loose (likely a forgotten ``connect``).

An unconnected connector (:mod:`acausal2d.compiler.flatten`) is

- fixed to ground where it is declared with ``ground=`` (the triangle ports
  of Ebert (2015), Tabelle 4.1; a gear's or a brake's ``support``), or
  held by its element's own equations (a joint's drive ``support``, named
  in the element's ``held_connectors``);
- free otherwise: its flows are zero (a frame or flange with no force or
  torque on it, a hydraulic port closed: no flow);
- an error if it is a signal input (nothing gives it a value);
- a band port left open (no band wound there).

A signal output nothing reads is not listed: the value is still in the
result.  The model's own connectors (the inputs of a model exported as an
FMU) are not its components' and are not listed either.
"""
import copy
from contextlib import contextmanager
from dataclasses import dataclass, field

from ..errors import (Acausal2dError, InitializationError, SimulationError, StartPoseError,
                      StructuralError)


@dataclass
class ConnectorReport:
    """What :func:`connector_report` found: ``grounded`` {path: potentials
    fixed}; the paths ``held`` (fixed by their element's own equations),
    ``free``, ``closed`` (hydraulic), ``open_bands`` and ``inputs``
    (unconnected signal inputs); ``suspects`` as (component path, connected
    side's paths, loose side's paths)."""
    grounded: dict = field(default_factory=dict)
    held: list = field(default_factory=list)
    free: list = field(default_factory=list)
    closed: list = field(default_factory=list)
    open_bands: list = field(default_factory=list)
    inputs: list = field(default_factory=list)
    suspects: list = field(default_factory=list)

    def loose(self):
        """The loose connectors of the suspect elements, in model order,
        each once (the likely cause of a failure)."""
        out = []
        for _, _, loose in self.suspects:
            out += [p for p in loose if p not in out]
        return out

    def unconnected(self):
        """Every unconnected connector's path."""
        return (list(self.grounded) + self.held + self.free + self.closed + self.open_bands
                + self.inputs)

    def suspect_texts(self):
        """One sentence per suspect element."""
        return ["%s passes power between %s and %s, but %s %s connected to nothing"
                % (path, _names(side), _names(loose), _names(loose),
                   "is" if len(loose) == 1 else "are")
                for path, side, loose in self.suspects]

    def likely_cause(self):
        """The sentence a failure a loose connector typically causes starts
        with: the loose sides of the suspect elements ('' when there are
        none)."""
        loose = self.loose()
        if not loose:
            return ""
        return ("Likely cause: %s %s connected to nothing (%s; a connect() missing?). "
                % (", ".join(loose), "is" if len(loose) == 1 else "are",
                   "; ".join(self.suspect_texts())))

    def unconnected_note(self):
        """Where no element is suspect, the note such a failure ends with:
        the connectors left unconnected and fixed to ground or free (at
        most :data:`MAX_NAMED`); '' when there are none."""
        if self.suspects:
            return ""
        named = ["%s (fixed to ground)" % p for p in self.grounded] + \
            ["%s (free)" % p for p in self.free + self.closed]
        if not named:
            return ""
        more = len(named) - MAX_NAMED
        return (" Unconnected (a likely cause if a connect() is missing): %s%s."
                % (", ".join(named[:MAX_NAMED]),
                   " and %d more (acausal2d check lists them)" % more if more > 0 else ""))


MAX_NAMED = 24
"""The most unconnected connectors a failure's message names."""


def _names(paths):
    return ", ".join(paths)


def inside_connected(model):
    """Ids of the connectors that a ``connect`` of an enclosing component
    (or of their own component's parent) joins to something: the
    connectors the flattening does not close (the sets of Ebert (2015), eq. 4.1)."""
    out = set()
    for scope in model.components():
        for a, b in scope._connections:
            out.update(id(c) for c in (a, b) if c.owner is not scope)
    return out


def _potential_ground(comp, conn):
    """The potentials an unconnected ``ground=`` connector fixes (those of
    a ground given as a function are read only where it evaluates)."""
    ground = conn.ground
    if callable(ground):
        try:
            ground = ground(comp)
        except Exception:           # noqa: BLE001 - named by the flattening itself
            return []
    return list(ground)


def _classify(report, comp, conn):
    if conn.ground is not None:
        report.grounded[conn.path] = _potential_ground(comp, conn)
    elif conn._name in comp.held_connectors:
        report.held.append(conn.path)
    elif conn.signal == "input":
        report.inputs.append(conn.path)
    elif conn.signal == "output":
        return
    elif conn.one_to_one:
        report.open_bands.append(conn.path)
    elif conn.kind == "HydraulicPort":
        report.closed.append(conn.path)
    else:
        report.free.append(conn.path)


def _loose(comp, side, connected):
    """Whether ``side`` (connectors of ``comp``) is loose: it has power
    connectors (not signal outputs), none connected, grounded or held."""
    power = [c for c in side if c.signal != "output"]
    return bool(power) and not any(id(c) in connected or c.ground is not None
                                   or c._name in comp.held_connectors for c in power)


def _suspect(comp, connected):
    """(path, connected side, loose side) of an element whose
    ``power_sides`` have one side connected and another loose, or None."""
    sides = [[comp._connectors[n] for n in names if n in comp._connectors]
             for names in comp.power_sides]
    sides = [side for side in sides if side]
    for k, side in enumerate(sides):
        if not _loose(comp, side, connected):
            continue
        driven = [c.path for j, other in enumerate(sides) if j != k
                  for c in other if id(c) in connected]
        if driven:
            return (comp.path, driven, [c.path for c in side if c.signal != "output"])
    return None


def connector_report(model):
    """The :class:`ConnectorReport` of ``model`` (a Component instance,
    its outer components resolved, as after flattening)."""
    connected = inside_connected(model)
    report = ConnectorReport()
    for comp in model.components():
        if comp is model:
            continue
        for conn in comp._connectors.values():
            if id(conn) not in connected:
                _classify(report, comp, conn)
        found = _suspect(comp, connected)
        if found is not None:
            report.suspects.append(found)
    return report


FIRST_FAILURES = ("State selection failed", "No consistent initial values")
"""Message starts of the failures that a loose connector typically causes
(besides every structural error and an unknown start pose)."""


def _caused_by_structure(exc):
    """Whether ``exc`` is a failure a loose connector typically causes: a
    structural error, a start pose that cannot be known, a part that cannot
    assemble, no consistent initial values or a failed state selection."""
    text = str(exc)
    return isinstance(exc, (StructuralError, StartPoseError)) or text.startswith(FIRST_FAILURES) \
        or " cannot assemble at the start" in text


def _run_failures():
    return (InitializationError, SimulationError, StructuralError)


def _any_failure(exc):
    """Whether ``exc`` is a failure of compiling, initializing or running
    (not a wrong argument or parameter value)."""
    return isinstance(exc, _run_failures())


@contextmanager
def loose_connectors_first(model):
    """Context manager around compiling, initializing or simulating
    ``model``: a failure of the run is raised again, of the same kind, with
    the loose sides of the suspect elements named first
    (:meth:`ConnectorReport.likely_cause`); a failure a loose connector
    typically causes (:func:`_caused_by_structure`) in a model without
    suspects ends with its unconnected connectors
    (:meth:`ConnectorReport.unconnected_note`).  The original is chained."""
    try:
        yield
    except Acausal2dError as exc:
        if "connect() missing" in str(exc):
            raise
        structural = _caused_by_structure(exc)
        if not (structural or _any_failure(exc)):
            raise
        report = connector_report(model)
        first = report.likely_cause()      # suspects: named before any failure of the run
        last = report.unconnected_note() if structural else ""
        if not (first or last):
            raise
        named = copy.copy(exc)
        named.args = (first + str(exc) + last,) + tuple(exc.args[1:])
        raise named from exc
