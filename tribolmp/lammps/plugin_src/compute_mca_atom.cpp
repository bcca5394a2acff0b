/* ---------------------------------------------------------------------
   tribolmp MCA plugin: compute mca/atom (see compute_mca_atom.h)
------------------------------------------------------------------------- */

#include "compute_mca_atom.h"

#include "atom.h"
#include "error.h"
#include "fix_mca_state.h"
#include "memory.h"
#include "modify.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;

static const char *names[FixMCAState::NOUT] = {"sxx",   "syy",   "szz",         "sxy", "sxz",
                                              "syz",   "eps_p", "links", "cross_links", "seq"};

ComputeMCAAtom::ComputeMCAAtom(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), column(-1), nmax(0), vec(nullptr)
{
  if (narg != 4) error->all(FLERR, "compute mca/atom: expected one column name, got {} words", narg - 3);
  for (int k = 0; k < FixMCAState::NOUT; k++)
    if (strcmp(arg[3], names[k]) == 0) column = k;
  if (column < 0)
    error->all(FLERR, "compute mca/atom: column: expected sxx|syy|szz|sxy|sxz|syz|eps_p|links|"
               "cross_links|seq, got {}", arg[3]);
  peratom_flag = 1;
  size_peratom_cols = 0;
}

ComputeMCAAtom::~ComputeMCAAtom()
{
  memory->destroy(vec);
}

void ComputeMCAAtom::init()
{
  if (!dynamic_cast<FixMCAState *>(modify->get_fix_by_id("mca_state")))
    error->all(FLERR, "compute mca/atom: needs pair_style mca (its fix mca_state)");
}

void ComputeMCAAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  if (atom->nmax > nmax) {
    memory->destroy(vec);
    nmax = atom->nmax;
    memory->create(vec, nmax, "mca/atom:vec");
    vector_atom = vec;
  }
  auto *fix = dynamic_cast<FixMCAState *>(modify->get_fix_by_id("mca_state"));
  int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    vec[i] = (fix && (mask[i] & groupbit)) ? fix->autom[i][column] : 0.0;
}

double ComputeMCAAtom::memory_usage()
{
  return (double) nmax * sizeof(double);
}
