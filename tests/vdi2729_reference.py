"""Closed-form VDI 2729 position solutions of the linkage modules (seed
Anhang B: DDD B.42-B.50, DDS B.71-B.85, DSD B.119-B.125, drives, line
intersections for SSD/SDS), written in numpy as a code path independent of
library/linkage.py, for the tests."""
import math

import numpy as np


def e(a):
    return np.array([np.cos(a), np.sin(a)])


def n(a):
    return np.array([-np.sin(a), np.cos(a)])


def vdi_dan(P1, l, phi):
    """Drive module: P = P1 + l e(phi)."""
    return P1 + l * e(phi)


def vdi_ddd(P1, P2, l1, l2, K):
    """DDD: intersection of two circles, branch K (B.42-B.50)."""
    H1, H2 = P2 - P1
    H3 = H1 * H1 + H2 * H2
    H4 = l1 * l1 - l2 * l2 + H3
    H5 = K * math.sqrt(4 * H3 * l1 * l1 - H4 * H4)
    H6 = (H1 * H4 - H2 * H5) / (2 * H3)
    H7 = (H2 * H4 + H1 * H5) / (2 * H3)
    return P1 + np.array([H6, H7])


def vdi_dds(P1, P2, phiU, l, v, K):
    """DDS: point on the offset guide line at distance l from P1 (B.71-B.85)."""
    H4, H5 = math.cos(phiU), math.sin(phiU)
    H6, H7 = P2 - P1
    H8 = H4 * H7 - H5 * H6 + v
    H9 = H6 * H6 + H7 * H7 + v * v - l * l + 2 * v * (H8 - v)
    H10 = H4 * H6 + H5 * H7
    H11 = K * math.sqrt(H10 * H10 - H9) - H10
    return P2 + np.array([H4 * H11 - H5 * v, H5 * H11 + H4 * v]), H11


def vdi_dsd(P1, P2, v):
    """DSD: guide through P1 with P2 at offset v (B.119-B.125), travel > 0."""
    d = P2 - P1
    H3 = d @ d
    H4 = math.sqrt(H3 - v * v)
    ex = (d[0] * H4 + v * d[1]) / H3
    ey = (d[1] * H4 - v * d[0]) / H3
    return math.atan2(ey, ex), H4


def line_intersection(A, u, B, w):
    """Parameters (s, t) with A + s u = B + t w."""
    M = np.column_stack([u, -w])
    return np.linalg.solve(M, B - A)


def wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi
