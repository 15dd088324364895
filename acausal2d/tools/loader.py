"""Loading models from Python model files."""
import importlib.util
import inspect
import os
import sys

from ..language.dsl import Component
from ..errors import ModelDefinitionError


def load_model(path, name=None, **kwargs):
    """Import the model file ``path`` and instantiate its model.

    The model is the class ``name`` if given; otherwise the one Component
    subclass defined in the file (a file defining several must be given a
    name).  ``kwargs`` go to the model's constructor.  A ``.json`` file is a
    mec2 model (:func:`acausal2d.tools.mec2.load_mec2`)."""
    if str(path).lower().endswith(".json"):
        from .mec2 import load_mec2
        if name is not None or kwargs:
            raise ModelDefinitionError("%s is a mec2 model (one model, no arguments); drop "
                                       "--model and the keyword arguments" % path)
        return load_mec2(path)
    if not os.path.isfile(path):
        raise ModelDefinitionError("model file %s does not exist" % path)
    path = os.path.abspath(path)
    folder = os.path.dirname(path)
    if folder not in sys.path:
        sys.path.insert(0, folder)
    modname = "acausal2d_model_" + os.path.splitext(os.path.basename(path))[0]
    spec = importlib.util.spec_from_file_location(modname, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[modname] = module
    try:
        spec.loader.exec_module(module)
    except ModelDefinitionError:
        raise
    except Exception as exc:
        raise ModelDefinitionError("importing %s failed: %s: %s"
                                   % (path, type(exc).__name__, exc)) from None
    classes = [obj for _, obj in inspect.getmembers(module, inspect.isclass)
               if issubclass(obj, Component) and obj.__module__ == modname]
    if name is not None:
        cls = getattr(module, name, None)
        if not (inspect.isclass(cls) and issubclass(cls, Component)):
            raise ModelDefinitionError("%s defines no model %r; models in the file: %s"
                                       % (path, name, ", ".join(c.__name__ for c in classes)
                                          or "none"))
    else:
        # prefer classes that are not used as building blocks of others in the file
        if not classes:
            raise ModelDefinitionError("%s defines no model (a subclass of acausal2d.Component)"
                                       % path)
        tops = [c for c in classes if not any(c is not o and issubclass(o, c) for o in classes)]
        models = [c for c in tops if getattr(c, "experiment", None) is not None] or tops
        if len(models) > 1:
            raise ModelDefinitionError("%s defines several models (%s); choose one with --model"
                                       % (path, ", ".join(c.__name__ for c in models)))
        cls = models[0]
    try:
        return cls(**kwargs)
    except ModelDefinitionError:
        raise
    except Exception as exc:
        raise ModelDefinitionError("building %s failed: %s: %s"
                                   % (cls.__name__, type(exc).__name__, exc)) from None
