"""Modelica's PartialCompliantWithRelativeStates options (Modelica Standard
Library 4.0, Modelica.Mechanics.Rotational.Interfaces and
Modelica.Mechanics.Translational.Interfaces)::

    parameter StateSelect stateSelect = StateSelect.prefer;
    parameter SI.Angle phi_nominal = 1e-4;        (translational: s_nominal)
    SI.Angle phi_rel(stateSelect = stateSelect,
                     nominal = if phi_nominal >= Modelica.Constants.eps
                               then phi_nominal else 1);
    SI.AngularVelocity w_rel(stateSelect = stateSelect);

The elements declare ``prefer`` and the nominal 1e-4 on their variables;
:func:`relative_states` applies the keywords ``phi_nominal`` (``s_nominal``)
and ``stateSelect`` a transcribed model gives.  Both decide the structure of
the compiled model (which unknowns are states, their error scale), so they
are constructor keywords, not parameters."""
import math
import numbers

from acausal2d.errors import ModelDefinitionError

EPS = 1e-15
"""Modelica.Constants.eps: a nominal below it means 1."""
STATE_SELECT = ("never", "avoid", "default", "prefer", "always")


def relative_states(comp, position, speed, nominal, state_select, nominal_name="phi_nominal"):
    """Apply Modelica's ``phi_nominal`` (named ``nominal_name``) to the
    variable ``position`` and ``stateSelect`` (``"StateSelect.prefer"``,
    ``"Modelica.StateSelect.prefer"`` or ``"prefer"``) to ``position`` and
    ``speed`` of ``comp``; None leaves the element's default.  Errors name
    the component and the keyword."""
    if nominal is not None:
        if isinstance(nominal, bool) or not isinstance(nominal, numbers.Real) or \
                not math.isfinite(nominal) or nominal < 0:
            raise ModelDefinitionError("%s: %s must be a finite number >= 0, not %r"
                                       % (comp.describe(), nominal_name, nominal))
        comp.variable(position).nominal = float(nominal) if nominal >= EPS else 1.0
    if state_select is not None:
        prefix, _, name = state_select.rpartition(".") if isinstance(state_select, str) \
            else ("", "", None)
        if name not in STATE_SELECT or not (prefix == "" or prefix.endswith("StateSelect")):
            raise ModelDefinitionError(
                "%s: stateSelect must be one of %s, not %r" % (
                    comp.describe(), ", ".join("StateSelect." + s for s in STATE_SELECT),
                    state_select))
        for var in (position, speed):
            comp.variable(var).state_select = name
