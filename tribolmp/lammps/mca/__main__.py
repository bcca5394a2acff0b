"""``python -m tribolmp.lammps.mca OUT [--restart FILE --restart-step N]`` (one MPI rank)."""

import sys

from .mpi import main

sys.exit(main())
