/* ---------------------------------------------------------------------
   tribolmp MCA plugin: fix mca/state (see fix_mca_state.h)
------------------------------------------------------------------------- */

#include "fix_mca_state.h"
#include "mca_memory.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "pair_mca.h"
#include "utils.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixMCAState::FixMCAState(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), initialized(0), last_commit(-1.0), slots(nullptr), autom(nullptr),
    nmax_local(0)
{
  if (igroup != 0) error->all(FLERR, "fix mca/state: group must be 'all', got {}", arg[1]);
  // a close-packed automaton has 6 (2D) or 12 (3D) touching neighbours; the
  // margin covers stretched links and polydisperse packings
  maxpartner = (domain->dimension == 3) ? 20 : 12;
  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "maxpartner") == 0) {
      if (iarg + 2 > narg) error->all(FLERR, "fix mca/state: maxpartner needs a value");
      maxpartner = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (maxpartner < 1 || maxpartner > 200)
        error->all(FLERR, "fix mca/state: maxpartner: expected 1-200, got {}", maxpartner);
      iarg += 2;
    } else
      error->all(FLERR, "fix mca/state: unknown keyword {}", arg[iarg]);
  }
  restart_global = 1;
  restart_peratom = 1;
  peratom_flag = 1;
  size_peratom_cols = NOUT;
  peratom_freq = 1;
  create_attribute = 1;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

FixMCAState::~FixMCAState()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(slots);
  memory->destroy(autom);
}

int FixMCAState::setmask()
{
  return 0;
}

void FixMCAState::init() {}

/* global restart: initialisation flag, step of the last committed update, maxpartner */

void FixMCAState::write_restart(FILE *fp)
{
  // called on every rank, but only rank 0 holds the open file (fp is null elsewhere)
  if (comm->me != 0) return;
  double list[3] = {(double) initialized, last_commit, (double) maxpartner};
  int size = 3 * sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(list, sizeof(double), 3, fp);
}

void FixMCAState::restart(char *buf)
{
  auto *list = (double *) buf;
  initialized = static_cast<int>(list[0]);
  last_commit = list[1];
  const int mp = static_cast<int>(list[2]);
  if (mp != maxpartner)
    error->all(FLERR, "fix mca/state: maxpartner {} differs from the restart file's {}; "
               "declare 'fix mca_state all mca/state maxpartner {}' before the run",
               maxpartner, mp, mp);
}

/* pending mirror copies (see fix_mca_state.h) */

void FixMCAState::sync_mirrors()
{
  auto *pair = dynamic_cast<PairMCA *>(force->pair_match("mca", 1, 0));
  if (pair) pair->sync_mirrors();
}

/* per-atom arrays */

void FixMCAState::grow_arrays(int nmax)
{
  memory->grow(slots, nmax, maxpartner * NSLOT, "mca/state:slots");
  memory->grow(autom, nmax, NAUTO, "mca/state:autom");
  // the per-atom output is the first NOUT columns of the automaton rows (LAMMPS reads
  // array_atom[i][0..NOUT-1]): pair mca writes them in its stress update, no copy
  array_atom = autom;
  // (before the new rows are first written: see mca_memory.h)
  MCAMemory::hugepage_hint(slots[0], sizeof(double) * nmax * maxpartner * NSLOT);
  MCAMemory::hugepage_hint(autom[0], sizeof(double) * nmax * NAUTO);
  for (int i = nmax_local; i < nmax; i++) {
    memset(slots[i], 0, sizeof(double) * maxpartner * NSLOT);
    memset(autom[i], 0, sizeof(double) * NAUTO);
  }
  nmax_local = nmax;
}

void FixMCAState::copy_arrays(int i, int j, int /*delflag*/)
{
  sync_mirrors();
  memcpy(slots[j], slots[i], sizeof(double) * maxpartner * NSLOT);
  memcpy(autom[j], autom[i], sizeof(double) * NAUTO);
}

void FixMCAState::set_arrays(int i)
{
  memset(slots[i], 0, sizeof(double) * maxpartner * NSLOT);
  memset(autom[i], 0, sizeof(double) * NAUTO);
}

int FixMCAState::pack_exchange(int i, double *buf)
{
  sync_mirrors();
  const int ns = maxpartner * NSLOT;
  memcpy(buf, slots[i], sizeof(double) * ns);
  memcpy(buf + ns, autom[i], sizeof(double) * NAUTO);
  return ns + NAUTO;
}

int FixMCAState::unpack_exchange(int nlocal, double *buf)
{
  const int ns = maxpartner * NSLOT;
  memcpy(slots[nlocal], buf, sizeof(double) * ns);
  memcpy(autom[nlocal], buf + ns, sizeof(double) * NAUTO);
  return ns + NAUTO;
}

int FixMCAState::pack_restart(int i, double *buf)
{
  sync_mirrors();
  const int ns = maxpartner * NSLOT;
  buf[0] = ns + NAUTO + 2;
  buf[1] = RESTART_LAYOUT;
  memcpy(buf + 2, slots[i], sizeof(double) * ns);
  memcpy(buf + 2 + ns, autom[i], sizeof(double) * NAUTO);
  return ns + NAUTO + 2;
}

// position in the automaton row of today's layout of each value of the layout before
// 2026-12-06 (stress[6], eps_p[6], eps_eq, deps[6], X, n_links, n_cross, counters[4], von
// Mises stress, X used, force[3], torque[3])
static const int OLD_TO_NEW[FixMCAState::NAUTO] = {
    FixMCAState::A_SIG, FixMCAState::A_SIG + 1, FixMCAState::A_SIG + 2, FixMCAState::A_SIG + 3,
    FixMCAState::A_SIG + 4, FixMCAState::A_SIG + 5, FixMCAState::A_EPT, FixMCAState::A_EPT + 1,
    FixMCAState::A_EPT + 2, FixMCAState::A_EPT + 3, FixMCAState::A_EPT + 4, FixMCAState::A_EPT + 5,
    FixMCAState::A_EEQ, FixMCAState::A_DEP, FixMCAState::A_DEP + 1, FixMCAState::A_DEP + 2,
    FixMCAState::A_DEP + 3, FixMCAState::A_DEP + 4, FixMCAState::A_DEP + 5, FixMCAState::A_X,
    FixMCAState::A_NL, FixMCAState::A_NC, FixMCAState::A_CF, FixMCAState::A_CB, FixMCAState::A_LB,
    FixMCAState::A_WF, FixMCAState::A_SEQ, FixMCAState::A_XU, FixMCAState::A_F, FixMCAState::A_F + 1,
    FixMCAState::A_F + 2, FixMCAState::A_T, FixMCAState::A_T + 1, FixMCAState::A_T + 2};

void FixMCAState::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[nlocal][m]);
  const int n = static_cast<int>(extra[nlocal][m]);
  const int ns = maxpartner * NSLOT;
  const double *rec = &extra[nlocal][m];
  if (n == ns + NAUTO + 2 && static_cast<int>(rec[1]) == RESTART_LAYOUT) {
    memcpy(slots[nlocal], rec + 2, sizeof(double) * ns);
    memcpy(autom[nlocal], rec + 2 + ns, sizeof(double) * NAUTO);
  } else if (n == ns + NAUTO + 1) {
    // a file of a plugin before 2026-12-06: the same values, the automaton row in the old
    // order (a run continued from it is the run the old plugin would have continued)
    memcpy(slots[nlocal], rec + 1, sizeof(double) * ns);
    for (int k = 0; k < NAUTO; k++) autom[nlocal][OLD_TO_NEW[k]] = rec[1 + ns + k];
  } else
    error->one(FLERR, "fix mca/state: restart record of {} values, expected {}: the file was "
               "written with another maxpartner or by a plugin before 2026-12-02 (slots of {} "
               "values, now {}); rerun from the data file", n, ns + NAUTO + 2, (int) NSLOT + 2,
               (int) NSLOT);
}

int FixMCAState::size_restart(int /*i*/)
{
  return maxpartner * NSLOT + NAUTO + 2;
}

int FixMCAState::maxsize_restart()
{
  return maxpartner * NSLOT + NAUTO + 2;
}

double FixMCAState::memory_usage()
{
  return (double) nmax_local * (maxpartner * NSLOT + NAUTO) * sizeof(double);
}
