"""The relations pass rebuilds only the equations that contain a relation
(issue 17, item 5): the others come back as the same objects, and the
rebuilt ones evaluate like the originals with the relation values the
discrete symbols take."""
import casadi as ca
import numpy as np

from acausal2d.compiler.relations import extract_relations
from acausal2d.language.symbols import SymbolTable, time


def test_only_equations_with_relations_are_rebuilt():
    t = SymbolTable()
    x, y, z = (t.new_variable(n) for n in "xyz")
    p = t.new_parameter("p")
    shared = ca.sin(x) * y + p                       # a subexpression used by several equations
    eqs = [shared - z,                               # no relation
           ca.if_else(x < y, shared, -shared) - 1,   # one relation: x < y
           x * x + ca.cos(z) - p,                    # no relation
           ca.fmax(z, time) + shared,                # one relation: max(z, time)
           ca.if_else(p < 1, x, y)]                  # a relation of a parameter: kept
    out, rels = extract_relations(eqs, t)
    assert out[0] is eqs[0] and out[2] is eqs[2]
    assert str(out[4]) == str(eqs[4])                # rebuilt (it has a comparison), unchanged
    assert [r.equation for r in rels] == [1, 3]
    assert [r.strict for r in rels] == [True, True]
    d = ca.vertcat(*[r.sym for r in rels])
    args = [ca.vertcat(x, y, z, p, time), d]
    new = ca.Function("new", args, [ca.vertcat(*out)])
    old = ca.Function("old", [args[0]], [ca.vertcat(*eqs)])
    g = ca.Function("g", [args[0]], [ca.vertcat(*[r.g for r in rels])])
    rng = np.random.default_rng(2)
    for _ in range(20):
        v = rng.normal(size=5)
        dv = (np.asarray(g(v)).ravel() > 0).astype(float)   # the relation values at v
        assert np.allclose(np.asarray(new(v, dv)).ravel(), np.asarray(old(v)).ravel(),
                           rtol=0, atol=1e-14)
