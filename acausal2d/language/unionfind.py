"""Disjoint sets (union-find) and the connection sets of a model."""


class UnionFind:
    """Disjoint sets of hashable keys with path halving."""

    def __init__(self):
        self.parent = {}

    def add(self, k):
        """Make sure ``k`` is known (as its own set if new)."""
        self.parent.setdefault(k, k)

    def find(self, k):
        """Representative of the set holding ``k`` (added if unknown)."""
        parent = self.parent
        parent.setdefault(k, k)
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    def union(self, a, b):
        """Merge the sets of ``a`` and ``b``."""
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.parent[ra] = rb

    def groups(self):
        """{representative: [keys]} of all sets."""
        out = {}
        for k in list(self.parent):
            out.setdefault(self.find(k), []).append(k)
        return out


def connector_sets(model):
    """UnionFind over ``id(connector)`` of every connector of ``model``,
    merged along all ``connect`` statements (inside/outside not
    distinguished), and the set of ids of connectors that appear in a
    connect statement."""
    uf = UnionFind()
    connected = set()
    for comp in model.components():
        for conn in comp._connectors.values():
            uf.add(id(conn))
        for a, b in comp._connections:
            connected.update((id(a), id(b)))
            uf.union(id(a), id(b))
    return uf, connected
