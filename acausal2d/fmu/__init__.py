"""FMI 2.0 FMU export (Model Exchange and Co-Simulation) of acausal2d
models as native code: :func:`export_fmu`; :func:`bind_inputs` turns a
model's top-level ``RealInput`` connectors into inputs."""
from .export import DynamicStateSelectionError, export_fmu
from ..library.inputs import bind_inputs

__all__ = ["export_fmu", "bind_inputs", "DynamicStateSelectionError"]
