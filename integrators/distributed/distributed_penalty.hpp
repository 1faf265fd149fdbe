#pragma once
// The penalty ODE of a scene of neighbour-coupled bodies (NeighbourDynamics) distributed over the
// ranks of an MPI communicator: each rank holds a contiguous block of bodies in SUNDIALS' parallel
// vector (N_VNew_Parallel), CVODE BDF with GMRES preconditioned by the band-block-diagonal
// preconditioner (CVBBDPRE, each rank's block from difference quotients of its local function),
// and the state of the bodies on a block's boundary exchanged with the neighbouring ranks before
// every right-hand side. The contact switches are not located (the modes follow the state).
#include "contact_ode/integrators/integrator.hpp"
#include "contact_ode/integrators/run_recorder.hpp"
#include "contact_ode/integrators/run_result.hpp"
#include "contact_ode/models/mechanical_system.hpp"
#include "contact_ode/models/neighbour_dynamics.hpp"

#include <mpi.h>

#include <functional>

namespace contact {

struct DistributedOptions {
  IntegratorOptions integrator;  // rtol, atol, max_steps (CVODE BDF; max_steps for the whole run)
  int krylov_dim = 30;           // GMRES's Krylov space (5 fails to converge on the chain)
  // Called on every rank every few steps (empty: never), e.g. to show progress. At the same steps
  // the ranks agree on the stop request (request_stop, a program's SIGINT): any one's ends the run
  // on every rank as Status::Interrupted, at the same step, so that no rank waits in MPI for ranks
  // that stopped.
  std::function<void(double t)> progress;
};

// Every rank calls it. Rank 0's result holds the samples (the whole state gathered) with their
// energies from scene.energy(); every rank's holds the same statistics and status.
RunResult run_distributed(const Dynamics& scene, const NeighbourDynamics& parts,
                          const DistributedOptions& options, const SolveOptions& span, MPI_Comm comm);

// The bodies rank r of `size` holds: [first, first + count), as even as possible.
std::pair<std::size_t, std::size_t> block_of(std::size_t bodies, int rank, int size);

}  // namespace contact
