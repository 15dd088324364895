"""Structure report of a model: sizes, states, structural index, closed
loops and the degree of freedom by the seed's eq. 2.1 next to the
structural one."""
from collections import Counter


from ..language.unionfind import UnionFind, connector_sets


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
        if self.nodes is not None:
            lines += _node_lines(self.nodes)
        if self.grubler is not None:
            lines.append("  degree of freedom: %d by seed eq. 2.1 (n = %d links with ground, "
                         "g = %d joints), %d structural (position states)"
                         % (self.grubler, self.links, self.joints, self.structural_dof))
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


def _node_lines(c):
    """The talk's eq. 1/2 counts of the node models (see
    :meth:`acausal2d.language.nodes.NodeModel.node_counts`)."""
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


def _planar_topology(model):
    """Links, joints and loops from the components' topology() declarations."""
    conn_sets, _ = connector_sets(model)
    links = UnionFind()

    def find(k):
        return links.find(conn_sets.find(k[1]) if k[0] == "c" else k)

    def union(a, b):
        links.union(find(a), find(b))

    joints, any_item = [], False
    ground = ("ground",)
    find(ground)
    used = [ground]
    for comp in model.components():
        for item in comp.topology():
            any_item = True
            kind = item[0]
            if kind == "ground":
                for f in item[1]:
                    union(("c", id(f)), ground)
                    used.append(("c", id(f)))
            elif kind == "rigid":
                frames = item[1]
                for f in frames[1:]:
                    union(("c", id(frames[0])), ("c", id(f)))
                used += [("c", id(f)) for f in frames]
            elif kind == "joint":
                joints.append((item[1], item[2], item[3]))
                used += [("c", id(item[1])), ("c", id(item[2]))]
    if not any_item:
        return None
    groups = {find(k) for k in used}
    n = len(groups)
    g = len(joints)
    F = 3 * (n - 1) - sum(3 - f for _, _, f in joints)
    # loops: edges - vertices + connected components of the link graph
    graph = UnionFind()
    for grp in groups:
        graph.add(grp)
    for a, b, _ in joints:
        graph.union(find(("c", id(a))), find(("c", id(b))))
    n_components = len({graph.find(grp) for grp in groups})
    loops = g - n + n_components
    return n, g, F, max(loops, 0)


def _index(structure, states):
    """Differentiation index: 0 for an ODE (every unknown a state or the
    derivative of one), 1 for a DAE solvable without differentiation, else
    one more than the differentiations needed."""
    if structure.structural_index():
        return structure.structural_index() + 1
    A = structure.var_to_diff
    covered = set(states) | {A[j] for j in states}
    return 0 if len(covered) == structure.n_var else 1


def check(model):
    """Compile ``model`` (a Component instance or a CompiledModel) and return a
    :class:`CheckReport`; raises the project's errors for a broken model."""
    from ..arguments import check_model
    from ..compiled import CompiledModel
    check_model(model, "check")
    cm = model if isinstance(model, CompiledModel) else CompiledModel(model)
    root, system = cm.model, cm.system
    s = system.structure
    point = cm.initial_point()
    state_nodes = s.state_nodes(point.selection)
    states = [system.node_names[j] for j in state_nodes]
    st = set(state_nodes)
    st |= {d for w, d in s.velocity_of if w in st}     # der(phi) given by the state w
    position_states = [j for j in state_nodes
                       if s.var_level[j] == 0 and s.var_to_diff[j] in st]
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
        grubler=topo[2] if topo else None, links=topo[0] if topo else 0,
        joints=topo[1] if topo else 0)
