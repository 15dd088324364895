"""Structure report of a model: sizes, states, structural index, closed
loops and the degree of freedom by the dissertation's eq. 2.1 next to the
structural one."""
import textwrap
from typing import Any
from collections import Counter


from ..compiler.connectors import connector_report
from ..compiler.flatten import grounded_ports
from ..language.unionfind import UnionFind, connector_sets
import casadi as ca


class CheckReport:
    """What :func:`check` found; ``str(report)`` is the printed form."""

    def __init__(self, **fields):
        self.__dict__.update(fields)

    def __str__(self):
        lines = ["Model %s" % self.name,
                 "  components:        %d (%s)" % (self.n_components, self.component_kinds),
                 "  equations:         %d flattened, %d after alias elimination, "
                 "%d after index reduction" % (self.n_flat_equations, self.n_equations,
                                               self.n_reduced_equations),
                 "  unknowns:          %d (%d eliminated as aliases)"
                 % (self.n_variables, self.n_aliases),
                 "  parameters:        %d" % self.n_parameters,
                 "  structural index:  %d%s" % (self.structural_index,
                                                 " (equations differentiated up to %d times)"
                                                 % (self.structural_index - 1)
                                                 if self.structural_index > 1 else ""),
                 "  states:            %s" % (", ".join(self.states) or "none"),
                 "  closed loops:      %d" % self.loops]
        lines += grounded_lines(self.grounded)
        lines += connector_lines(self.connectors)
        if self.nodes is not None:
            lines += _node_lines(self.nodes)
        if self.grubler is not None:
            lines.append("  degree of freedom: %d by Ebert (2015) eq. 2.1 (n = %d links with ground, "
                         "g = %d joints%s), %d structural (position states)%s"
                         % (self.grubler, self.links, self.joints, _terms(self.dof_terms),
                            self.structural_dof, _with_grounded(self.grounded)))
            if self.structural_dof < self.grubler:
                lines.append("                     (%d prescribed: drives that give the motion "
                             "as a function of time, or constraints eq. 2.1 does not see)"
                             % (self.grubler - self.structural_dof))
            elif self.structural_dof > self.grubler:
                lines.append("                     (%d more position states than eq. 2.1 "
                             "counts: bodies or couplings without a declared topology)"
                             % (self.structural_dof - self.grubler))
        else:
            lines.append("  degree of freedom: %d structural (position states); no planar "
                         "joints declared for eq. 2.1" % self.structural_dof)
        return "\n".join(lines)


def grounded_lines(grounded, head="  grounded ports:    "):
    """The ports fixed to ground because nothing is connected to them (Ebert 2015,
    Tabelle 4.1), by name with the potentials fixed, as printed lines
    (none when there are none); ``grounded`` as
    :func:`~acausal2d.compiler.flatten.grounded_ports` returns it."""
    if not grounded:
        return []
    names = ["%s\xa0(%s)" % (path, ",\xa0".join(pots)) for path, pots in grounded.items()]
    text = "%d unconnected, so fixed to ground (Ebert 2015, Tabelle 4.1): %s" % (
        len(names), ", ".join(names))
    lines = textwrap.wrap(text, 100, initial_indent=head, subsequent_indent=" " * len(head),
                          break_on_hyphens=False)      # no break inside a port's entry
    return [line.replace("\xa0", " ") for line in lines]


CONNECTOR_GROUPS = (
    ("held", "  held ports:        ", "%d unconnected, held by their own element: %s"),
    ("free", "  free connectors:   ", "%d unconnected, no force or torque acts there: %s"),
    ("closed", "  closed ports:      ", "%d hydraulic port%s unconnected, so closed (no flow): %s"),
    ("open_bands", "  open band ports:   ", "%d unconnected, no band wound there: %s"),
    ("inputs", "  signal inputs:     ", "%d unconnected, nothing gives them a value: %s"),
)
"""(field of the ConnectorReport, head of the line, text) of the report's
groups of unconnected connectors besides the grounded ports."""


def _wrapped(text, head):
    lines = textwrap.wrap(text, 100, initial_indent=head, subsequent_indent=" " * len(head),
                          break_on_hyphens=False)
    return [line.replace("\xa0", " ") for line in lines]


def connector_lines(report):
    """The lines of the connector report (:class:`~acausal2d.compiler.
    connectors.ConnectorReport`) after the grounded ports: free, closed,
    open and unfed connectors by group, then the likely mistakes."""
    lines = []
    for name, head, fmt in CONNECTOR_GROUPS:
        paths = getattr(report, name)
        if paths:
            args = (len(paths),) + (("s" if len(paths) > 1 else "",) if "%s unc" in fmt
                                    else ()) + (", ".join(paths),)
            lines += _wrapped(fmt % args, head)
    for text in report.suspect_texts():
        lines += _wrapped("likely mistake: %s; a connect() missing?" % text, "  ")
    return lines


def unconnected_line(report, head="  unconnected: "):
    """One line naming the unconnected connectors besides the grounded
    ports (those have their own line), by group; '' when there are none."""
    parts = ["%d %s (%s)" % (len(paths), word, ", ".join(paths))
             for word, paths in (("held by their element", report.held),
                                 ("free", report.free), ("closed", report.closed),
                                 ("open band port%s" % ("s" if len(report.open_bands) > 1 else ""),
                                  report.open_bands)) if paths]
    return head + "; ".join(parts) if parts else ""


def _with_grounded(grounded):
    """The degree-of-freedom line's note that both counts hold with the
    grounded ports fixed (their links joined to ground)."""
    n = len(grounded)
    return "; both with the %d grounded port%s fixed" % (n, "s" if n > 1 else "") if n else ""


def _terms(t):
    """The further terms of eq. 2.1 that are present: band joints (among the
    g joints), the coupling of band joints wrapped on one contour, identical
    freedoms f_id and passive constraints s."""
    names = (("band_joints", "%d band joint"), ("coupling", "%d coupling"),
             ("identical", "f_id = %d"), ("passive", "s = %d"))
    return "".join(", " + fmt % t[k] + ("s" if k == "band_joints" and t[k] > 1 else "")
                   for k, fmt in names if t.get(k))


def _node_lines(c):
    """Schnabel and Gössner's eq. 1/2 counts of the node models (see
    :meth:`acausal2d.library.nodes.NodeModel.node_counts`)."""
    lines = ["  nodes (talk):      N = %d, N_base = %d, C1 = %d, C2 = %d: F = %d (eq. 1), "
             "m = %d loops (eq. 2)" % (c["N"], c["N_base"], c["C1"], c["C2"], c["F"], c["m"])]
    if c["driven"]:
        lines.append("                     driven (inputs, not counted): %s"
                     % ", ".join(c["driven"]))
    if c["not_counted"]:
        lines.append("                     not counted: %s" % ", ".join(c["not_counted"]))
    return lines


def _node_counts(model):
    """Sum of the eq. 1/2 counts of all node models in ``model``, or None."""
    found = [c.node_counts() for c in model.components() if hasattr(c, "node_counts")]
    if not found:
        return None
    out = {k: sum(f[k] for f in found) for k in ("N", "N_base", "C1", "C2")}
    out["F"] = 2 * (out["N"] - out["N_base"]) - out["C1"] - 2 * out["C2"]
    out["m"] = out["C1"] + out["C2"] - out["N"] + out["N_base"]
    out["driven"] = [d for f in found for d in f["driven"]]
    out["not_counted"] = [d for f in found for d in f["not_counted"]]
    return out


def _loops(topo, nodes):
    """Closed loops: from the planar topology (eq. 2.1), else the node
    models' eq. 2 (not below 0), else 0."""
    if topo:
        return topo[3]
    return max(nodes["m"], 0) if nodes else 0


class _Topology:
    """Collects the topology() items of all components for Ebert (2015), eq. 2.1:
    links (union of frames), joints (f each), band joints (a span end on a
    wheel contact, f from the contact), coupling constraints of band joints
    wrapped on one contour, identical freedoms f_id and passive constraints s."""

    def __init__(self, model):
        self.conn_sets, _ = connector_sets(model)
        self.links = UnionFind()
        self.ground = ("ground",)
        self.find(self.ground)
        self.used = [self.ground]
        self.joints, self.bands, self.contacts = [], [], {}
        self.coupling = self.identical = self.passive = 0
        self.any_item = False
        for comp in model.components():
            for item in comp.topology():
                self.any_item = True
                self._add(item)

    def find(self, k):
        return self.links.find(self.conn_sets.find(k[1]) if k[0] == "c" else k)

    def _add(self, item):
        kind = item[0]
        if kind in ("ground", "rigid"):
            frames = item[1]
            first = ("c", id(frames[0])) if kind == "rigid" and frames else self.ground
            for f in frames:
                self.links.union(self.find(("c", id(f))), self.find(first))
            self.used += [("c", id(f)) for f in frames]
        elif kind == "joint":
            self.joints.append((item[1], item[2], item[3]))
            self.used += [("c", id(item[1])), ("c", id(item[2]))]
        elif kind == "band":
            self.bands.append(item[1:])
            self.used += [("c", id(item[1])), ("c", id(item[2]))]
        elif kind == "contact":
            self.contacts[self.conn_sets.find(id(item[1]))] = item[2]
        elif kind in ("coupling", "identical", "passive"):
            setattr(self, kind, getattr(self, kind) + item[1])

    def all_joints(self):
        """Joints with their f; a span end on a wheel contact is a band joint
        with the contact's f (1 rolling, 2 sliding), else a pin (f = 1)."""
        out = list(self.joints)
        n_band = 0
        for link, end, port in self.bands:
            f = self.contacts.get(self.conn_sets.find(id(port)))
            n_band += f is not None
            out.append((link, end, 1 if f is None else f))
        return out, n_band


def _planar_topology(model):
    """Links, joints, F and loops by Ebert (2015), eq. 2.1 from the components'
    topology() declarations (None when nothing is declared)."""
    topo = _Topology(model)
    if not topo.any_item:
        return None
    find = topo.find
    joints, n_band = topo.all_joints()
    groups = {find(k) for k in topo.used}
    n, g = len(groups), len(joints)
    F = (3 * (n - 1) - sum(3 - f for _, _, f in joints)
         - topo.coupling - topo.identical + topo.passive)
    # loops: edges - vertices + connected components of the link graph
    graph = UnionFind()
    for grp in groups:
        graph.add(grp)
    for a, b, _ in joints:
        graph.union(find(("c", id(a))), find(("c", id(b))))
    n_components = len({graph.find(grp) for grp in groups})
    loops = g - n + n_components
    extra = {"band_joints": n_band, "coupling": topo.coupling,
             "identical": topo.identical, "passive": topo.passive}
    return n, g, F, max(loops, 0), extra


def _index(structure, states):
    """Differentiation index: 0 for an ODE (every unknown a state or the
    derivative of one), 1 for a DAE solvable without differentiation, else
    one more than the differentiations needed."""
    if structure.structural_index():
        return structure.structural_index() + 1
    A = structure.var_to_diff
    covered = set(states) | {A[j] for j in states}
    return 0 if len(covered) == structure.n_var else 1


POSITION_UNITS = ("rad", "m")
"""Units of the unknowns a position state can be: an angle or a length."""


def _velocity_states(system, states):
    """Derivative nodes that a state gives: der(phi) of a state w with
    ``w == der(phi)`` (the 'always' pass's pairs, or an equation holding
    der(phi) and the state alone, linearly), and the states' own
    derivative nodes that are states themselves."""
    s = system.structure
    st = set(states)
    given = {d for w, d in s.velocity_of if w in st}
    for i in range(s.n_eq):
        nodes = set(s.eq_vars[i])
        if len(nodes) != 2:
            continue
        for d in nodes:
            (other,) = nodes - {d}
            if s.var_level[d] == 1 and other in st and \
                    is_linear_pair(s.eq_expr[i], s.var_sym[d], s.var_sym[other]):
                given.add(d)
    return st | given


def is_linear_pair(expr, a, b):
    """Whether ``expr`` is c1 a + c2 b with constant nonzero c1, c2."""
    grad = ca.gradient(expr, ca.vertcat(a, b))
    return bool(grad.is_constant()) and all(abs(float(g)) > 0 for g in ca.DM(grad).full().ravel())


def _position_states(system, states):
    """The states that are positions of a second-order motion: an angle or
    a length (:data:`POSITION_UNITS`) of level 0 whose derivative is a
    state or is given by one (:func:`_velocity_states`): a joint's phi with
    w, a motor's phi with ``w == der(phi)``, a clutch's phi_rel with
    der(phi_rel).  A first-order state (an angle integrated from a speed
    input, a filter's output) is not one."""
    s = system.structure
    given = _velocity_states(system, states)
    return [j for j in states if s.var_level[j] == 0 and s.var_to_diff[j] in given
            and system.node_info[j].unit in POSITION_UNITS]


def check(model: Any) -> "CheckReport":
    """Compile ``model`` (a model file's path, a Component subclass or
    instance, or a CompiledModel) and return a :class:`CheckReport`; raises
    the project's errors for a broken model."""
    from ..arguments import model_argument
    from ..compiled import CompiledModel
    model = model_argument(model, "check")
    cm = model if isinstance(model, CompiledModel) else CompiledModel(model)
    root, system = cm.model, cm.system
    s = system.structure
    point = cm.initial_point()
    state_nodes = s.state_nodes(point.selection)
    states = [system.display_name(j) for j in state_nodes]
    position_states = _position_states(system, state_nodes)
    topo = _planar_topology(root)
    nodes = _node_counts(root)
    kinds = Counter(type(c).__name__ for c in root.components() if c is not root)
    return CheckReport(
        name=type(root).__name__,
        n_components=sum(kinds.values()),
        component_kinds=", ".join("%s %d" % kv for kv in sorted(kinds.items())),
        n_flat_equations=system.n_flat_equations,
        n_equations=len(system.equations), n_reduced_equations=s.n_eq,
        n_variables=len(system.all_variables), n_aliases=len(system.aliases),
        n_parameters=len(system.parameters),
        structural_index=_index(s, state_nodes),
        states=states, structural_dof=len(position_states),
        loops=_loops(topo, nodes), nodes=nodes,
        grounded=grounded_ports(system.flat_equations),
        connectors=connector_report(root),
        grubler=topo[2] if topo else None, links=topo[0] if topo else 0,
        joints=topo[1] if topo else 0,
        dof_terms=topo[4] if topo else {})
