"""Shared pieces of the planar elements: rotations between a frame and the
world (Ebert 2015, Anhang A.1), the gravity field :class:`PlanarWorld`, and the
connection queries used for drawing and topology.
"""
import casadi as ca

from acausal2d import Component, Parameter
from acausal2d.language.unionfind import connector_sets


def rotate(phi, vx, vy):
    """World components of the vector (vx, vy) given in a frame turned by
    ``phi``: R(phi) (vx, vy), R the 2x2 rotation (Ebert 2015, Anhang A.1)."""
    c, s = ca.cos(phi), ca.sin(phi)
    return c * vx - s * vy, s * vx + c * vy


def resolve(phi, vx, vy):
    """Components of the world vector (vx, vy) along the axes of a frame
    turned by ``phi``: R(phi)^T (vx, vy)."""
    c, s = ca.cos(phi), ca.sin(phi)
    return c * vx + s * vy, -s * vx + c * vy


class PlanarWorld(Component):
    """Gravity field for all bodies of the model (default {0, -9.81} m/s²).

    Place one in a model to change gravity; a model without one gets the
    default automatically (elements that need it declare
    ``world = Outer(PlanarWorld)``)."""
    g = Parameter((0.0, -9.81), "m/s2", "gravity acceleration, world frame")


# --------------------------------------------------------------------------
# connection queries for drawing and topology (shared with library/belt.py)
# --------------------------------------------------------------------------


def is_connected(conn):
    """True if the connector ``conn`` appears in a connect statement of its
    model (see :func:`acausal2d.language.unionfind.connector_sets`)."""
    _, connected = connector_sets(conn.owner.root)
    return id(conn) in connected

