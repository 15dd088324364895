"""The compiler pipeline: flatten -> relations -> balance -> aliases ->
balance -> structure -> Pantelides -> states declared 'always' -> a frozen
:class:`~acausal2d.compiler.system.System`.

Each pass is a function of its inputs that returns new values; the symbols
of one compilation live in its own
:class:`~acausal2d.language.symbols.SymbolTable`, owned by the system.
"""
from ..errors import ModelDefinitionError, StructuralError
from ..language.dsl import STATE_SELECT, Component
from ..language.symbols import SymbolTable
from .aliases import eliminate_all_aliases
from .always_states import differentiate_for_always
from .balance import check_balance
from .diagnosis import loose_parts
from .flatten import flatten
from .gc_pause import cyclic_gc_paused
from .pantelides import pantelides
from .relations import extract_relations
from .structure import initial_structure
from .system import System


def _balanced(model, equations, variables, table):
    """check_balance, with the loose parts of the model named in its error."""
    try:
        check_balance(equations, variables, table)
    except StructuralError as exc:
        hint = loose_parts(model)
        if not hint:
            raise
        raise StructuralError("%s\n%s" % (hint, exc)) from None


def compile_system(model: Component) -> System:
    """Compile a model instance into a :class:`System` (see the module
    docstring; the cyclic garbage collector is paused meanwhile)."""
    with cyclic_gc_paused():
        return _compile(model)


def _compile(model):
    table = SymbolTable()
    flat = flatten(model, table)
    if not flat.variables and not flat.equations:
        raise ModelDefinitionError(
            "%s has no unknowns and no equations: there is nothing to simulate. Give it "
            "components (e.g. from acausal2d.library) and connect them, or choose another "
            "model of the file with --model." % model.describe())
    exprs, relations = extract_relations([eq.expr for eq in flat.equations], table)
    equations = [eq.with_expr(e) for eq, e in zip(flat.equations, exprs)]
    _balanced(model, equations, flat.variables, table)
    equations, variables, aliases = eliminate_all_aliases(equations, flat.variables, table)
    _balanced(model, equations, variables, table)
    s = initial_structure(table, [eq.expr for eq in equations], variables)
    s = pantelides(s, lambda i: equations[i].describe())
    info = {v.sym.element_hash(): v for v in variables}
    priority = [STATE_SELECT.index(info[s.var_sym[s.var_base[j]].element_hash()].state_select)
                for j in range(s.n_var)]
    s = differentiate_for_always(s, priority, lambda i: equations[i].describe())
    return System(model, flat, equations, variables, aliases, relations, s)
