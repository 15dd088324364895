"""A model file the user writes: an exception of the user's own code
(import, ``__init__``, ``equations``, a study) reports the file, line and
source text of the user's frame, in the command line and in Python (the
original exception chained); ``--traceback`` or ACAUSAL2D_TRACEBACK=1 shows
the whole traceback."""
import os
import subprocess
import sys
import textwrap

import pytest

import acausal2d
from acausal2d import ModelDefinitionError
from acausal2d.usercode import user_frame

HEAD = textwrap.dedent('''\
    from acausal2d import Component, start
    from acausal2d.library import rotational


    class M(Component):
        experiment = {"stop_time": 0.1}

        def __init__(self, **kw):
            super().__init__(**kw)
            self.inertia = rotational.Inertia(J=1.0, phi=start(0.0, fixed=True),
                                              w=start(1.0, fixed=True))
''')

# (name, source appended to HEAD, the offending source text, the exception)
BROKEN = {
    "NameError": ("        self.other = rotational.Inertia(J=undefined_name)\n",
                  "self.other = rotational.Inertia(J=undefined_name)",
                  "NameError: name 'undefined_name' is not defined"),
    "AttributeError": ("        self.other = rotational.Inertai(J=1.0)\n",
                       "self.other = rotational.Inertai(J=1.0)", "AttributeError"),
    "ZeroDivisionError": ("        self.other = rotational.Inertia(J=1.0 / 0)\n",
                          "self.other = rotational.Inertia(J=1.0 / 0)",
                          "ZeroDivisionError: float division by zero"),
}


def _write(tmp_path, source):
    path = tmp_path / "my_model.py"
    path.write_text(HEAD + source)
    return str(path), len((HEAD + source).splitlines())


def _cli(*args, env=None):
    full = {k: v for k, v in os.environ.items() if k != "ACAUSAL2D_TRACEBACK"}
    full.update(env or {})
    return subprocess.run([sys.executable, "-m", "acausal2d", *args], capture_output=True,
                          text=True, env=full, timeout=300)


@pytest.mark.parametrize("kind", sorted(BROKEN))
def test_an_error_in_init_names_the_users_file_and_line_in_python(tmp_path, kind):
    source, text, message = BROKEN[kind]
    path, line = _write(tmp_path, source)
    with pytest.raises(ModelDefinitionError) as err:
        acausal2d.load_model(path)
    assert "%s:%d" % (path, line) in str(err.value)
    assert text in str(err.value) and message in str(err.value)
    assert type(err.value.__cause__).__name__ == kind      # chained, never suppressed


@pytest.mark.parametrize("kind", sorted(BROKEN))
def test_an_error_in_init_names_the_users_file_and_line_in_the_cli(tmp_path, kind):
    source, text, message = BROKEN[kind]
    path, line = _write(tmp_path, source)
    proc = _cli("check", path)
    assert proc.returncode == 2
    assert "%s:%d" % (path, line) in proc.stderr and text in proc.stderr
    assert message in proc.stderr and "Traceback" not in proc.stderr
    assert "--traceback" in proc.stderr


def test_traceback_flag_and_environment_show_the_whole_traceback(tmp_path):
    path, line = _write(tmp_path, BROKEN["NameError"][0])
    for proc in (_cli("check", path, "--traceback"), _cli("--traceback", "check", path),
                 _cli("check", path, env={"ACAUSAL2D_TRACEBACK": "1"})):
        assert proc.returncode == 2
        assert "Traceback (most recent call last)" in proc.stderr
        assert 'File "%s", line %d, in __init__' % (path, line) in proc.stderr
        assert "The above exception was the direct cause" in proc.stderr


def test_an_error_in_equations_names_the_users_line(tmp_path):
    source = textwrap.dedent('''\

        class N(Component):
            def __init__(self, **kw):
                super().__init__(**kw)
                self.inertia = rotational.Inertia(J=1.0)

            def equations(self):
                return [self.inertia.phi == self.inertai.w]
    ''')
    path, line = _write(tmp_path, source)
    model = acausal2d.load_model(path, "N")
    with pytest.raises(ModelDefinitionError) as err:
        acausal2d.check(model)
    assert "%s:%d" % (path, line) in str(err.value)
    assert "return [self.inertia.phi == self.inertai.w]" in str(err.value)


def test_an_error_at_import_names_the_users_line(tmp_path):
    path = tmp_path / "imp.py"
    path.write_text("import math\n\nX = math.sqrt(-1)\n")
    with pytest.raises(ModelDefinitionError) as err:
        acausal2d.load_model(str(path))
    assert "%s:3" % path in str(err.value) and "X = math.sqrt(-1)" in str(err.value)
    assert isinstance(err.value.__cause__, ValueError)


def test_the_user_frame_is_the_innermost_one_outside_the_framework(tmp_path):
    """An error raised inside numpy called from the user's line names the
    user's line, not numpy's."""
    path = tmp_path / "np_user.py"
    path.write_text("import numpy as np\n\n\ndef f():\n    return np.zeros((2, 2)) @ np.zeros(3)\n")
    namespace = {}
    exec(compile(path.read_text(), str(path), "exec"), namespace)
    try:
        namespace["f"]()
    except ValueError as exc:
        frame = user_frame(exc)
    assert frame.filename == str(path) and frame.lineno == 5
    assert frame.source == "return np.zeros((2, 2)) @ np.zeros(3)"
