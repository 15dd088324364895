"""Dymola's result format (``dsres.mat``): MAT version 4 files with the
matrices ``Aclass``, ``name``, ``description``, ``dataInfo``, ``data_1`` and
``data_2``, as Dymola, OpenModelica and their plotting tools (DyMat,
buildingspy's ``Reader``, the Modelica plot windows) write and read them.

The layout (``Aclass`` = ``Atrajectory / 1.1 / / binTrans``), following
Dymola's own description of the format:

- ``name``, ``description``: character matrices, one column per variable;
  the first variable is the abscissa ``Time``.
- ``dataInfo``: 4 x n int32; column i is (block, signed column,
  interpolation 0, extrapolation): block 0 for the abscissa, 1 for
  parameters (``data_1``, constant over the run), 2 for trajectories
  (``data_2``); the column's sign says whether the variable is the
  negated column (aliases ``a = -b`` share ``b``'s data).
- ``data_1``: (1 + parameters) x 2, the values at the first and last time;
  ``data_2``: (1 + distinct trajectories) x time points; the first row of
  both is the time.

A trajectory that equals another one, or its negation, bit for bit (the
aliases the compiler eliminated) is stored once and shared, as Dymola does.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import TypeVar, Union
import os
import re
import struct

import numpy as np
from numpy.typing import ArrayLike

from ..errors import Acausal2dError
from .files import atomic_path

PathT = TypeVar("PathT", bound=Union[str, "os.PathLike[str]"])

__all__ = ["write_mat", "read_mat", "mat_units"]

_ACLASS = ["Atrajectory", "1.1", "", "binTrans"]


def _char_matrix(strings, by_column):
    """Character matrix (uint8) of ``strings`` in UTF-8, padded with blanks:
    one string per column (``by_column``, binTrans) or per row.  A MAT v4
    text matrix holds bytes (readers take them as Latin-1); a name outside
    ASCII (``φ_gelenk``, ``関節``) is stored as its UTF-8 bytes, as
    OpenModelica stores it, and :func:`read_mat` gives it back."""
    encoded = [s.encode("utf-8") for s in strings]
    width = max([len(b) for b in encoded] + [1])
    rows = np.array([list(b.ljust(width)) for b in encoded], dtype=np.uint8).reshape(
        len(encoded), width)
    return rows.T if by_column else rows


def _matrix_bytes(name, array, text=False):
    """One MAT v4 matrix: header (type, rows, columns, imaginary flag, name
    length), the name with its NUL, the data in column-major order."""
    if text:
        data = array.astype(np.uint8)
        mtype = 51                   # little-endian, uint8, text
    elif array.dtype.kind == "i":
        data, mtype = array.astype("<i4"), 20
    else:
        data, mtype = array.astype("<f8"), 0
    rows, cols = data.shape
    encoded = name.encode("ascii") + b"\0"
    return struct.pack("<5i", mtype, rows, cols, 0, len(encoded)) + encoded + \
        np.asfortranarray(data).tobytes(order="F")


def _share_columns(names, columns):
    """(data rows, dataInfo column of each name): columns equal to an
    earlier one or its negation bit for bit share its row (signed)."""
    rows, seen, where = [], {}, []
    for name in names:
        v = np.ascontiguousarray(columns[name], dtype=float)
        key, negated = v.tobytes(), (-v).tobytes()
        if key in seen:
            where.append(seen[key])
        elif negated in seen and np.any(v != 0):
            where.append(-seen[negated])
        else:
            rows.append(v)
            seen[key] = len(rows) + 1          # row 1 is the time
            where.append(len(rows) + 1)
    return rows, where


def write_mat(path: PathT, time: ArrayLike, columns: Mapping[str, ArrayLike],
              parameters: Mapping[str, float] | None = None,
              descriptions: Mapping[str, str] | None = None) -> PathT:
    """Write a Dymola result file: ``time`` (1-D), ``columns`` ({name:
    values over time}, trajectories), ``parameters`` ({name: value},
    constants), ``descriptions`` ({name: text}, e.g. the unit).  Folders are
    created and the file is replaced atomically; returns ``path``."""
    time = np.asarray(time, dtype=float)
    parameters = dict(parameters or {})
    descriptions = dict(descriptions or {})
    traj = [n for n in columns if n not in parameters]
    for n in traj:
        if np.shape(columns[n]) != time.shape:
            raise Acausal2dError("write_mat: column %r has %d values but there are %d time "
                                 "points" % (n, np.size(columns[n]), time.size))
    rows, where = _share_columns(traj, columns)
    names = ["Time"] + list(parameters) + traj
    info = [[0, 1, 0, -1]] + [[1, k + 2, 0, 0] for k in range(len(parameters))] + \
        [[2, w, 0, -1] for w in where]
    t01 = [time[0], time[-1]] if time.size else [0.0, 0.0]
    data_1 = np.array([t01] + [[v, v] for v in parameters.values()], dtype=float)
    data_2 = np.vstack([time] + rows) if rows else time[None, :]
    descr = ["Time in [s]"] + [descriptions.get(n, "") for n in names[1:]]
    blob = b"".join([
        _matrix_bytes("Aclass", _char_matrix(_ACLASS, by_column=False), text=True),
        _matrix_bytes("name", _char_matrix(names, by_column=True), text=True),
        _matrix_bytes("description", _char_matrix(descr, by_column=True), text=True),
        _matrix_bytes("dataInfo", np.array(info, dtype=np.int32).T),
        _matrix_bytes("data_1", data_1),
        _matrix_bytes("data_2", data_2)])
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            fh.write(blob)
    return path


def _strings(matrix, by_column):
    """The strings of a text matrix (scipy reads its bytes as Latin-1):
    UTF-8 where the bytes are (:func:`_char_matrix`), else Latin-1."""
    chars = matrix.T if by_column else matrix
    out = []
    for row in chars:
        text = "".join(row).rstrip(" \0")
        try:
            text = text.encode("latin-1").decode("utf-8")
        except (UnicodeEncodeError, UnicodeDecodeError):
            pass
        out.append(text)
    return out


def _load(path):
    """The matrices of a result file, checked: (mat, binTrans?, names)."""
    import scipy.io
    fname = os.fspath(path)
    if not os.path.isfile(fname):
        raise Acausal2dError("result file not found: %s" % fname)
    try:
        mat = scipy.io.loadmat(fname, chars_as_strings=False)
    except Exception as exc:          # scipy raises ValueError, TypeError, OSError ...
        raise Acausal2dError("%s is not a readable MAT file: %s" % (fname, exc)) from None
    missing = [k for k in ("Aclass", "name", "dataInfo", "data_2") if k not in mat]
    if missing:
        raise Acausal2dError("%s is not a Dymola result file: no %s matrix (a result file "
                             "has Aclass, name, description, dataInfo, data_1, data_2)"
                             % (fname, ", ".join(missing)))
    trans = "binTrans" in _strings(mat["Aclass"], by_column=False)
    return mat, trans, _strings(mat["name"], by_column=trans)


def read_mat(path):
    """``(time, columns)`` of the trajectories (``data_2``) of a Dymola or
    OpenModelica result file (binTrans or binNormal), signs of aliases
    applied; parameters (``data_1``) are left out.  Errors name the file
    and what is missing."""
    mat, trans, names = _load(path)
    info = mat["dataInfo"] if trans else mat["dataInfo"].T
    data = mat["data_2"] if trans else mat["data_2"].T
    time = np.asarray(data[0], dtype=float).copy()
    columns = {}
    for i, name in enumerate(names):
        block, col = int(info[0][i]), int(info[1][i])
        if block == 2 and abs(col) > 1:
            columns[name] = np.sign(col) * np.asarray(data[abs(col) - 1], dtype=float)
    return time, columns


def mat_units(path):
    """{name: unit} from the descriptions of a result file (Modelica's
    ``"text [unit]"`` or ``"[unit|display unit]"``); names without one are
    left out."""
    mat, trans, names = _load(path)
    if "description" not in mat:
        return {}
    units = {}
    for name, text in zip(names, _strings(mat["description"], by_column=trans)):
        match = re.search(r"\[([^\]|]*)(\|[^\]]*)?\]\s*$", text)
        if match and match.group(1).strip():
            units[name] = match.group(1).strip()
    return units
