"""What a component's hooks may ask about the whole model during one
flattening (:meth:`~acausal2d.language.dsl.Component.derived_parameters`,
:meth:`~acausal2d.language.dsl.Component.guesses`)."""
import casadi as ca
import numpy as np

from .unionfind import connector_sets


class ModelContext:
    """The model being flattened, its connection sets, and model-wide values
    computed once per flattening and shared between components (e.g. the
    pre-assembly of all linkage elements, the layout of all belts)."""

    def __init__(self, model):
        self.model = model
        self._shared = {}
        self._sets, self._connected = connector_sets(model)
        self.parameters = []        # (name, symbol, value, declaration), once bound

    def evaluate(self, exprs):
        """Numeric values of expressions in the model's parameters (after the
        symbols are bound, i.e. in :meth:`guesses`)."""
        syms = ca.vertcat(*[sym for _, sym, _, _ in self.parameters]) if self.parameters \
            else ca.SX(0, 1)
        vals = [v for _, _, v, _ in self.parameters]
        out = ca.Function("evaluate", [syms], [ca.vertcat(*[ca.SX(e) for e in exprs])])(vals)
        return np.asarray(out, dtype=float).ravel()

    def shared(self, key, compute):
        """The value stored under ``key`` for this flattening; computed by
        ``compute()`` on first use."""
        if key not in self._shared:
            self._shared[key] = compute()
        return self._shared[key]

    def is_connected(self, conn):
        """True if ``conn`` appears in a connect statement of the model."""
        return id(conn) in self._connected

    def partners(self, conn):
        """The other connectors in the connection set of ``conn``."""
        k = self._sets.find(id(conn))
        return [c for comp in self.model.components() for c in comp._connectors.values()
                if c is not conn and self._sets.find(id(c)) == k]
