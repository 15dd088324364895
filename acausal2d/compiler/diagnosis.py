"""What a structural error is probably about: parts of the model that hang
free.  The components and their connections form a graph (networkx); a
model that falls apart into separate groups, and connectors left
unconnected, are named so that the user sees which connection is missing
rather than a library equation."""


def _graph(model):
    import networkx as nx
    g = nx.Graph()
    for comp in model.components():
        if comp._connectors:
            g.add_node(comp)
        for a, b in comp._connections:
            if a.owner is not b.owner:
                g.add_edge(a.owner, b.owner)
    return g


def _connected(model):
    ids = set()
    for comp in model.components():
        for a, b in comp._connections:
            ids.update((id(a), id(b)))
    return ids


def loose_parts(model):
    """Text naming the separate groups of components and the connectors
    left unconnected (those not fixed to ground or required), or '' when the
    model is one connected whole."""
    import networkx as nx
    g = _graph(model)
    if g.number_of_nodes() < 2:
        return ""
    groups = sorted(nx.connected_components(g), key=len, reverse=True)
    connected = _connected(model)
    loose = [c.path for comp in g.nodes for c in comp._connectors.values()
             if id(c) not in connected and c.ground is None and not c.required
             and comp is not model]
    if len(groups) < 2:
        return ""
    parts = ["The model falls apart into %d separate groups of components:" % len(groups)]
    for grp in groups[:4]:
        names = sorted(c.describe() for c in grp)
        parts.append("  - " + ", ".join(names[:8]) + (", ..." if len(names) > 8 else ""))
    if loose:
        parts.append("Unconnected connectors (probably one of them should connect the groups): "
                     + ", ".join(sorted(loose)[:12]))
    return "\n".join(parts)
