"""The run's output-row store (acausal2d.runtime.rows.OutputRows): blocks in,
the same points out as the list of (t, z) pairs it replaced."""
import numpy as np
import pytest

from acausal2d.runtime.rows import OutputRows
from conftest import assert_copied


def _filled():
    rows = OutputRows(2)
    rows.append((0.0, [1.0, 2.0]))
    rows.add_block(np.array([0.1, 0.2, 0.3]), np.array([[3.0, 4.0], [5.0, 6.0], [7.0, 8.0]]))
    rows.extend([(0.4, np.array([9.0, 10.0])), (0.5, np.array([11.0, 12.0]))])
    rows.append((0.6, np.array([13.0, 14.0])))
    return rows


def test_points_come_back_in_order_as_pairs():
    rows = _filled()
    assert len(rows) == 7 and rows
    for k, t, z in ((0, 0.0, [1.0, 2.0]), (2, 0.2, [5.0, 6.0]), (-1, 0.6, [13.0, 14.0])):
        assert_copied(rows[k][0], t)
        assert_copied(rows[k][1], z)
    assert_copied([t for t, _ in rows[3:6]], [0.3, 0.4, 0.5])
    T, Z = rows.arrays()
    assert_copied(T, [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
    assert_copied(Z[:, 0], [1.0, 3.0, 5.0, 7.0, 9.0, 11.0, 13.0])
    with pytest.raises(IndexError):
        rows[7]


def test_append_copies_the_row():
    rows, z = OutputRows(2), np.array([1.0, 2.0])
    rows.append((0.0, z))
    z[0] = 99.0
    assert_copied(rows[0][1][0], 1.0)


@pytest.mark.parametrize("n", [0, 1, 2, 3, 4, 6, 7, 9])
def test_truncate_keeps_the_first_points(n):
    rows = _filled()
    rows.truncate(n)
    assert len(rows) == min(n, 7)
    T, Z = rows.arrays()
    assert_copied(T, [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6][:n])
    assert Z.shape == (min(n, 7), 2)
    rows.append((1.0, [0.0, 0.0]))                  # still appendable after a cut
    assert_copied(rows[-1][0], 1.0)
    assert len(rows) == min(n, 7) + 1


def test_keep_until_drops_the_later_points_of_a_segment():
    rows = _filled()
    rows.keep_until(0.25, start=1)
    assert_copied([t for t, _ in rows[:]], [0.0, 0.1, 0.2])
    rows.keep_until(-1.0, start=3)                  # nothing after the start: unchanged
    assert len(rows) == 3


def test_empty_store():
    rows = OutputRows(3)
    assert not rows and len(rows) == 0
    T, Z = rows.arrays()
    assert T.shape == (0,) and Z.shape == (0, 3)
