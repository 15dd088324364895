"""``modelDescription.xml`` (FMI 2.0) of an exported model.

Value references: the parameters (inputs among them) first, then the
variable nodes of the index-reduced system, the eliminated aliases and
their derivatives, in the order of the generated C data.
"""
from xml.sax.saxutils import quoteattr

SOURCE_FILES = ("a2d_casadi.c", "a2d_core.c", "a2d_cs.c", "a2d_fmi2.c")
"""The C files in the FMU's sources/ (listed in modelDescription.xml)."""


STRUCTURAL = ("read when the model was compiled (it decides the model's structure): a "
              "constant of this FMU; export the model again with another value")
"""The description of a parameter the compiler read
(:attr:`~acausal2d.compiled.CompiledModel.structural`): the FMU cannot
change it, so it is a local constant, and ``fmi2SetReal`` refuses it."""


def _variable(var):
    attrs = " ".join("%s=%s" % (k, quoteattr(str(v))) for k, v in var["attrs"].items())
    real = " ".join("%s=%s" % (k, quoteattr(str(v))) for k, v in var["real"].items())
    return '    <ScalarVariable %s>\n      <Real %s/>\n    </ScalarVariable>' % (attrs, real)


def variables(data):
    """The ScalarVariable entries: list of dicts with ``name``, ``vr``,
    ``attrs`` and ``real`` (attributes of the Real element)."""
    s, units = data.system, data.units
    out, inputs = [], {p: name for name, p in data.input_params.items()}
    for k, (name, _, _, decl) in enumerate(s.parameters):
        real = {"start": repr(float(data.p0[k]))}
        if name in inputs:
            attrs = {"name": inputs[name], "valueReference": k, "causality": "input",
                     "variability": "continuous",
                     "description": "input (top-level RealInput %s)" % inputs[name]}
        elif name in data.structural:
            attrs = {"name": name, "valueReference": k, "causality": "local",
                     "variability": "constant", "initial": "exact",
                     "description": STRUCTURAL + (" (%s)" % decl.doc if decl.doc else "")}
        else:
            attrs = {"name": name, "valueReference": k, "causality": "parameter",
                     "variability": "fixed", "description": decl.doc or ""}
        if decl.unit:
            real["unit"] = decl.unit
        out.append({"name": attrs["name"], "attrs": attrs, "real": real})
    taken = {v["name"] for v in out}
    outputs, docs = set(s.outputs), _docs(s)
    for vr, name in enumerate(s.names, start=len(s.parameters)):
        if name in taken:
            continue
        attrs = {"name": name, "valueReference": vr,
                 "causality": "output" if name in outputs else "local",
                 "variability": "continuous"}
        if docs.get(name):
            attrs["description"] = docs[name]
        out.append({"name": name, "attrs": attrs,
                    "real": {"unit": units[name]} if units.get(name) else {}})
    return out


def _docs(s):
    """{column name: description} of the declared variables (not derivatives)."""
    level = s.structure.var_level
    docs = {name: getattr(info, "doc", "") for name, info, lv in
            zip(s.node_names, s.node_info, level) if lv == 0}
    docs.update((a.var.name, getattr(a.var, "doc", "")) for a in s.aliases)
    return docs


def _structure(data, vars_):
    """(outputs, derivatives, initial unknowns) as 1-based variable indices."""
    index = {v["name"]: i + 1 for i, v in enumerate(vars_)}
    names = data.system.node_names
    A = data.system.structure.var_to_diff
    outputs = sorted(index[n] for n in data.system.outputs if n in index)
    states = [index[names[j]] for j in data.states]
    ders = [index[names[A[j]]] for j in data.states]
    for x, dx in zip(states, ders):
        vars_[dx - 1]["real"]["derivative"] = x
    return outputs, ders, sorted(set(outputs) | set(states) | set(ders))


def _units(vars_):
    used = sorted({v["real"]["unit"] for v in vars_ if "unit" in v["real"]})
    if not used:
        return []
    return ["  <UnitDefinitions>"] + ['    <Unit name=%s/>' % quoteattr(u) for u in used] + \
        ["  </UnitDefinitions>"]


def model_description(data, kind):
    """Text of modelDescription.xml for ``kind`` 'me' or 'cs'."""
    vars_ = variables(data)
    outputs, ders, initial = _structure(data, vars_)
    ident = data.identifier
    kind_elem = ('  <ModelExchange modelIdentifier="%s" canNotUseMemoryManagementFunctions="true">'
                 % ident if kind == "me" else
                 '  <CoSimulation modelIdentifier="%s" canHandleVariableCommunicationStepSize="true"'
                 ' canNotUseMemoryManagementFunctions="true">' % ident)
    kind_elem += "\n    <SourceFiles>\n%s\n    </SourceFiles>\n  </%s>" % (
        "\n".join('      <File name="%s"/>' % f for f in SOURCE_FILES),
        "ModelExchange" if kind == "me" else "CoSimulation")
    exp = data.experiment             # resolved RunOptions: the default experiment

    def unknowns(tag, idx):
        if not idx:
            return []
        return ["    <%s>" % tag] + ['      <Unknown index="%d"/>' % i for i in idx] + \
            ["    </%s>" % tag]
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<fmiModelDescription fmiVersion="2.0" modelName=%s guid="%s" description=%s '
             'generationTool="acausal2d %s" variableNamingConvention="flat" '
             'numberOfEventIndicators="%d">' % (quoteattr(data.model_name), data.guid,
                                                 quoteattr(data.doc), data.version,
                                                 len(data.system.relations)),
             kind_elem] + _units(vars_) + \
        ['  <DefaultExperiment startTime="0" stopTime="%r" tolerance="%r"/>'
         % (exp.stop_time, exp.rtol),
         "  <ModelVariables>"] + [_variable(v) for v in vars_] + \
        ["  </ModelVariables>", "  <ModelStructure>"] + unknowns("Outputs", outputs) + \
        unknowns("Derivatives", ders) + unknowns("InitialUnknowns", initial) + \
        ["  </ModelStructure>", "</fmiModelDescription>", ""]
    return "\n".join(lines)
