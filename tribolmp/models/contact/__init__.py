"""Contact mechanics (being written)."""
from .mdr import TangentialMDR, axisymmetric_profile, normal_force
