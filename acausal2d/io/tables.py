"""Reading result and reference tables: our CSV files (first column
``time``, dotted names) and Modelica/Dymola CSV files (quoted headers,
``Time``, ``;`` or tab delimiters, duplicated event rows), with errors that
name the file, the line and the column.
"""
import csv
import difflib
import io
import os

import numpy as np

from ..errors import Acausal2dError

CELL_LIMIT = 1 << 26
"""Largest cell (e.g. a header name) read from a CSV file, in characters."""


def _detect_delimiter(line):
    for d in (",", ";", "\t"):
        if d in line:
            return d
    return ","


def _find_time_column(names):
    for wanted in ("time", "Time"):
        if wanted in names:
            return names.index(wanted)
    for i, n in enumerate(names):
        if n.lower() == "time":
            return i
    return None


def _few(names, near=None, n=8):
    """A short, readable list of ``names`` (closest matches to ``near`` first)."""
    names = list(names)
    if not names:
        return "(none)"
    chosen = []
    if near is not None:
        chosen = difflib.get_close_matches(near, names, n=n, cutoff=0.5)
    for name in names:
        if len(chosen) >= n:
            break
        if name not in chosen:
            chosen.append(name)
    text = ", ".join(chosen)
    if len(names) > len(chosen):
        text += ", ... (%d in all)" % len(names)
    return text


def read_csv(path):
    """Read a result CSV file.

    Accepts our result files (first column ``time``, other columns named by
    dotted variable names) and Modelica/Dymola-style files (quoted headers,
    time column ``Time`` or ``time``, rows repeated at events and at the
    end).  Blank lines are skipped; the delimiter may be ``,``, ``;`` or a
    tab.

    Returns ``(time, columns)``: ``time`` is a 1-D float array (non-decreasing;
    repeated values are kept, they mark events) and ``columns`` maps every
    other column name to a float array of the same length.

    Raises :class:`~acausal2d.errors.Acausal2dError` if the file is missing,
    has no time column, contains a cell that is not a number or is NaN or
    infinite (the message gives the signal and the line), or its time
    decreases.
    """
    fname = os.fspath(path)
    if not os.path.isfile(fname):
        raise Acausal2dError("CSV file not found: %s" % fname)
    try:
        with open(fname, newline="", encoding="utf-8-sig") as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise Acausal2dError("cannot read CSV file %s: %s" % (fname, e)) from None

    first = next((ln for ln in text.splitlines() if ln.strip()), None)
    if first is None:
        raise Acausal2dError("CSV file %s is empty" % fname)
    try:
        return _parse_rows(fname, text, first)
    except csv.Error as exc:
        raise Acausal2dError("%s is not a readable CSV file: %s" % (fname, exc)) from None


def _parse_rows(fname, text, first):
    """(time, columns) of the text of a CSV file (see :func:`read_csv`)."""
    if csv.field_size_limit() < CELL_LIMIT:
        csv.field_size_limit(CELL_LIMIT)
    reader = csv.reader(io.StringIO(text), delimiter=_detect_delimiter(first))
    header, rows, lines = _split_rows(fname, reader)
    itime = _find_time_column(header)
    if itime is None:
        raise Acausal2dError("%s has no time column (expected a column named 'time' or "
                             "'Time'); the header has: %s" % (fname, _few(header)))
    if not rows:
        raise Acausal2dError("%s has a header but no data rows" % fname)
    data = _numbers(fname, header, rows, lines)
    t = data[:, itime].copy()
    _check_time(t, "%s" % fname, lines)
    columns = {name: data[:, i].copy() for i, name in enumerate(header) if i != itime}
    check_finite(columns, t, fname, lines)
    return t, columns


def check_finite(columns, t, what, lines=None):
    """Refuse a NaN or infinite value: the error names ``what`` (the file),
    the signal, the row (the file's line when ``lines`` is given) and its
    time.  A comparison against a NaN says nothing, so it is an input
    error, not a failed signal."""
    for name, v in columns.items():
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            i = bad[0]
            where = "line %d" % lines[i] if lines is not None else "row %d" % (i + 1)
            raise Acausal2dError("%s: signal %r is %s at %s (time %.10g)%s; a comparison needs "
                                 "finite numbers" % (what, name, v[i], where, t[i],
                                                     "" if bad.size == 1 else
                                                     " and at %d more rows" % (bad.size - 1)))


def _split_rows(fname, reader):
    """(header, data rows, their line numbers); blank rows skipped, trailing
    empty cells dropped, the cell count of every row checked."""
    header, rows, lines = None, [], []
    for row in reader:
        if not any(c.strip() for c in row):
            continue
        if header is None:
            header = _header(fname, row, reader.line_num)
            continue
        ncol = len(header)
        if len(row) > ncol and not any(c.strip() for c in row[ncol:]):
            row = row[:ncol]
        if len(row) != ncol:
            raise Acausal2dError("%s, line %d: %d cells, but the header has %d columns"
                                 % (fname, reader.line_num, len(row), ncol))
        rows.append(row)
        lines.append(reader.line_num)
    return header or [], rows, lines


def _header(fname, row, line):
    """Column names of a header row: each named, none twice."""
    header = [c.strip() for c in row]
    while header and header[-1] == "":      # trailing delimiter
        header.pop()
    seen = set()
    for i, name in enumerate(header):
        if name == "":
            raise Acausal2dError("%s, line %d: column %d of the header has no name"
                                 % (fname, line, i + 1))
        if name in seen:
            raise Acausal2dError("%s, line %d: column %r appears twice in the header"
                                 % (fname, line, name))
        seen.add(name)
    return header


def _numbers(fname, header, rows, lines):
    """The data rows as a float array; the first cell that is not a number
    is named by line and column."""
    try:
        return np.array(rows, dtype=float)
    except ValueError:
        pass
    for row, line in zip(rows, lines):
        for c, cell in enumerate(row):
            try:
                float(cell)
            except ValueError:
                raise Acausal2dError("%s, line %d, column %r: cannot read %r as a number"
                                     % (fname, line, header[c], cell)) from None
    raise Acausal2dError("%s: the data rows cannot be read as numbers" % fname)


def _check_time(t, what, lines=None):
    def where(i):
        return "line %d" % lines[i] if lines is not None else "row %d" % (i + 1)

    bad = np.flatnonzero(~np.isfinite(t))
    if bad.size:
        raise Acausal2dError("%s: time is not a finite number at %s" % (what, where(bad[0])))
    dec = np.flatnonzero(np.diff(t) < 0)
    if dec.size:
        i = dec[0] + 1
        raise Acausal2dError("%s: time is not monotonic; it goes back from %.10g to %.10g at %s"
                             % (what, t[i - 1], t[i], where(i)))
