"""Loading models from model files (Python source under any file name)."""
import importlib.machinery
import importlib.util
import inspect
import os
import sys

from typing import Any, Callable

from ..errors import Acausal2dError, ModelDefinitionError
from ..language.dsl import Component
from ..usercode import user_error_text


def _source_line(exc):
    """The offending source line of a SyntaxError, indented on a line of its own."""
    text = (exc.text or "").rstrip()
    return "\n    " + text.strip() if text.strip() else ""


def _import(path):
    """Execute the model file as a module; errors of the user's code,
    including ``SystemExit``, become ModelDefinitionError naming the file."""
    folder = os.path.dirname(path)
    if folder not in sys.path:
        sys.path.insert(0, folder)
    stem = os.path.splitext(os.path.basename(path))[0]
    modname = "acausal2d_model_" + "".join(ch if ch.isalnum() else "_" for ch in stem)
    loader = importlib.machinery.SourceFileLoader(modname, path)
    spec = importlib.util.spec_from_loader(modname, loader)
    module = importlib.util.module_from_spec(spec)
    sys.modules[modname] = module
    try:
        loader.exec_module(module)
    except Acausal2dError:
        raise
    except SystemExit as exc:
        raise ModelDefinitionError("importing %s: the file calls sys.exit(%s); a model file "
                                   "must define its model classes and return" % (path, exc.code)) \
            from None
    except SyntaxError as exc:
        raise ModelDefinitionError("%s is not valid Python (line %s: %s)%s"
                                   % (path, exc.lineno, exc.msg, _source_line(exc))) from exc
    except Exception as exc:
        raise ModelDefinitionError(user_error_text("importing %s" % path, exc)) from exc
    return module, modname


def _classes(module, modname):
    """(component classes of the file, its models): the models are the
    classes with an ``experiment``, or all classes if none has one."""
    classes = [obj for _, obj in inspect.getmembers(module, inspect.isclass)
               if issubclass(obj, Component) and obj.__module__ == modname
               and not obj.__name__.startswith("_")]
    return classes, [c for c in classes if getattr(c, "experiment", None) is not None] or classes


def model_names(path):
    """Names of the models a model file defines (those ``--model`` takes;
    see :func:`load_model`), in source order."""
    path = os.path.abspath(os.fspath(path))
    module, modname = _import(path)
    models = _classes(module, modname)[1]
    order = list(vars(module))
    return [c.__name__ for c in sorted(models, key=lambda c: (_class_line(c),
                                                              order.index(c.__name__)))]


def _class_line(cls):
    """The line of ``cls``'s class statement; classes a file generates (no
    class statement) follow, in the order the file defines them."""
    try:
        return inspect.getsourcelines(cls)[1]
    except (OSError, TypeError):
        return float("inf")


def _choose(path, module, modname, name):
    """The model class: ``name`` if given, else the only model of the file."""
    classes, models = _classes(module, modname)
    if name is not None:
        return _named(path, module, name, classes)
    if not classes:
        raise ModelDefinitionError("%s defines no model (a subclass of acausal2d.Component)"
                                   % path)
    if len(models) > 1:
        raise ModelDefinitionError("%s defines several models (%s); choose one with --model NAME "
                                   "(load_model(path, name))"
                                   % (path, ", ".join(c.__name__ for c in models)))
    return models[0]


def _named(path, module, name, classes):
    """The class ``name`` of the file; the framework's ``Component`` is not
    a model."""
    cls = getattr(module, name, None)
    if cls is Component or not (inspect.isclass(cls) and issubclass(cls, Component)):
        raise ModelDefinitionError("%s defines no model %r; models in the file: %s"
                                   % (path, name, ", ".join(c.__name__ for c in classes)
                                      or "none"))
    return cls


def load_model(path: "str | os.PathLike[str]", name: "str | None" = None,
               **kwargs: Any) -> Component:
    """Import the model file ``path`` (Python source; any file name) and
    instantiate its model.

    The model is the class ``name`` if given; otherwise the one model the
    file defines: the one class with an ``experiment`` (declared or
    inherited), or the file's only component class.  A file with several
    models (a base model and its subclass count as two) must be given a
    name; the error lists them.  ``Component`` itself is not a model.
    ``kwargs`` go to the model's constructor.  A file with a suffix of
    :data:`READERS` (``.json``: a mec2 model,
    :func:`acausal2d.library.nodes.mec2.load_mec2`) is read by its reader."""
    suffix = os.path.splitext(os.fspath(path))[1].lower() \
        if isinstance(path, (str, os.PathLike)) else None
    if suffix in READERS:
        return _load_other(path, READERS[suffix], name, kwargs)
    if not isinstance(path, (str, os.PathLike)) or not os.path.isfile(path):
        raise ModelDefinitionError("model file %s does not exist" % (path,))
    path = os.path.abspath(os.fspath(path))
    module, modname = _import(path)
    cls = _choose(path, module, modname, name)
    try:
        return cls(**kwargs)
    except Acausal2dError:
        raise
    except SystemExit as exc:
        raise ModelDefinitionError("building %s: it calls sys.exit(%s)" % (cls.__name__, exc.code)) \
            from None
    except Exception as exc:
        raise ModelDefinitionError(user_error_text("building %s" % cls.__name__, exc)) from exc


READERS: dict = {}
"""{suffix: (kind, read)}: model files that are not Python source, read by
``read(path)`` -> model (:func:`register_reader`)."""


def register_reader(suffix: str, kind: str, read: Callable[[str], Any]) -> None:
    """Let :func:`load_model` read the model files ending in ``suffix``
    (e.g. ``".json"``, files of ``kind``, e.g. "mec2") with ``read(path)``.
    The package root registers the library's mec2 reader, so that io
    imports nothing of the library (tests/test_layering.py)."""
    READERS[suffix.lower()] = (kind, read)


def _load_other(path, reader, name, kwargs):
    """A model file of a registered reader: one model, no constructor arguments."""
    kind, read = reader
    if name is not None or kwargs:
        raise ModelDefinitionError("%s is a %s model (one model, no arguments); drop "
                                   "--model and the keyword arguments" % (path, kind))
    return read(os.fspath(path))
