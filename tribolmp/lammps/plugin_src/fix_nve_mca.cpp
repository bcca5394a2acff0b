/* ---------------------------------------------------------------------
   tribolmp MCA plugin: fix nve/mca (see fix_nve_mca.h)
------------------------------------------------------------------------- */

#include "fix_nve_mca.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixNVEMCA::FixNVEMCA(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg), inertia(0.4)
{
  time_integrate = 1;
  dynamic_group_allow = 1;
  for (int iarg = 3; iarg < narg; iarg++) {
    if (strcmp(arg[iarg], "disc") == 0) {
      if (domain->dimension != 2)
        error->all(FLERR, "fix nve/mca: disc: expected a 2d simulation, got dimension {}",
                   domain->dimension);
      inertia = 0.5;
    } else
      error->all(FLERR, "fix nve/mca: expected no keyword or 'disc', got {}", arg[iarg]);
  }
  if (!atom->radius_flag || !atom->omega_flag || !atom->torque_flag || !atom->rmass_flag)
    error->all(FLERR, "fix nve/mca: needs per-atom radius, omega, torque and mass "
               "(atom_style sphere or bpm/sphere)");
}

int FixNVEMCA::setmask()
{
  return INITIAL_INTEGRATE | FINAL_INTEGRATE;
}

void FixNVEMCA::init()
{
  dtv = update->dt;
  dtf = 0.5 * update->dt * force->ftm2v;
  double *radius = atom->radius;
  int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if ((mask[i] & groupbit) && radius[i] == 0.0)
      error->one(FLERR, "fix nve/mca: atom {} has zero radius, expected finite-size spheres",
                 atom->tag[i]);
}

void FixNVEMCA::reset_dt()
{
  dtv = update->dt;
  dtf = 0.5 * update->dt * force->ftm2v;
}

// (the inverse moment of inertia is formed as dtf / (inertia * (r^2 m)), not as
// (dtf / inertia) / (r^2 m): the operations of nve/bpm/sphere, so that a run with this fix
// reproduces one with nve/bpm/sphere bit for bit)

// half a step of velocity and angular velocity from force and torque (the two half-kicks of
// velocity Verlet); move: also the drift of the position with the new velocity
template <bool MOVE> void FixNVEMCA::kick()
{
  double **x = atom->x, **v = atom->v, **f = atom->f;
  double **omega = atom->omega, **torque = atom->torque;
  double *radius = atom->radius, *rmass = atom->rmass;
  int *mask = atom->mask;
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double dtfm = dtf / rmass[i];
    double *vi = v[i], *fi = f[i], *wi = omega[i], *ti = torque[i];
    vi[0] += dtfm * fi[0];
    vi[1] += dtfm * fi[1];
    vi[2] += dtfm * fi[2];
    if (MOVE) {
      double *xi = x[i];
      xi[0] += dtv * vi[0];
      xi[1] += dtv * vi[1];
      xi[2] += dtv * vi[2];
    }
    const double dtirotate = dtf / (inertia * (radius[i] * radius[i] * rmass[i]));
    wi[0] += dtirotate * ti[0];
    wi[1] += dtirotate * ti[1];
    wi[2] += dtirotate * ti[2];
  }
}

void FixNVEMCA::initial_integrate(int /*vflag*/)
{
  kick<true>();
}

void FixNVEMCA::final_integrate()
{
  kick<false>();
}
