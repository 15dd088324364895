"""Top-level ``RealInput`` connectors of a model as parameters.

A model's own ``RealInput`` connectors that nothing inside drives are the
inputs of the model as a whole (FMU inputs, the inputs u of a
linearisation).  :func:`bind_inputs` gives every such connector a value
source: a ``Constant`` named ``<connector>_source`` takes the connector's
place in the model's connections, and its parameter ``k`` is the input (a
parameter of the compiled functions, so it changes without recompiling:
``--set <connector>_source.k=...``, ``params``, ``fmi2SetReal``).  Used by
the FMU export and by ``linearize``/``modes``.

The user's model is left as it was: the sources go into a copy.
"""
from acausal2d.compiled import own_copy
from acausal2d.errors import ModelDefinitionError
from acausal2d.language.connectors import RealInput
from acausal2d.library.signals import Constant


def bind_inputs(model, values=None):
    """A copy of ``model`` whose own ``RealInput`` connectors are replaced by
    constant sources, and {input name: parameter name of its value}:
    ``(bound model, mapping)``.  ``values``: {input name: start value}
    (default 0).  The mapping is also kept as the copy's
    ``input_parameters``; ``model`` itself is not changed."""
    model = own_copy(model)
    values = dict(values or {})
    inputs = {}
    for name, conn in list(model._connectors.items()):
        if not isinstance(conn, RealInput):
            continue
        src = Constant(k=float(values.pop(name, 0.0)))
        setattr(model, name + "_source", src)
        pairs = model._connections
        for i, (a, b) in enumerate(pairs):
            if a is conn or b is conn:
                pairs[i] = (src.y if a is conn else a, src.y if b is conn else b)
        del model._connectors[name]
        inputs[name] = name + "_source.k"
    if values:
        raise ModelDefinitionError("%s has no input %s; its inputs (top-level RealInput "
                                   "connectors): %s" % (type(model).__name__,
                                                        ", ".join(sorted(values)),
                                                        ", ".join(inputs) or "none"))
    model.input_parameters = dict(getattr(model, "input_parameters", {}), **inputs)
    return model, inputs
